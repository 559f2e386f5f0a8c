//! The command line on the surfaces' own inputs, run as a user would: height maps, `stpn` tags
//! files, Loop's valence limit and the three-crease triangles `stpn` splits; each error one
//! sentence naming the file (and line) and what is wrong.

mod common;

use common::cli::*;

/// The height map: a grayscale PNG (or the generated default) on a mesh with texture
/// coordinates renders and exports; without coordinates, with a missing, non-PNG or colour image,
/// or with `--heightmap` for another displacement, one sentence and exit 1.
#[test]
fn heightmap_displacement_and_its_errors() {
    let grid = model_path("grid_uv_8x8.obj");
    // 4 x 2, 8-bit grayscale.
    let png = gray_png("hm.png", 4, 2, &[0, 64, 128, 255, 255, 128, 64, 0]);
    let out_png = tmp("hm-render.png");
    for extra in [vec![], vec!["--heightmap", p(&png), "--bias", "0.5"]] {
        let mut args = vec![
            "render",
            p(&grid),
            "-o",
            p(&out_png),
            "--width",
            "96",
            "--height",
            "64",
            "--level",
            "8",
            "--displace",
            "heightmap",
        ];
        args.extend(extra);
        expect_success(&args);
    }
    let obj = tmp("hm.obj");
    let mesh = export_and_reload(&obj, &[p(&grid), "--level", "4", "--displace", "heightmap"]);
    // Watertight: 81 + 208 edges x 3 + 128 x 3 distinct vertices.
    assert_eq!(mesh.stats().vertices, 81 + 208 * 3 + 128 * 3);

    let o = p(&out_png);
    expect_error(
        &[
            "render",
            p(&model_path("icosahedron.obj")),
            "-o",
            o,
            "--displace",
            "heightmap",
        ],
        &["icosahedron.obj", "no texture coordinates"],
    );
    // Texture coordinates on some faces only: the count is named, for render and info.
    let partial = write(
        "partial-vt.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2 4 3\n",
    );
    let partly = "the mesh has texture coordinates (vt) on 1 of its 2 faces, not on every one: the heightmap displacement reads the map on every face";
    expect_error(
        &["render", p(&partial), "-o", o, "--displace", "heightmap"],
        &["partial-vt.obj", partly],
    );
    expect_error(
        &[
            "info",
            p(&partial),
            "--displace",
            "heightmap",
            "--pixel-error",
            "1",
        ],
        &["partial-vt.obj", partly],
    );
    // info refuses before it prints the mesh's statistics, as for its other inputs.
    for mesh in [p(&partial), p(&model_path("icosahedron.obj"))] {
        let args = [
            "info",
            mesh,
            "--displace",
            "heightmap",
            "--pixel-error",
            "1",
        ];
        let out = meshrefine(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?} printed before refusing");
    }
    let text = write("not-a.png", b"hello");
    let hm = ["--displace", "heightmap", "--heightmap"];
    for (extra, needle) in [
        (
            vec![hm[0], hm[1], hm[2], "nope.png"],
            "cannot read height map 'nope.png'",
        ),
        (
            vec![hm[0], hm[1], hm[2], p(&text)],
            "is not a readable PNG image",
        ),
        (
            vec![hm[0], hm[1], "--bias", "nan"],
            "--bias nan is not a finite number",
        ),
    ] {
        let mut args = vec!["render", p(&grid), "-o", o];
        args.extend(extra);
        expect_error(&args, &[needle]);
    }
    // info refuses a map it cannot read before printing anything, as render refuses it before
    // drawing.
    #[rustfmt::skip]
    let out = meshrefine(&["info", p(&grid), "--pixel-error", "1", "--displace", "heightmap",
        "--heightmap", p(&text)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(stderr.contains("is not a readable PNG image"), "{stderr}");
}

/// Scalar-tagged PN: renders with tags derived from hard edges or from a tags file; bad tag
/// files, broken restrictions and `--tags` with another surface are one sentence and exit 1.
#[test]
fn stpn_tags_render_and_their_errors() {
    let cyl = model_path("cylinder_hard_normals.obj");
    let png = tmp("stpn.png");
    let o = p(&png);
    let size = ["--width", "96", "--height", "64", "--level", "6"];
    let mut args = vec!["render", p(&cyl), "-o", o, "--surface", "stpn"];
    args.extend(size);
    expect_success(&args);
    // Creases from dihedral angles: the cube's edges (90°) with a 60° crease angle; its
    // corners, where three creases meet, stay smooth with a warning.
    let cube = model_path("cube_tri.obj");
    let out = meshrefine(&[
        "render",
        p(&cube),
        "-o",
        o,
        "--surface",
        "stpn",
        "--crease-angle",
        "60",
        "--level",
        "4",
        "--width",
        "64",
        "--height",
        "64",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("8 vertices where three or more hard edges meet"),
        "{stderr}"
    );
    // A tags file on the tetrahedron: tension at its first vertex.
    let tet = model_path("tetrahedron.obj");
    let mesh = meshrefine::mesh::Mesh::load_obj(&tet).unwrap().0;
    let v = mesh.positions[0];
    let good = write(
        "good.tags",
        format!("# tension\nt {} {} {} 0.6\n", v.x, v.y, v.z).as_bytes(),
    );
    let mut args = vec![
        "render",
        p(&tet),
        "-o",
        o,
        "--surface",
        "stpn",
        "--tags",
        p(&good),
    ];
    args.extend(size);
    expect_success(&args);
    let bad = write("bad.tags", b"t 1 2\n");
    let three: String = mesh
        .positions
        .iter()
        .map(|q| format!("t {} {} {} 0 1 0 1 0 0\n", q.x, q.y, q.z))
        .collect();
    let three = write("three.tags", three.as_bytes());
    for (extra, needle) in [
        (
            vec!["--surface", "stpn", "--tags", p(&bad)],
            "bad.tags' line 1: 2 numbers",
        ),
        (
            vec!["--surface", "stpn", "--tags", p(&three)],
            "three crease vertices",
        ),
        (
            vec!["--surface", "stpn", "--tags", "missing.tags"],
            "cannot read tags file 'missing.tags'",
        ),
    ] {
        let mut args = vec!["render", p(&tet), "-o", o];
        args.extend(extra);
        expect_error(&args, &[needle]);
    }
}

/// A vertex of absurd valence under `--surface loop` is refused before anything is built: one
/// sentence naming the file, the vertex and the limit, exit 1 (a bicone of 40,000 triangles
/// whose poles have valence 20,000: about 8 · 10^8 control points).
#[test]
fn an_absurd_valence_is_refused_naming_the_limit() {
    let n = 20_000u32;
    let mut text = String::from("v 0 0 1\nv 0 0 -1\n");
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        text += &format!("v {} {} 0\n", a.cos(), a.sin());
    }
    for i in 0..n {
        let (a, b) = (3 + i, 3 + (i + 1) % n);
        text += &format!("f 1 {a} {b}\nf 2 {b} {a}\n");
    }
    let path = write("loop_absurd.obj", text.as_bytes());
    let out = tmp("loop_absurd_out.obj");
    let want = [
        "loop_absurd.obj",
        "vertex 1 has 20000 neighbours",
        "past the limit of 33554432 control points (128 MiB)",
    ];
    expect_error(&["info", p(&path), "--surface", "loop"], &want);
    expect_error(
        &["export", p(&path), "-o", p(&out), "--surface", "loop"],
        &want,
    );
}

/// Tags files: numbers are counted without a trailing comment; overflowing sharpness, a zero
/// crease direction and a second line for a vertex are each `file line N:` errors.
#[test]
fn tags_file_errors_name_the_line() {
    let tet = model_path("tetrahedron.obj");
    let mesh = meshrefine::mesh::Mesh::load_obj(&tet).unwrap().0;
    let v = mesh.positions[0];
    let at = format!("t {} {} {}", v.x, v.y, v.z);
    let png = tmp("tags-errors.png");
    let good = write(
        "commented.tags",
        format!("{at} 0.5 1 0 1 0 0 # a crease\n").as_bytes(),
    );
    expect_success(&[
        "render",
        p(&tet),
        "-o",
        p(&png),
        "--surface",
        "stpn",
        "--tags",
        p(&good),
        "--width",
        "32",
        "--height",
        "32",
        "--level",
        "2",
    ]);
    for (name, text, needle) in [
        (
            "sharp.tags",
            format!("{at} 0 1e20 0 1 0 0\n"),
            "sharp.tags' line 1: sharpness 1e20 is not within [0, 1e6]",
        ),
        (
            "zero.tags",
            format!("# c\n{at} 0 1 0 0 0 0\n"),
            "zero.tags' line 2: crease direction (0, 0, 0) is zero",
        ),
        (
            "twice.tags",
            format!("{at} 0.5\n{at} 0 1 0 1 0 0\n"),
            "twice.tags' line 2: the vertex at",
        ),
        // Not text: named with its line, as OBJ files are.
        (
            "nul.tags",
            format!("{at} 0.5\n\0\0"),
            "nul.tags' line 2: contains a NUL byte, so this is binary data, not a tags file",
        ),
        (
            "latin1.tags",
            format!("{at} 0.5\n# caf\u{e9}\n"),
            "latin1.tags' line 2: is not UTF-8 text",
        ),
        (
            "utf16.tags",
            "\u{fffe}".to_string(),
            "utf16.tags' line 1: is UTF-16 text (it starts with a UTF-16 byte-order mark): save it as UTF-8",
        ),
        // A long word is quoted short; control characters are escaped, never written raw.
        (
            "long.tags",
            format!("{at} {}\n", "9".repeat(100_000) + "x"),
            "long.tags' line 1: '9999999999999999999999999999999999999999… (100001 characters)' is not a finite number",
        ),
        (
            "escape.tags",
            format!("{at} 0.5\n\u{1b}[31mRED\n"),
            "escape.tags' line 2: '\\u{1b}[31mRED' is not a tag line",
        ),
    ] {
        let mut bytes = text.into_bytes();
        if name == "utf16.tags" {
            // A UTF-16 (little-endian) byte-order mark, then "t" in UTF-16.
            bytes = vec![0xff, 0xfe, b't', 0];
        }
        if name == "latin1.tags" {
            // The é as Latin-1's one byte, not UTF-8's two.
            let at = bytes.windows(2).position(|w| w == "é".as_bytes()).unwrap();
            bytes.splice(at..at + 2, [0xe9]);
        }
        let path = write(name, &bytes);
        expect_error(
            &[
                "render",
                p(&tet),
                "-o",
                p(&png),
                "--surface",
                "stpn",
                "--tags",
                p(&path),
            ],
            &[needle],
        );
    }
    // A tags file of comments alone tags nothing: said once.
    let empty = write("empty.tags", b"# nothing yet\n\n");
    #[rustfmt::skip]
    let w = warnings_of(&[
        "render", p(&tet), "-o", p(&png), "--surface", "stpn", "--tags", p(&empty), "--width",
        "32", "--height", "32", "--level", "2",
    ]);
    assert_eq!(
        w,
        [format!("warning: tags file '{}' tags no vertex (no line but comments): every vertex keeps its derived tags", p(&empty))]
    );
    // A file with nothing in it is said to be empty.
    let nothing = write("nothing.tags", b"");
    #[rustfmt::skip]
    let w = warnings_of(&[
        "render", p(&tet), "-o", p(&png), "--surface", "stpn", "--tags", p(&nothing), "--width",
        "32", "--height", "32", "--level", "2",
    ]);
    assert_eq!(
        w,
        [format!("warning: tags file '{}' tags no vertex (it is empty): every vertex keeps its derived tags", p(&nothing))]
    );
    // The whole sentence stays one short line.
    let long = write(
        "long-coordinate.obj",
        format!("v 0 0 {}x\n", "9".repeat(1 << 20)).as_bytes(),
    );
    let out = meshrefine(&["info", p(&long)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.len() < 300 && stderr.lines().count() == 1,
        "{stderr:.400}"
    );
}

/// Derived creases that break scalar-tagged PN's restriction (three crease corners) split
/// those triangles, with a warning naming the file, the first face's line and the option, and
/// the export stays closed; a tags file that breaks it is an error naming the mesh's face line
/// and the tags file. Height-map errors are words, not Rust's debug text.
#[test]
fn stpn_and_heightmap_errors_name_the_cause() {
    let spot = model_path("spot_control_tri.obj");
    let png = tmp("cause.png");
    let obj = tmp("spot-creases.obj");
    let out = meshrefine(&[
        "export",
        p(&spot),
        "-o",
        p(&obj),
        "--surface",
        "stpn",
        "--crease-angle",
        "30",
        "--level",
        "4",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("spot_control_tri.obj': split 2 triangle(s) at their centroids")
            && stderr.contains("from --crease-angle 30")
            && stderr.contains("the first: the face at line 214)"),
        "{stderr}"
    );
    let (mesh, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
    // 372 triangles, two of them split in three: 376 elements of 16 triangles; closed.
    assert_eq!(mesh.triangles.len(), 376 * 16);
    assert_eq!(mesh.stats().boundary_edges, 0, "the split opened a crack");
    let tet = model_path("tetrahedron.obj");
    let all: String = meshrefine::mesh::Mesh::load_obj(&tet)
        .unwrap()
        .0
        .positions
        .iter()
        .map(|q| format!("t {} {} {} 0 1 0 1 0 0\n", q.x, q.y, q.z))
        .collect();
    let three = write("all-creases.tags", all.as_bytes());
    expect_error(
        &[
            "render",
            p(&tet),
            "-o",
            p(&png),
            "--surface",
            "stpn",
            "--tags",
            p(&three),
        ],
        &[
            "tetrahedron.obj': the face at line ",
            "has three crease vertices",
            "(the creases come from tags file '",
        ],
    );
    let indexed = tmp("indexed.png");
    {
        let mut e = png::Encoder::new(std::fs::File::create(&indexed).unwrap(), 2, 1);
        e.set_color(png::ColorType::Indexed);
        e.set_depth(png::BitDepth::Eight);
        e.set_palette(vec![0u8; 6]);
        e.write_header().unwrap().write_image_data(&[0, 1]).unwrap();
    }
    let grid = model_path("grid_uv_8x8.obj");
    let args = [
        "render",
        p(&grid),
        "-o",
        p(&png),
        "--displace",
        "heightmap",
        "--heightmap",
        p(&indexed),
    ];
    expect_error(
        &args,
        &["indexed.png' is a palette (indexed colour) PNG image"],
    );
    let out = meshrefine(&args);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("Indexed"));
}

/// A triangle whose three corners carry creases derived from split normals (two `vn` at each)
/// is split the same way by every command that draws stpn, `bench` included, whose scene
/// would otherwise refuse it without naming the file.
#[test]
fn derived_three_crease_triangles_are_split_for_bench_too() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 -1 -1\nv 2 -1 -1\nv -1 2 -1\nvn 0 0 1\nvn 0 1 0\n\
                f 1//1 2//1 3//1\nf 1//2 4//2 2//2\nf 2//2 5//2 3//2\nf 3//2 6//2 1//2\n";
    let obj = write("three-creases.obj", text.as_bytes());
    let png = tmp("three-creases.png");
    let split = "three-creases.obj': split 1 triangle(s) at their centroids, whose three corners are crease vertices (from the mesh's split normals; scalar-tagged PN triangles allow two; the first: the face at line 9)";
    let w = warnings_of(&[
        "render",
        p(&obj),
        "-o",
        p(&png),
        "--surface",
        "stpn",
        "--level",
        "2",
        "--width",
        "32",
        "--height",
        "32",
    ]);
    assert!(w.len() == 1 && w[0].ends_with(split), "{w:#?}");
    let prefix = tmp("three-creases-bench");
    let w = warnings_of(&[
        "bench",
        p(&obj),
        "--surfaces",
        "flat,stpn",
        "--levels",
        "1",
        "--frames",
        "1",
        "--drivers",
        "static",
        "--width",
        "32",
        "--height",
        "32",
        "--out",
        p(&prefix),
    ]);
    assert!(w.len() == 1 && w[0].ends_with(split), "{w:#?}");
    // Both surfaces timed on the split mesh: 4 triangles, one of them in three.
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{csv}");
    assert!(
        // mesh, coarse triangles, elements, after the quoted device (which holds commas).
        rows.iter().all(|r| r.contains("\",three-creases,6,6,1,")),
        "{csv}"
    );
}

/// A height map whose level 0 alone (5800² f32 texels, 134.6 MB) is more than a storage buffer
/// may span (maxStorageBufferRange, 128 MiB on lavapipe) renders without a validation message:
/// the texels live in a texel buffer, limited by maxTexelBufferElements, which the map's whole
/// pyramid (44.9 M texels) is within.
#[test]
fn a_heightmap_beyond_a_storage_buffer_range_renders() {
    let side = 5800u32;
    let row: Vec<u8> = (0..side).map(|x| (x * 255 / side) as u8).collect();
    let data: Vec<u8> = (0..side).flat_map(|_| row.iter().copied()).collect();
    let png = gray_png("hm-big.png", side, side, &data);
    let out = tmp("hm-big-render.png");
    let grid = model_path("grid_uv_8x8.obj");
    let args = [
        "render",
        p(&grid),
        "-o",
        p(&out),
        "--width",
        "96",
        "--height",
        "64",
        "--level",
        "4",
        "--displace",
        "heightmap",
        "--heightmap",
        p(&png),
    ];
    let o = meshrefine(&args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");
}
