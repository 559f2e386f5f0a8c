//! The command line on bad and unusual mesh files, run as a user would: one clear sentence and
//! exit status 1 where a file cannot be drawn (naming it and the line), a warning where it can
//! with something dropped, never a panic, a hang or a validation message; meshes at any `f32`
//! scale framed, blank images errors.

mod common;

use common::cli::*;

#[test]
fn bad_meshes_give_one_clear_sentence() {
    let out = tmp("out.png");
    let missing = tmp("does-not-exist.obj");
    expect_error(
        &["render", p(&missing), "-o", p(&out)],
        &["does-not-exist.obj", "cannot read"],
    );
    let empty = write("empty.obj", b"");
    expect_error(&["render", p(&empty), "-o", p(&out)], &["empty.obj"]);
    let comments = write("comments.obj", b"# nothing here\n# at all\n");
    expect_error(&["render", p(&comments), "-o", p(&out)], &["comments.obj"]);
    let binary = write(
        "binary.obj",
        &[0x89, b'P', b'N', b'G', 0, 1, 2, 3, 255, 254, 10, 0],
    );
    expect_error(&["render", p(&binary), "-o", p(&out)], &["binary.obj"]);
    let range = write("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
    expect_error(
        &["render", p(&range), "-o", p(&out)],
        &["range.obj", "line 4", "99"],
    );
    let nan = write("nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_error(&["render", p(&nan), "-o", p(&out)], &["nan.obj", "line 2"]);
    let inf = write("inf.obj", b"v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
    expect_error(&["info", p(&inf)], &["inf.obj", "line 3"]);
    let zero = write("zero.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    expect_error(
        &["export", p(&zero), "-o", p(&tmp("zero-out.obj"))],
        &["zero.obj", "line 4"],
    );
    let lines_only = write("lines.obj", b"v 0 0 0\nv 1 0 0\nl 1 2\n");
    expect_error(&["info", p(&lines_only)], &["lines.obj"]);
}

/// No Vulkan driver at all: one sentence and a failure, validating or not (the loader's own
/// messages while the instance is not created are not printed beside it).
#[test]
fn a_missing_vulkan_driver_is_one_sentence() {
    let env = [("VK_DRIVER_FILES", "/nonexistent/no-driver.json")];
    for validate in [false, true] {
        let mut args = vec![
            "render",
            "--level",
            "1",
            "-o",
            "/tmp/meshrefine-no-driver.png",
        ];
        if validate {
            args.insert(0, "--validate");
        }
        let out = meshrefine_env(&args, &env);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert!(
            lines.len() == 1 && lines[0].starts_with("error: ") && stderr.contains("Vulkan driver"),
            "{stderr}"
        );
    }
}

#[test]
fn questionable_meshes_render_with_a_warning() {
    // Degenerate faces are dropped; a non-manifold mesh is fine for the flat surface. Both warn.
    for (file, warning) in [
        ("degenerate_faces.obj", "dropped 3 degenerate face(s)"),
        (
            "nonmanifold_edge.obj",
            "is not a manifold mesh: 1 edge(s) shared by more than two triangles",
        ),
    ] {
        let out = tmp(&format!("{file}.png"));
        let mesh = model_path(file);
        let args = [
            "--validate",
            "render",
            p(&mesh),
            "-o",
            p(&out),
            "--width",
            "64",
            "--height",
            "64",
        ];
        let o = meshrefine(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{file}: {stderr}");
        assert!(stderr.contains(warning), "{file}: {stderr}");
    }
}

#[test]
fn unbounded_inputs_are_refused_up_front() {
    // Each run timed alone (holding the lock other tests' GPU runs take), so that waiting for
    // them is not counted.
    let mut took = Duration::ZERO;
    let mut refused = |args: &[&str], needles: &[&str]| {
        let _guard = common::gpu_lock();
        let t0 = Instant::now();
        let out = bin()
            .args(args)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        took += t0.elapsed();
        check_error(&out, args, needles);
    };
    refused(&["info", "/dev/zero"], &["/dev/zero", "character device"]);
    refused(
        &["info", "/dev/urandom"],
        &["/dev/urandom", "character device"],
    );
    let dir = tmp("a-directory.obj");
    std::fs::create_dir_all(&dir).unwrap();
    refused(&["info", p(&dir)], &["a-directory.obj", "directory"]);
    // 20 GB of NUL bytes, sparse: refused by its size without reading.
    let huge = tmp("huge-sparse.obj");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(20 << 30).unwrap();
    drop(f);
    refused(
        &["info", p(&huge)],
        &["huge-sparse.obj", "21474836480 bytes", "1073741824"],
    );
    std::fs::remove_file(&huge).ok();
    // Under the limit, 512 MB of NUL bytes: refused at the first chunk.
    let zeros = tmp("zeros.obj");
    let f = std::fs::File::create(&zeros).unwrap();
    f.set_len(512 << 20).unwrap();
    drop(f);
    refused(
        &["render", p(&zeros), "-o", "z.png"],
        &["zeros.obj", "line 1", "NUL"],
    );
    std::fs::remove_file(&zeros).ok();
    assert!(took < Duration::from_secs(20), "{took:?}");
}

/// Every input path (the mesh, `--heightmap`, `--tags`), on every command that reads it, is
/// checked before it is opened: a FIFO (or a link to one) is one sentence naming it, not a hang.
#[test]
fn a_fifo_is_refused_without_opening_it() {
    let fifo = tmp("pipe.obj");
    let link = tmp("link-to-pipe.obj");
    std::fs::remove_file(&fifo).ok();
    std::fs::remove_file(&link).ok();
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    std::os::unix::fs::symlink(&fifo, &link).unwrap();
    let grid = model_path("grid_uv_8x8.obj");
    let tet = model_path("tetrahedron.obj");
    let (png, obj) = (tmp("f.png"), tmp("f.obj"));
    for path in [&fifo, &link] {
        let hm = ["--displace", "heightmap", "--heightmap", p(path)];
        let tags = ["--surface", "stpn", "--tags", p(path)];
        let mut cases = vec![
            vec!["info", p(path)],
            vec!["render", p(path), "-o", "f.png"],
        ];
        for (cmd, out) in [("render", &png), ("export", &obj)] {
            cases.push([vec![cmd, p(&grid), "-o", p(out)], hm.to_vec()].concat());
            cases.push([vec![cmd, p(&tet), "-o", p(out)], tags.to_vec()].concat());
        }
        cases.push(
            [
                vec!["view", p(&grid), "--headless-output", p(&png)],
                hm.to_vec(),
            ]
            .concat(),
        );
        cases.push(
            [
                vec!["view", p(&tet), "--headless-output", p(&png)],
                tags.to_vec(),
            ]
            .concat(),
        );
        for args in cases {
            let _guard = common::gpu_lock();
            let child = bin()
                .args(&args)
                .env_remove("DISPLAY")
                .env_remove("WAYLAND_DISPLAY")
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            let out = wait_at_most(child, Duration::from_secs(20))
                .unwrap_or_else(|| panic!("{args:?} hung on a FIFO"));
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
            assert!(
                stderr.starts_with("error: ")
                    && stderr.contains("is a FIFO")
                    && stderr.contains(p(path)),
                "{stderr}"
            );
        }
    }
    std::fs::remove_file(&link).ok();
    std::fs::remove_file(&fifo).ok();
}

#[test]
fn meshes_of_any_f32_scale_are_framed_and_blank_images_are_errors() {
    let size = ["--width", "64", "--height", "48", "--level", "2"];
    let near_max = "v 3e38 1 1\nv 3e38 -1 1\nv 3e38 -1 -1\nv 3e38 1 -1\nf 1 2 3\nf 1 3 4\n";
    let cases = [
        ("edge-1e-5", tetrahedron(0.5e-5, 0.0)),
        ("edge-2e-5", tetrahedron(1e-5, 0.0)),
        ("edge-1e19", tetrahedron(0.5e19, 0.0)),
        ("edge-1e-18", tetrahedron(0.5e-18, 0.0)),
        ("offset-1e7", tetrahedron(1.0, 1e7)),
        ("near-3e38", near_max.to_string()),
    ];
    for (name, text) in &cases {
        let mesh = write(&format!("{name}.obj"), text.as_bytes());
        for driver in ["pattern", "tess", "static"] {
            let png = tmp(&format!("{name}-{driver}.png"));
            let mut args = vec!["--validate", "render", p(&mesh), "-o", p(&png)];
            args.extend(["--driver", driver]);
            args.extend(size);
            ok(&args);
            let n = covered(&png);
            assert!(
                n > 64 * 48 / 10,
                "{name} {driver}: only {n} pixels show the mesh"
            );
        }
    }
    // A sine displacement far from the origin reaches phases f32 cannot resolve: refused,
    // naming the frequency as typed, or as the mesh's default where none was given.
    let far = write("offset-1e7-sine.obj", tetrahedron(1.0, 1e7).as_bytes());
    let far_png = tmp("far.png");
    let sine = ["render", p(&far), "-o", p(&far_png), "--displace", "sine"];
    expect_error(
        &sine,
        &["at the default --frequency 13.856407 (24 over the mesh's bounding radius) reaches phases"],
    );
    expect_error(
        &[&sine[..], &["--frequency", "13"]].concat(),
        &["--displace sine at --frequency 13 reaches phases"],
    );
    // What f32 cannot draw is dropped as degenerate, and a mesh of only that is refused.
    let subnormal = write("subnormal.obj", tetrahedron(1e-45, 0.0).as_bytes());
    expect_error(
        &["info", p(&subnormal)],
        &["subnormal.obj", "underflows", "no triangles"],
    );
    let too_big = write("edge-1e20.obj", tetrahedron(1e20, 0.0).as_bytes());
    expect_error(
        &["render", p(&too_big), "-o", p(&tmp("x.png"))],
        &["edge-1e20.obj", "overflows", "no triangles"],
    );
    let mut mixed = tetrahedron(1.0, 0.0);
    mixed += "v 1e-45 0 0\nv 0 1e-45 0\nv 0 0 1e-45\nf 5 6 7\n";
    let mixed = write("mixed-subnormal.obj", mixed.as_bytes());
    let out = meshrefine(&["info", p(&mixed)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("dropped 1 degenerate face(s)") && stderr.contains("at line 12"),
        "{stderr}"
    );

    // Two specks far apart: each far below a pixel once both are framed. The image is written
    // but reported as blank, status 1.
    let specks = "v 0 0 0\nv 1e-6 0 0\nv 0 1e-6 0\nv 1000 0 0\nv 1000 1e-6 0\nv 1000 0 1e-6\nf 1 2 3\nf 4 5 6\n";
    let specks = write("specks.obj", specks.as_bytes());
    let png = tmp("specks.png");
    std::fs::remove_file(&png).ok();
    let mut args = vec!["render", p(&specks), "-o", p(&png)];
    args.extend(size);
    expect_error(&args, &["specks.png", "is blank", "specks.obj"]);
    assert!(png.exists() && covered(&png) == 0);
    // On the light background the check compares with that background.
    let mut light = args.clone();
    light.extend(["--background", "light"]);
    expect_error(&light, &["specks.png", "is blank", "specks.obj"]);
    // A field of view that shrinks the mesh to a speck is named.
    let mut wide = vec!["render", "--fov", "179.999", "-o", p(&png)];
    wide.extend(size);
    expect_error(&wide, &["is blank", "framed at --fov 179.999"]);
    let out = meshrefine(&args);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("wrote"));
    // Drawn adaptively (the default) with nothing culled: the message blames no culling.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("cull"), "{stderr}");
    assert!(!stderr.contains("--msaa"), "{stderr}");
    // A single pixel: the fan covers its centre, which the default multisampling's four
    // samples can miss; the message says so, and one sample draws it.
    let fan = model_path("fan24_open.obj");
    let one = [
        "render",
        p(&fan),
        "-o",
        p(&png),
        "--width",
        "1",
        "--height",
        "1",
    ];
    let out = meshrefine(&one);
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains("--msaa 1 samples each pixel's centre"),
            "{stderr}"
        );
    }
    let mut single = one.to_vec();
    single.extend(["--msaa", "1"]);
    expect_success(&single);
    // An eye nearer a face than the near plane (a thousandth of the framed radius) sees it
    // clipped: among the reasons given.
    let (tri, near_png) = (tmp("near-plane-triangle.obj"), tmp("near-plane.png"));
    std::fs::write(&tri, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    #[rustfmt::skip]
    let near = ["render", p(&tri), "-o", p(&near_png), "--surface", "flat", "--width", "64",
        "--height", "64", "--eye", "0.3,0.3,0.0015", "--look-at", "0.3,0.3,-1"];
    expect_error(
        &near,
        &["is blank", "or nearer the eye than the near plane"],
    );
}

#[test]
fn texture_coordinates_are_validated() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let vt = "vt 0 0\nvt 1 0\nvt 0 1\n";
    let refused = |name: &str, text: String, needles: [&str; 2]| {
        let mesh = write(&format!("{name}.obj"), text.as_bytes());
        let file = format!("{name}.obj");
        expect_error(&["info", p(&mesh)], &[&file, needles[0], needles[1]]);
    };
    let zero = ["line 4", "texture coordinate 0"];
    refused("vt-zero", format!("{tri}f 1/0 2/0 3/0\n"), zero);
    let none = ["line 4", "no 'vt' lines"];
    refused("vt-none", format!("{tri}f 1/2 2/2 3/2\n"), none);
    refused(
        "vt-range",
        format!("{tri}{vt}f 1/99/1 2/1 3/1\n"),
        ["line 7", "99"],
    );
    refused(
        "vt-rel",
        format!("{tri}{vt}f 1/-5 2/1 3/1\n"),
        ["line 7", "-5"],
    );
    refused(
        "vt-text",
        format!("{tri}vt abc def\nf 1 2 3\n"),
        ["line 4", "'abc'"],
    );
    refused(
        "vt-nan",
        format!("{tri}vt nan 0\nf 1 2 3\n"),
        ["line 4", "NaN"],
    );
    let good = write(
        "vt-good.obj",
        format!("{tri}{vt}f 1/1 2/2 3/3\n").as_bytes(),
    );
    ok(&["info", p(&good)]);
}

#[test]
fn logs_are_bounded_and_limits_name_the_file_and_the_remedy() {
    // A cube plus one face of 2.4 million indices: of its 2.4 M fan triangles, 0.96 M repeat a
    // vertex and all but two of the others repeat the three vertices of an earlier triangle.
    let mut text = std::fs::read_to_string(model_path("cube_tri.obj")).unwrap();
    let line = text.lines().count() + 1;
    text += &format!("f {}\n", "1 2 3 4 5 ".repeat(480_000));
    let big = write("cube-plus-big-face.obj", text.as_bytes());
    let out = meshrefine(&["info", p(&big)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.lines().count() <= 2,
        "{} lines: {}",
        stderr.lines().count(),
        &stderr[..stderr.len().min(2000)]
    );
    assert!(
        stderr.contains(&format!(
            "'{}': dropped 2399996 degenerate face(s)",
            p(&big)
        )) && stderr.contains(&format!("at line {line}")),
        "{stderr}"
    );
    let info = String::from_utf8_lossy(&out.stdout);
    assert!(info.contains("triangles: 14\n"), "{info}");
    // The non-manifold warning names the path, not the file stem.
    let nm = model_path("nonmanifold_edge.obj");
    let out = meshrefine(&[
        "render",
        p(&nm),
        "-o",
        p(&tmp("nm.png")),
        "--width",
        "32",
        "--height",
        "32",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("warning: '{}' is not a manifold mesh", p(&nm))),
        "{stderr}"
    );
}

/// A mesh with a flipped face is drawn, with one warning naming the file and how many edges
/// join triangles of opposite winding; the same mesh wound consistently gets none.
#[test]
fn a_flipped_face_is_warned_about() {
    for (name, faces, warned) in [
        ("flipped.obj", "f 1 2 3\nf 2 3 4\n", true),
        ("wound.obj", "f 1 2 3\nf 2 4 3\n", false),
    ] {
        let mesh = tmp(name);
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n{faces}");
        std::fs::write(&mesh, text).unwrap();
        #[rustfmt::skip]
        let out = meshrefine(&[
            "render", p(&mesh), "-o", p(&tmp("flipped.png")), "--level", "2", "--width", "32",
            "--height", "32",
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name}: {stderr}");
        let warning = format!(
            "warning: '{}' is not consistently oriented: 1 edge(s) join triangles of opposite winding",
            p(&mesh)
        );
        assert_eq!(stderr.contains(&warning), warned, "{name}: {stderr}");
        assert_eq!(
            stderr.matches("oriented").count(),
            warned as usize,
            "{stderr}"
        );
    }
}

/// A text file that is not an OBJ stops at its first line, as it is read: a 20 MB file of
/// words (or of bytes that are not UTF-8) is refused naming line 1, not read to its end and then
/// found empty. OBJ files that begin with comments, blank lines or any OBJ statement still load.
#[test]
fn text_that_is_not_obj_stops_at_its_first_line() {
    let words = write("words.obj", "hello world\n".repeat(1 << 21).as_bytes());
    expect_error(
        &["info", p(&words)],
        &["words.obj' line 1", "'hello'", "not a Wavefront OBJ file"],
    );
    let latin1 = write("latin1.obj", b"\xe9t\xe9\nv 0 0 0\n");
    expect_error(&["info", p(&latin1)], &["line 1", "not UTF-8 text"]);
    // UTF-16 (Notepad's "Unicode"): named as such, not as binary data.
    let utf16: Vec<u8> = [0xfeff_u16]
        .into_iter()
        .chain("v 0 0 0\r\n".encode_utf16())
        .flat_map(u16::to_le_bytes)
        .collect();
    let utf16 = write("utf16.obj", &utf16);
    expect_error(
        &["info", p(&utf16)],
        &["line 1", "is UTF-16 text", "save it as UTF-8"],
    );
    // Comments and names in Latin-1 / CP1252 before the first statement load, as they do
    // further down.
    let tri = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for (name, head) in [
        (
            "comments-first.obj",
            &b"# made by hand\n\n  mtllib x.mtl\no tri\n"[..],
        ),
        (
            "latin1-comment.obj",
            b"# Cr\xe9\xe9 par 3ds Max\nmtllib x.mtl\n",
        ),
        ("cp1252-name.obj", b"o caf\xe9\n"),
    ] {
        let ok = write(name, &[head, &tri[..]].concat());
        let out = meshrefine(&["info", p(&ok)]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// A file name holding a newline stays one header comment in an export (the file reloads),
/// and one line in a message.
#[test]
fn control_characters_in_names_are_escaped() {
    let tet = std::fs::read(model_path("tetrahedron.obj")).unwrap();
    let odd = write("a\nf 1 2 999.obj", &tet);
    let obj = tmp("escaped-name.obj");
    ok(&["export", p(&odd), "-o", p(&obj), "--level", "1"]);
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(
        text.starts_with("# meshrefine export of 'a\\nf 1 2 999'"),
        "{text:.200}"
    );
    ok(&["info", p(&obj)]);
    let missing = tmp("no\u{1b}[31mfile.obj");
    let out = meshrefine(&["info", p(&missing)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains('\u{1b}') && stderr.contains("no\\u{1b}[31mfile.obj"),
        "{stderr}"
    );
    // Standard output too: the mesh's path, the files written, the benchmark's mesh name.
    let clears = write("v\u{1b}[2Jx.obj", &tet);
    let (png, obj) = (tmp("w\nx.png"), tmp("e\u{1b}[2J.obj"));
    let runs = [
        (vec!["info", p(&clears)], "mesh: "),
        (
            vec!["export", p(&clears), "--level", "1", "-o", p(&obj)],
            "e\\u{1b}[2J.obj",
        ),
        (
            vec!["render", p(&clears), "--level", "1", "-o", p(&png)],
            "w\\nx.png",
        ),
        (
            vec![
                "bench",
                p(&clears),
                "--levels",
                "1",
                "--frames",
                "1",
                "--drivers",
                "pattern",
            ],
            "Every row: mesh v\\u{1b}[2Jx",
        ),
    ];
    for (args, needle) in runs {
        let out = meshrefine(&args);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{args:?}: {stdout}");
        assert!(!stdout.contains('\u{1b}'), "{args:?}: {stdout}");
        assert!(stdout.contains(needle), "{args:?}: {needle} in {stdout}");
        if args[0] == "info" {
            assert!(stdout.contains("v\\u{1b}[2Jx.obj"), "{stdout}");
        }
    }
    // A benchmark's --out with a newline: escaped where the summary names the table, and in
    // the table's Command line (single-quoted there, as it holds a backslash).
    let prefix = tmp("b\nout");
    #[rustfmt::skip]
    let out = ok(&[
        "bench", p(&clears), "--levels", "1", "--frames", "1", "--drivers", "static", "--out",
        p(&prefix),
    ]);
    assert!(
        out.contains("b\\nout.md\n") && out.contains("wrote "),
        "{out}"
    );
    let md = std::fs::read_to_string(prefix.with_file_name("b\nout.md")).unwrap();
    assert!(
        md.lines().next().unwrap().ends_with("b\\nout'`"),
        "{md:.300}"
    );
    // The table's mesh cells (the mesh is named by its file) escaped too.
    assert!(
        !md.contains('\u{1b}') && md.contains("v\\u{1b}[2Jx"),
        "{md}"
    );
}

/// Coincident triangles are dropped with the degenerate ones' one-line warning; Loop, which
/// needs every face, refuses them naming the line and what it cannot take; the pillow (two
/// triangles on the same three vertices) among them.
#[test]
fn duplicate_triangles_are_dropped_and_loop_names_them() {
    let mut text =
        String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 1 3 4\n");
    for k in 0..3000 {
        text.push_str(["f 1 2 3\n", "f 2 3 1\n", "f 3 2 1\n"][k % 3]);
    }
    let dups = write("dups.obj", text.as_bytes());
    let png = tmp("dups.png");
    let w = warnings_of(&[
        "render",
        p(&dups),
        "-o",
        p(&png),
        "--width",
        "32",
        "--height",
        "32",
        "--level",
        "2",
    ]);
    assert_eq!(w.len(), 1, "{w:#?}");
    assert!(
        w[0].contains("dups.obj': dropped 3000 degenerate face(s)")
            && w[0].contains("at line 9, repeats the three vertices of an earlier face"),
        "{}",
        w[0]
    );
    let info = ok(&["info", p(&dups)]);
    assert!(info.contains("triangles: 4\n"), "{info}");
    let pillow = write(
        "pillow.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n",
    );
    for file in [&pillow, &dups] {
        let line = if file == &pillow { "line 5" } else { "line 9" };
        expect_error(
            &["render", p(file), "-o", p(&png), "--surface", "loop"],
            &[
                p(file),
                &format!("the face at {line} repeats the three vertices of an earlier face"),
                "two faces on the same three vertices",
            ],
        );
    }
    expect_error(
        &["info", p(&pillow), "--surface", "loop"],
        &["pillow.obj", "line 5"],
    );
}

/// An export of a mesh far from the origin keeps the refined shape: written in `f64` where
/// `f32` would round it away, it is the same mesh as at the origin, moved (the tetrahedron at
/// 1e7, every corner exact in `f32`; at that offset `f32` steps by 1, the whole tetrahedron's
/// size). Near the origin, up to 256 radii away, the lines are `f32`'s.
#[test]
fn exports_far_from_the_origin_keep_their_shape() {
    let coords = |text: &str| -> Vec<[f64; 3]> {
        (text.lines())
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let c: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                [c[0], c[1], c[2]]
            })
            .collect()
    };
    let export = |name: &str, offset: f64, surface: &str, driver: &str| -> String {
        let mesh = write(&format!("{name}.obj"), tetrahedron(1.0, offset).as_bytes());
        let obj = tmp(&format!("{name}-{surface}-{driver}.out.obj"));
        let args = ["export", p(&mesh), "--surface", surface, "--driver", driver];
        ok(&[&args[..], &["--level", "8", "-o", p(&obj)]].concat());
        std::fs::read_to_string(&obj).unwrap()
    };
    for (surface, driver) in [("pn", "pattern"), ("phong", "tess")] {
        let near_text = export("tet-origin", 0.0, surface, driver);
        let far_text = export("tet-1e7", 1e7, surface, driver);
        // Near the origin (and at 100 radii) each coordinate is its f32's shortest decimal;
        // far away, digits f32 does not hold.
        let f32_digits = |text: &str| {
            (text.lines())
                .filter_map(|l| l.strip_prefix("v "))
                .flat_map(|l| l.split(' '))
                .all(|c| c.parse::<f32>().unwrap().to_string() == c)
        };
        assert!(f32_digits(&near_text) && !f32_digits(&far_text));
        assert!(f32_digits(&export("tet-100", 100.0, surface, driver)));
        let (near, far) = (coords(&near_text), coords(&far_text));
        assert_eq!(near.len(), far.len());
        assert!(near.len() > 100);
        let worst = near
            .iter()
            .zip(&far)
            .flat_map(|(a, b)| (0..3).map(move |k| (b[k] - 1e7 - a[k]).abs()))
            .fold(0.0f64, f64::max);
        // Near: f32's rounding of coordinates up to 1.4 (at most 6e-8); far: f64's.
        assert!(worst < 2e-7, "{surface} {driver}: moved by {worst}");
        let mut distinct: Vec<String> = far.iter().map(|c| format!("{c:?}")).collect();
        distinct.sort();
        distinct.dedup();
        assert_eq!(
            distinct.len(),
            far.len(),
            "{surface} {driver}: vertices merged"
        );
    }
}

/// A polygon whose triangles cannot cover it (a bow tie crossing itself, a concave star past
/// the corners that are clipped) is loaded with one warning naming its line; warped quads and a
/// concave polygon within the limit load silently.
#[test]
fn polygons_that_triangles_cannot_cover_are_named() {
    let bow = "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\nv 0 0 1\nv 1 1 1\nv 1 0 1\nv 0 1 1\nf 5 6 7 8\n".to_string();
    assert_eq!(
        info_stderr("bow.obj", bow.as_bytes()).trim_end(),
        format!(
            "warning: '{}': 2 polygons (the first at line 5) cross or touch themselves, or are concave with more than 256 corners: they are split into triangles that may overlap or turn over (split such faces into simple polygons in the file)",
            tmp("bow.obj").display()
        )
    );
    let star = |n: usize| {
        let mut text = String::new();
        for k in 0..n {
            let r = 1.0 - 0.5 * (k % 2) as f64;
            let a = k as f64 * std::f64::consts::TAU / n as f64;
            text += &format!("v {} {} 0\n", r * a.cos(), r * a.sin());
        }
        text + "f " + &(1..=n).map(|k| k.to_string()).collect::<Vec<_>>().join(" ") + "\n"
    };
    let big = info_stderr("star1000.obj", star(1000).as_bytes());
    assert!(
        big.contains("the polygon at line 1001 crosses or touches itself"),
        "{big}"
    );
    assert_eq!(info_stderr("star256.obj", star(256).as_bytes()), "");
    let warped =
        "v 0 0 0\nv 1 0 0.2\nv 1 1 0\nv 0 1 0.3\nv 2 0 0\nv 2 1 0.1\nf 1 2 3 4\nf 2 5 6 3\n";
    assert_eq!(info_stderr("warped.obj", warped.as_bytes()), "");
}

/// A face that gives `vt` on some corners only has none, and loading says so once.
#[test]
fn partial_texture_coordinates_are_said() {
    let stderr = info_stderr(
        "partial_vt.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3\nf 2/2 4 3\n",
    );
    assert_eq!(
        stderr.trim_end(),
        format!(
            "warning: '{}': 2 face(s) give texture coordinates (vt) for some corners only (the first at line 7): those faces have none",
            tmp("partial_vt.obj").display()
        )
    );
}

/// Lines that are no OBJ statement (a capital `F`, a word run into its numbers, stray text)
/// drop what they meant to say: the loader says how many it ignored and where the first is;
/// the statements of the format meshrefine does not draw (groups, materials, lines) pass
/// silently.
#[test]
fn lines_that_are_no_obj_statement_are_warned_about() {
    let stderr = info_stderr(
        "misspelt.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nF 2 4 3\nf2 4 3\ng side\nusemtl red\nl 1 2\n",
    );
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("no OBJ statement"))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].contains("2 line(s)") && warnings[0].contains("line 6, 'F'"),
        "{stderr}"
    );
    // Statements of the format that draw nothing here, and a statement continued on the next
    // line with `\`.
    let stderr = info_stderr(
        "groups.obj",
        b"mtllib none.mtl\no thing\ng side \\\n  top\ns 1\ncall other.obj\ncsh ls\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\nl 1 2\n",
    );
    assert!(!stderr.contains("no OBJ statement"), "{stderr}");
    // A byte-order mark inside the file (two files joined, the second with one) is shown
    // escaped, not as an invisible character before a word said to be no statement.
    let stderr = info_stderr(
        "joined.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\u{feff}f 1 3 2\nf 1 2 4\n".as_bytes(),
    );
    assert!(
        stderr.contains("(the first: line 5, '\\u{feff}f')") && !stderr.contains('\u{feff}'),
        "{stderr}"
    );
}

/// Detail far below the drawing frame's precision (a cube of unit size beside a triangle
/// reaching 1e18 away, drawn in `f32` at unit radius) collapses to one point: every export
/// drops the triangles of no area that makes, at uniform levels on both drivers and
/// adaptively, so that no face repeats a vertex (which a reader warns about and drops).
#[test]
fn exports_drop_the_triangles_that_collapse_to_a_point() {
    let cube = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/models/cube_tri.obj"
    ))
    .unwrap();
    let mesh = write(
        "cube-beside-1e18.obj",
        format!("{cube}\nv 1e18 0 0\nv 0 1e18 0\nv 0 0 1e18\nf 9 10 11\n").as_bytes(),
    );
    for (name, args) in [
        ("pattern-l1", vec!["--level", "1"]),
        ("pattern-l2", vec!["--level", "2"]),
        ("tess-l2", vec!["--level", "2", "--driver", "tess"]),
        ("adaptive", vec!["--pixel-error", "1"]),
    ] {
        let out = tmp(&format!("collapsed-{name}.obj"));
        let mut all = vec!["export", p(&mesh), "-o", p(&out)];
        all.extend(args);
        ok(&all);
        let text = std::fs::read_to_string(&out).unwrap();
        let faces: Vec<Vec<&str>> = (text.lines())
            .filter_map(|l| l.strip_prefix("f "))
            .map(|f| f.split(' ').map(|c| c.split('/').next().unwrap()).collect())
            .collect();
        assert!(!faces.is_empty(), "{name}: no face");
        for f in &faces {
            assert!(
                f[0] != f[1] && f[1] != f[2] && f[2] != f[0],
                "{name}: face {f:?} repeats a vertex"
            );
        }
        // Reading it back drops nothing.
        let info = meshrefine(&["info", p(&out)]);
        let stderr = String::from_utf8_lossy(&info.stderr);
        assert!(
            info.status.success() && !stderr.contains("degenerate"),
            "{name}: {stderr}"
        );
    }
}
