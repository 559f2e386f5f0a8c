//! The command line, run as a user would, with the validation layer on (`--validate` makes any
//! validation message or leak an error): `render`, `export`, `info`, the headless `view` and
//! `devices` on good input, standard output closed or full, `loop` from the command line, the
//! demo script's arguments. Bad input, option values, `bench` and adaptive drawing have files of
//! their own (`cli_inputs.rs`, `cli_surface_inputs.rs`, `cli_options.rs`, `cli_bench.rs`,
//! `cli_adaptive.rs`); their shared helpers are in `common/cli.rs`.

mod common;

use common::cli::*;

/// `info --level` with `--surface loop` counts the GPU drivers' bytes as `bench` stores them:
/// the elements' and M1, Loop's passes' data and the tables.
#[test]
fn info_counts_loops_geometry_as_bench_does() {
    let spot = model_path("spot_control_tri.obj");
    let info = ok(&["info", p(&spot), "--level", "8", "--surface", "loop"]);
    let bench = ok(&[
        "bench",
        p(&spot),
        "--levels",
        "8",
        "--surfaces",
        "loop",
        "--drivers",
        "pattern,tess,static",
        "--frames",
        "1",
        "--width",
        "32",
        "--height",
        "32",
    ]);
    for (driver, row) in [
        ("pattern", "pattern/instanced"),
        ("tess", "tess"),
        ("static", "static"),
    ] {
        let stored = (bench.lines())
            .find(|l| l.split_whitespace().next() == Some(row))
            .and_then(|l| l.split_whitespace().last())
            .unwrap_or_else(|| panic!("no {row} row: {bench}"));
        let line = format!("  {driver:8} {stored:>14} bytes of GPU geometry");
        assert!(info.contains(&line), "{line:?} not in {info}\n{bench}");
    }
}

#[test]
fn info_reports_topology_and_footprint() {
    let s = ok(&["info", p(&model_path("nonmanifold_edge.obj"))]);
    assert!(s.contains("non-manifold edges: 1"), "{s}");
    let s = ok(&["info", p(&model_path("grid_open_8x8.obj")), "--level", "64"]);
    assert!(s.contains("vertices: 81"), "{s}");
    assert!(s.contains("triangles: 128"), "{s}");
    assert!(s.contains("boundary edges: 32"), "{s}");
    assert!(s.contains("valence histogram"), "{s}");
    // 128 coarse triangles x 4096 = 524288 refined triangles; static holds 128 x 2145 vertices
    // and 3 indices per refined triangle.
    assert!(s.contains("524288 refined triangles"), "{s}");
    // The tessellator's concentric rings make 6144 triangles a patch at level 64 (1.5 N²), said
    // on tess's line.
    assert!(
        s.contains("786432 refined triangles (6144 per element)"),
        "{s}"
    );
    let static_bytes = 128u64 * 2145 * 24 + 524288 * 3 * 4;
    assert!(
        s.contains(&format!("static {static_bytes:>15}")) || s.contains(&static_bytes.to_string()),
        "{s}"
    );
    assert!(!s.contains("note:"), "{s}");
    // Past lavapipe's maxTessellationGenerationLevel (64), tess's line says it cannot draw it,
    // in render's sentence; the other drivers' do not.
    let s = ok(&["info", p(&model_path("grid_open_8x8.obj")), "--level", "65"]);
    let note = "    note: level 65 is beyond this device's maxTessellationGenerationLevel (64): the tess driver cannot draw it";
    assert_eq!(s.matches("note:").count(), 1, "{s}");
    assert!(s.lines().any(|l| l.starts_with(note)), "{s}");
    // Past one allocation, the static driver's line says render refuses it, in render's
    // sentence (its vertex buffer: 5856 elements x 131,841 vertices x 24 bytes at level 512).
    let spot = model_path("spot_tri.obj");
    // A --device that names none is refused, as render refuses it, before anything is
    // printed: where the notes need the device and where nothing reads it.
    for extra in [&["--level", "512"][..], &[]] {
        let mut args = vec!["--device", "no-such-gpu", "info", p(&spot)];
        args.extend(extra);
        let out = meshrefine(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("no Vulkan device matches --device 'no-such-gpu'; available: "),
            "{stderr}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // One that names a device, in any case or with spaces around it, is taken.
    for name in ["LLVMPIPE", " llvm "] {
        let s = ok(&["--device", name, "info", p(&spot), "--level", "65"]);
        assert!(s.lines().any(|l| l.starts_with(note)), "{name}: {s}");
    }
    let s = ok(&["info", p(&spot), "--level", "512"]);
    let bytes = 5856u64 * 131_841 * 24;
    let sentence = format!(
        "the static driver's refined mesh at level 512 needs {bytes} bytes, over this device's maxMemoryAllocationSize"
    );
    let lines: Vec<&str> = s.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with("  static "))
        .unwrap();
    assert!(
        lines[at + 1].starts_with(&format!("    note: {sentence}")),
        "{s}"
    );
    let png = tmp("static-512.png");
    let out = meshrefine(&[
        "render",
        p(&spot),
        "--level",
        "512",
        "--driver",
        "static",
        "-o",
        p(&png),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains(&sentence), "{stderr}");
    assert!(
        lines[at + 1].ends_with(stderr.trim_end().split(&sentence).nth(1).unwrap()),
        "{s}\n{stderr}"
    );
    // Loop's elements are M1's faces: the icosahedron's 20 triangles make 80, x 64 at level 8
    // (what `export --surface loop --level 8` writes).
    let ico = model_path("icosahedron.obj");
    let s = ok(&["info", p(&ico), "--surface", "loop", "--level", "8"]);
    assert!(
        s.contains(
            "5120 refined triangles (64 per M1 face: the elements are one Loop step's faces)"
        ),
        "{s}"
    );
}

#[test]
fn render_export_and_headless_view_work() {
    let png = tmp("render.png");
    ok(&[
        "--validate",
        "render",
        "-o",
        p(&png),
        "--width",
        "160",
        "--height",
        "120",
        "--wireframe",
        "--driver",
        "tess",
        "--level",
        "5",
    ]);
    let img = std::fs::read(&png).unwrap();
    assert_eq!(&img[1..4], b"PNG");

    // Icosahedron at level 4 (V=12, E=30, F=20). pattern: V + E(N-1) + F(N-1)(N-2)/2 = 162
    // welded vertices, 20*16 triangles. tess (transform feedback): the tessellator's rings have
    // 19 vertices and 24 triangles per patch: 12 + 30*3 + 20*7 = 242 vertices, 480 triangles.
    for (driver, vertices, triangles) in [("pattern", 162, 320), ("tess", 242, 480)] {
        let obj = tmp(&format!("export-{driver}.obj"));
        let ico = model_path("icosahedron.obj");
        let s = ok(&[
            "--validate",
            "export",
            p(&ico),
            "-o",
            p(&obj),
            "--level",
            "4",
            "--driver",
            driver,
        ]);
        assert!(s.contains("wrote"), "{s}");
        let (mesh, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
        let stats = mesh.stats();
        let counts = (stats.vertices, stats.triangles, stats.boundary_edges);
        assert_eq!(counts, (vertices, triangles, 0), "{driver}");
        assert_eq!(stats.inconsistently_oriented_edges, 0, "{driver}");
        assert_faces_agree_with_normals(&mesh);
    }

    // No display: `view` renders headlessly and says where the image went.
    let view_png = tmp("view.png");
    let s = ok(&["view", "--headless-output", p(&view_png), "--level", "3"]);
    assert!(s.contains("no display") && s.contains("view.png"), "{s}");
    assert!(view_png.exists());
    // The last frame asked for is that one frame; what only a window reads is named, once.
    let shot = tmp("view-shot.png");
    let _ = std::fs::remove_file(&shot);
    let args = ["view", "--headless-output", p(&view_png), "--level", "3"];
    let window_only = [
        "--screenshot",
        p(&shot),
        "--frames",
        "5",
        "--animate",
        "--fullscreen",
    ];
    let out = meshrefine(&[&args[..], &window_only[..]].concat());
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        std::fs::read(&shot).unwrap(),
        std::fs::read(&view_png).unwrap()
    );
    // The screenshot at the image's own path keeps the image (a copy onto itself would empty it).
    let same = ["--screenshot", p(&view_png)];
    let out = meshrefine(&[&args[..], &same[..]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(&view_png).unwrap(),
        std::fs::read(&shot).unwrap()
    );
    assert!(stdout.contains("wrote the screenshot"), "{stdout}");
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(
        warnings,
        ["warning: --frames, --animate, --fullscreen apply only to the window and are ignored: no display found (DISPLAY and WAYLAND_DISPLAY are unset)"],
        "{stderr}"
    );
    // A display that cannot be reached: the same fallback, saying so, at the window's size.
    std::fs::remove_file(&view_png).unwrap();
    let _guard = common::gpu_lock();
    let o = bin()
        .args(["view", "--headless-output", p(&view_png), "--level", "3"])
        .args(["--width", "320", "--height", "200"])
        .env("DISPLAY", ":97531")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        s.contains("cannot connect to the display ':97531'") && view_png.exists(),
        "{s}"
    );
    let png = png::Decoder::new(std::fs::File::open(&view_png).unwrap());
    let info = png.read_info().unwrap().info().clone();
    assert_eq!((info.width, info.height), (320, 200));
    drop(_guard);
    // --view, which the window starts in, is the headless image's: the plain view is one
    // colour over the background (one sample per pixel: no blended silhouettes).
    #[rustfmt::skip]
    ok(&[
        "view", "--headless-output", p(&view_png), "--view", "plain", "--msaa", "1", "--width",
        "160", "--height", "90",
    ]);
    let decoder = png::Decoder::new(std::fs::File::open(&view_png).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size()];
    reader.next_frame(&mut rgba).unwrap();
    let colours: std::collections::BTreeSet<&[u8]> = rgba.chunks_exact(4).collect();
    assert_eq!(colours.len(), 2, "{colours:?}");
}

/// The headless `view` has no panel to switch to what an option applies to: it warns of the
/// options its one image ignores as `render` does, and says that `--lod` (the window's level
/// by distance) draws the image uniformly at `--level`: the image `--level` alone draws.
#[test]
fn headless_view_warns_of_what_its_image_ignores() {
    let warnings = |out: &Output| -> Vec<String> {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        (stderr.lines())
            .filter(|l| l.starts_with("warning:"))
            .map(String::from)
            .collect()
    };
    let run = |png: &Path, extra: &[&str]| {
        let mut args = vec![
            "view",
            "--headless-output",
            p(png),
            "--width",
            "64",
            "--height",
            "48",
        ];
        args.extend(extra);
        meshrefine(&args)
    };
    let (with, without) = (tmp("view-lod.png"), tmp("view-no-lod.png"));
    for (lod, level) in [(&["--lod", "--level", "8"][..], "8"), (&["--lod"], "16")] {
        assert_eq!(
            warnings(&run(&with, lod)),
            [format!(
                "warning: --lod chooses levels by distance only in the window: no display found (DISPLAY and WAYLAND_DISPLAY are unset), so the image is drawn uniformly at --level {level}"
            )],
        );
        assert!(warnings(&run(&without, &["--level", level])).is_empty());
        assert_eq!(
            std::fs::read(&with).unwrap(),
            std::fs::read(&without).unwrap(),
            "{lod:?}"
        );
    }
    // What only a window reads is ignored with one warning, even a directory that is none.
    assert_eq!(
        warnings(&run(&with, &["--level", "8", "--frames", "3", "--screenshot-dir", "no/such/dir"])),
        ["warning: --frames, --screenshot-dir apply only to the window and are ignored: no display found (DISPLAY and WAYLAND_DISPLAY are unset)"]
    );
    #[rustfmt::skip]
    let out = run(&with, &[
        "--level", "8", "--max-level", "8", "--cull", "off", "--geomorph", "off", "--alpha", "0.5",
    ]);
    assert_eq!(
        warnings(&out),
        [
            "warning: --alpha applies only to --surface phong, not to --surface pn: it is ignored",
            "warning: --max-level applies only when drawing adaptively (with --pixel-error, or by default without --level or --lod): it is ignored",
            "warning: --cull applies only when drawing adaptively (with --pixel-error, or by default without --level or --lod): it is ignored",
            "warning: --geomorph applies only when drawing adaptively (with --pixel-error, or by default without --level or --lod): it is ignored",
        ]
    );
    // An empty DISPLAY names no display, as an unset one: headless, said so.
    let _guard = common::gpu_lock();
    let out = bin()
        .args([
            "view",
            "--headless-output",
            p(&with),
            "--width",
            "32",
            "--height",
            "24",
        ])
        .args(["--level", "2"])
        .env("DISPLAY", "")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success()
            && stdout.contains("no display found (DISPLAY and WAYLAND_DISPLAY are unset or empty)"),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_full_stdout_is_an_error_line_and_a_closed_one_ends_quietly() {
    for args in stdout_commands() {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        // /dev/full: every write fails with ENOSPC.
        let full = std::fs::File::create("/dev/full").unwrap();
        let _guard = common::gpu_lock();
        let out = bin()
            .args(&args)
            .env_remove("DISPLAY")
            .stdout(full)
            .output()
            .unwrap();
        drop(_guard);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?} >/dev/full: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert_eq!(
            stderr.trim(),
            "error: cannot write to standard output: No space left on device (os error 28)",
            "{args:?}"
        );
        // A pipe closed early (`| head`, `| true`): status 0, nothing said.
        let out = with_closed_stdout(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?} | true: {stderr}");
        assert!(stderr.is_empty(), "{args:?} | true: {stderr}");
    }
    // `bench --out` writes its files before the summary: they are there whether standard
    // output is closed early (status 0) or full (status 1).
    let tet = model_path("tetrahedron.obj");
    for (name, full_stdout) in [("closed", false), ("full", true)] {
        let prefix = tmp(&format!("bench-out-{name}"));
        let files = ["md", "csv", "json"].map(|x| prefix.with_extension(x));
        for f in &files {
            let _ = std::fs::remove_file(f);
        }
        let mut args = vec!["bench", p(&tet), "--out", p(&prefix)];
        args.extend("--levels 2 --frames 1 --width 32 --height 32".split(' '));
        let code = if full_stdout {
            let full = Stdio::from(std::fs::File::create("/dev/full").unwrap());
            meshrefine_with(&args, full, Stdio::null()).code()
        } else {
            with_closed_stdout(&args).status.code()
        };
        assert_eq!(code, Some(if full_stdout { 1 } else { 0 }), "{name}");
        for f in &files {
            let text = std::fs::read_to_string(f).unwrap_or_else(|e| panic!("{name}: {f:?}: {e}"));
            assert!(text.contains("tetrahedron"), "{name}: {f:?}");
        }
    }
    // A full stderr while warning: warnings are dropped, the command still succeeds.
    let degenerate = model_path("degenerate_faces.obj");
    let full = || Stdio::from(std::fs::File::create("/dev/full").unwrap());
    let status = meshrefine_with(&["info", p(&degenerate)], Stdio::null(), full());
    assert_eq!(status.code(), Some(0));
    // ... and an error still gives status 1 (not a panic's 101).
    let status = meshrefine_with(&["info", "no-such.obj"], Stdio::null(), full());
    assert_eq!(status.code(), Some(1));
}

/// Every surface x displacement renders from the command line, and an export of a displaced
/// curved surface reloads as a closed mesh with the refined counts.
#[test]
fn surfaces_and_displacements_render_and_export() {
    let png = tmp("surfaces.png");
    for s in ["flat", "phong", "pn"] {
        for d in ["none", "sine", "noise"] {
            let out = meshrefine(&[
                "render",
                "-o",
                png.to_str().unwrap(),
                "--width",
                "96",
                "--height",
                "64",
                "--level",
                "4",
                "--surface",
                s,
                "--displace",
                d,
            ]);
            assert!(
                out.status.success(),
                "{s} + {d}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
    let obj = tmp("pn-sine.obj");
    let ico = model_path("icosahedron.obj");
    let mesh = export_and_reload(
        &obj,
        &[
            p(&ico),
            "--level",
            "4",
            "--surface",
            "pn",
            "--displace",
            "sine",
        ],
    );
    // 20 faces x 16 triangles; 12 + 30 x 3 + 20 x 3 distinct vertices (welded: watertight).
    assert_eq!(mesh.triangles.len(), 320);
    assert_eq!(mesh.stats().vertices, 12 + 30 * 3 + 20 * 3);
    assert_eq!(mesh.stats().boundary_edges, 0);
}

/// `--surface loop` from the command line: `info` reports M1, the configurations and the
/// tables' bytes; render works on every driver with both boundary rules; an export of a closed
/// mesh reloads closed (welded on exact bits) with M1's counts; a mesh Loop cannot subdivide,
/// the height map (no texture coordinates on M1) and an unknown boundary rule are one sentence
/// each; bench rows carry the surface, the tables' bytes and the passes' cost.
#[test]
fn loop_surface_from_the_command_line() {
    let spot = model_path("spot_control_tri.obj");
    let info = ok(&["info", p(&spot), "--surface", "loop"]);
    assert!(
        info.contains("loop: M1 has 746 vertices and 1488 faces (edge-only boundaries)"),
        "{info}"
    );
    assert!(info.contains("configurations: 9"), "{info}");
    // Valences 3 to 10: 3 + 6 to 10 + 6 control points.
    assert!(info.contains("control points per face: 9 to 16"), "{info}");
    let bytes = info
        .lines()
        .find_map(|l| l.strip_prefix("basis function tables: "))
        .and_then(|l| l.strip_suffix(" bytes"))
        .and_then(|n| n.parse::<u64>().ok())
        .unwrap_or_else(|| panic!("no table line: {info}"));
    assert!(bytes > 0 && bytes <= 1 << 20, "{bytes}");
    let png = tmp("loop.png");
    let grid = model_path("grid_open_8x8.obj");
    for driver in ["static", "pattern", "tess"] {
        for (mesh, boundary) in [(&spot, "edge-only"), (&grid, "edge-and-corner")] {
            expect_success(&[
                "render",
                p(mesh),
                "-o",
                p(&png),
                "--width",
                "96",
                "--height",
                "64",
                "--level",
                "5",
                "--surface",
                "loop",
                "--boundary",
                boundary,
                "--driver",
                driver,
            ]);
        }
    }
    let obj = tmp("loop.obj");
    let ico = model_path("icosahedron.obj");
    for driver in ["pattern", "tess"] {
        let mesh = export_and_reload(
            &obj,
            &[
                p(&ico),
                "--level",
                "4",
                "--surface",
                "loop",
                "--driver",
                driver,
            ],
        );
        assert_eq!(
            mesh.stats().boundary_edges,
            0,
            "{driver}: the export is not closed"
        );
        if driver == "pattern" {
            // 80 M1 faces x 16 triangles; 42 + 120 x 3 + 80 x 3 distinct vertices.
            assert_eq!(mesh.triangles.len(), 80 * 16);
            assert_eq!(mesh.stats().vertices, 42 + 120 * 3 + 80 * 3);
        }
    }
    let bad = model_path("nonmanifold_edge.obj");
    expect_error(
        &["render", p(&bad), "-o", p(&png), "--surface", "loop"],
        &[
            "nonmanifold_edge.obj",
            "loop surface cannot subdivide",
            // The file's numbering and lines (the file's own comment says "edge 1-2").
            "the edge between vertex 1 and vertex 2 is shared by more than two faces (the face at line 9, the face at line 10 and the face at line 11)",
        ],
    );
    expect_error(
        &["info", p(&bad), "--surface", "loop"],
        &["nonmanifold_edge.obj", "more than two faces"],
    );
    // The other refusals name the first offending vertex or edge, and a face that repeats a
    // vertex, which the other surfaces drop with a warning, is an error: dropping it would
    // change the topology Loop subdivides.
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv -1 0 0\nv 0 -1 0\n";
    for (name, faces, want) in [
        (
            "loop_repeat.obj",
            "f 1 2 3\nf 2 4 4\n",
            "the face at line 8 repeats a vertex index",
        ),
        (
            "loop_orient.obj",
            "f 1 2 3\nf 2 3 4\n",
            "the face at line 7 and the face at line 8 both run from vertex 2 to vertex 3",
        ),
        (
            "loop_bowtie.obj",
            "f 1 2 3\nf 1 5 6\n",
            "vertex 1 (used by the face at line 7) is non-manifold",
        ),
    ] {
        let path = write(name, format!("{tri}{faces}").as_bytes());
        for cmd in ["render", "export"] {
            let out_file = if cmd == "render" { &png } else { &obj };
            expect_error(
                &[cmd, p(&path), "-o", p(out_file), "--surface", "loop"],
                &[name, "loop surface cannot subdivide", want],
            );
        }
        expect_error(&["info", p(&path), "--surface", "loop"], &[name, want]);
    }
    let uv = model_path("grid_uv_8x8.obj");
    expect_error(
        &[
            "render",
            p(&uv),
            "-o",
            p(&png),
            "--surface",
            "loop",
            "--displace",
            "heightmap",
        ],
        &["loop surface has no texture coordinates"],
    );
    expect_error(
        &[
            "render",
            "-o",
            p(&png),
            "--surface",
            "loop",
            "--bft-level",
            "9",
        ],
        &["--bft-level 9 is not within [1, 7]"],
    );
    for level in ["0", "8"] {
        expect_error(
            &["info", p(&spot), "--surface", "loop", "--bft-level", level],
            &[&format!("--bft-level {level} is not within [1, 7]")],
        );
    }
    let coarse = ok(&["info", p(&spot), "--surface", "loop", "--bft-level", "3"]);
    assert!(
        coarse.contains("table level: 3 (8 segments per M1-face edge, 45 lattice points)"),
        "{coarse}"
    );
    let out = meshrefine(&[
        "render",
        "-o",
        p(&png),
        "--surface",
        "loop",
        "--boundary",
        "sharp",
    ]);
    assert_eq!(out.status.code(), Some(2), "clap refuses an unknown value");
    let prefix = tmp("loop-bench");
    ok(&[
        "bench",
        "--surfaces",
        "flat,loop",
        "--levels",
        "2",
        "--drivers",
        "pattern,tess",
        "--frames",
        "1",
        "--width",
        "64",
        "--height",
        "64",
        "--out",
        p(&prefix),
    ]);
    let json = std::fs::read_to_string(prefix.with_extension("json")).unwrap();
    let loop_rows: Vec<&str> = json
        .lines()
        .filter(|l| l.contains("\"surface\":\"loop\""))
        .collect();
    assert_eq!(loop_rows.len(), 4, "{json}");
    for r in loop_rows {
        assert!(r.contains(&format!("\"table_bytes\":{bytes}")), "{r}");
        assert!(r.contains("\"elements\":1488"), "{r}");
        assert!(!r.contains("\"pre_pass_ms\":null"), "{r}");
        assert!(!r.contains("\"throughput_vs_flat\":null"), "{r}");
    }
}

#[test]
fn render_and_info_work_without_arguments() {
    // `render` alone writes meshrefine.png of the default scene in the current folder; `info`
    // alone describes the default mesh.
    let dir = tmp("no-arguments");
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("meshrefine.png");
    let _ = std::fs::remove_file(&png);
    let out = {
        let _guard = common::gpu_lock();
        bin()
            .arg("render")
            .current_dir(&dir)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap()
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("wrote meshrefine.png"));
    // Without --level it draws adaptively at 1 px, and says which levels it drew.
    assert!(
        stdout.contains("adaptive at 1 px, max level 64: levels (level:elements) "),
        "{stdout}"
    );
    let image = png::Decoder::new(std::fs::File::open(&png).unwrap());
    let info = image.read_info().unwrap().info().clone();
    assert_eq!((info.width, info.height), (1280, 720));
    let s = ok(&["info"]);
    assert!(s.contains("mesh: the default mesh (spot)"), "{s}");
    assert!(s.contains("triangles: 372"), "{s}");
}

#[test]
fn devices_lists_lavapipe_with_its_features() {
    let s = ok(&["devices"]);
    let first = s.lines().next().unwrap_or_default();
    assert!(first.ends_with("(default)"), "{s}");
    assert!(
        s.contains("maxTessellationGenerationLevel): up to 64"),
        "{s}"
    );
    assert!(
        s.contains("export through tess (transformFeedback): yes"),
        "{s}"
    );
    assert!(s.lines().all(|l| l.chars().count() <= 120), "{s}");
    // It lists every device whatever --device names, and says it ignores it.
    let o = meshrefine(&["--device", "no such device", "devices"]);
    assert!(o.status.success());
    assert_eq!(String::from_utf8_lossy(&o.stdout), s);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("warning: --device applies only to the commands that draw, not to devices (which lists every device): it is ignored"),
        "{stderr}"
    );
}

/// `render --background light` draws on the pale grey (its corner pixel is the light clear
/// colour, the dark default's is the dark one); `--view levels` and `--view normals` colour
/// the mesh differently from the shaded default; `--wireframe cage` adds the cyan cage,
/// `--wireframe` (`refined`) the refined edges and `--wireframe both` the two together.
#[test]
fn render_views_backgrounds_and_the_cage() {
    let small = [
        "--width", "96", "--height", "64", "--level", "4", "--msaa", "1",
    ];
    let render = |name: &str, extra: &[&str]| {
        let out = tmp(name);
        let mut args = vec!["--validate", "render", "-o", p(&out)];
        args.extend(small);
        args.extend(extra);
        ok(&args);
        rgba_of(&out)
    };
    let dark = render("bg-dark.png", &[]);
    let light = render("bg-light.png", &["--background", "light"]);
    let srgb = |b| meshrefine::render::background_srgb8(b);
    use meshrefine::render::Background;
    assert_eq!(dark[..4], srgb(Background::Dark));
    assert_eq!(light[..4], srgb(Background::Light));
    for (view, name) in [
        ("levels", "view-levels.png"),
        ("normals", "view-normals.png"),
    ] {
        let img = render(name, &["--view", view]);
        assert_ne!(img, dark, "--view {view} drew the shaded image");
    }
    let cyan = |img: &[u8]| {
        (img.chunks_exact(4))
            .filter(|p| p[2] as i32 > p[0] as i32 + 40 && p[1] as i32 > p[0] as i32 + 30)
            .count()
    };
    let caged = render("cage.png", &["--wireframe", "cage"]);
    assert_eq!(cyan(&dark), 0);
    assert!(cyan(&caged) > 50, "{} cage pixels", cyan(&caged));
    // `--wireframe` alone is `refined`: the refined edges, darker, no cage; `both` is the
    // refined wireframe with the cage over it: every pixel it changes is the cage's cyan.
    let refined = render("wire-refined.png", &["--wireframe"]);
    let named = render("wire-refined-named.png", &["--wireframe", "refined"]);
    assert_eq!(refined, named);
    let both = render("wire-both.png", &["--wireframe", "both"]);
    let changed = |a: &[u8], b: &[u8]| -> Vec<[u8; 4]> {
        (a.chunks_exact(4).zip(b.chunks_exact(4)))
            .filter(|(x, y)| x != y)
            .map(|(_, y)| y.try_into().unwrap())
            .collect()
    };
    assert_eq!(cyan(&refined), 0);
    let edges = changed(&dark, &refined).len();
    assert!(edges > 500, "{edges} refined edge pixels");
    let edges = changed(&caged, &both).len();
    assert!(edges > 500, "{edges} refined edge pixels with the cage");
    let cage = changed(&refined, &both);
    assert!(
        cage.len() > 50,
        "{} cage pixels over the wireframe",
        cage.len()
    );
    assert_eq!(cyan(cage.as_flattened()), cage.len(), "{cage:?}");
    let out = meshrefine(&["render", "--background", "pink"]);
    assert_eq!(out.status.code(), Some(2));
}

/// On a terminal (a pseudo-terminal made by `script`), the export's progress is one line
/// rewritten in place: each report starts with a carriage return, and the line ends only after
/// the last (`export: N passes, T triangles, written`), padded over what it replaces.
#[test]
fn export_progress_on_a_terminal_is_one_line_rewritten() {
    let ico = model_path("icosahedron.obj");
    let obj = tmp("progress_terminal.obj");
    let bytes = (3 * 54 * 3 * std::mem::size_of::<meshrefine::render::XfbVertex>()).to_string();
    let quote = |s: &str| format!("'{}'", s.replace('\'', "'\\''"));
    let command = [
        env!("CARGO_BIN_EXE_meshrefine"),
        "export",
        p(&ico),
        "-o",
        p(&obj),
        "--level",
        "6",
        "--driver",
        "tess",
    ]
    .map(quote)
    .join(" ");
    let _guard = common::gpu_lock();
    // `script -c` runs its command with $SHELL: a POSIX shell, for the quoting above.
    let out = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .env("SHELL", "/bin/sh")
        .env("MESHREFINE_VALIDATE", "1")
        .env("MESHREFINE_PROGRESS_AFTER", "0")
        .env("MESHREFINE_MAX_CAPTURE_BYTES", &bytes)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stdin(Stdio::null())
        .output()
        .expect("script (util-linux) runs the export on a terminal");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(!text.contains("validation"), "{text}");
    // The terminal ends lines with "\r\n"; progress lines are the ones saying "export:".
    let lines: Vec<&str> = (text.split("\r\n"))
        .filter(|l| l.contains("export:"))
        .collect();
    assert_eq!(lines.len(), 1, "{text:?}");
    let updates: Vec<&str> = lines[0].split('\r').filter(|u| !u.is_empty()).collect();
    assert!(lines[0].starts_with("\rexport: 1/7 passes"), "{text:?}");
    assert_eq!(
        updates.last().map(|u| u.trim_end()),
        Some("export: 7 passes, 1080 triangles, written"),
        "{text:?}"
    );
    // Each update covers the one before it.
    for pair in updates.windows(2) {
        assert!(pair[1].len() >= pair[0].len(), "{text:?}");
    }
}

/// A long export reports how far it is on standard error, a few plain lines when that is not a
/// terminal: each pass captured, the writing, the end (forced here from the start with
/// MESHREFINE_PROGRESS_AFTER=0). An export made in many small passes (MESHREFINE_MAX_CAPTURE_BYTES)
/// writes the same file as one made in one pass, which, being small, says nothing there. Bad
/// values of either variable are one sentence naming it.
#[test]
fn exports_report_progress_and_passes_keep_the_file() {
    let ico = model_path("icosahedron.obj");
    // Three of icosahedron's 20 elements a pass at level 6: 54 tess triangles of 3 vertices
    // (an `XfbVertex` each), or 28 pattern vertices of 64 bytes each.
    let xfb_vertex = std::mem::size_of::<meshrefine::render::XfbVertex>();
    for (driver, bytes, triangles) in [
        ("tess", 3 * 54 * 3 * xfb_vertex, 20 * 54),
        ("pattern", 3 * 28 * 64, 20 * 36),
    ] {
        let one = tmp(&format!("progress_one_{driver}.obj"));
        let many = tmp(&format!("progress_many_{driver}.obj"));
        let run = |o: &Path, env: &[(&str, &str)]| {
            let a = [
                "export",
                p(&ico),
                "-o",
                p(o),
                "--level",
                "6",
                "--driver",
                driver,
            ];
            succeeds(&a, env)
        };
        let quiet = run(&one, &[]);
        assert!(!quiet.contains("export:"), "{quiet}");
        let bytes = bytes.to_string();
        let env = [
            ("MESHREFINE_PROGRESS_AFTER", "0"),
            ("MESHREFINE_MAX_CAPTURE_BYTES", bytes.as_str()),
        ];
        let loud = run(&many, &env);
        let lines: Vec<&str> = loud.lines().filter(|l| l.starts_with("export:")).collect();
        assert_eq!(
            lines.first(),
            Some(&"export: 1/7 passes (3 of 20 elements)"),
            "{loud}"
        );
        assert!(
            lines.contains(&"export: 7/7 passes (20 of 20 elements)"),
            "{loud}"
        );
        assert!(
            lines.iter().any(|l| l.starts_with("export: writing, ")),
            "{loud}"
        );
        let last = format!("export: 7 passes, {triangles} triangles, written");
        assert_eq!(lines.last(), Some(&last.as_str()), "{loud}");
        assert!(lines.len() <= 8, "more than a few lines: {loud}");
        assert!(!loud.contains('\r'), "{loud}");
        assert!(
            without_command(&one) == without_command(&many),
            "{driver}: passes change the file"
        );
    }
    for (var, value, says) in [
        (
            "MESHREFINE_PROGRESS_AFTER",
            "soon",
            "MESHREFINE_PROGRESS_AFTER must be a number of seconds, not 'soon'",
        ),
        (
            "MESHREFINE_MAX_CAPTURE_BYTES",
            "0",
            "MESHREFINE_MAX_CAPTURE_BYTES must be a positive number of bytes, not '0'",
        ),
    ] {
        let o = tmp("progress_bad.obj");
        let out = meshrefine_env(&["export", p(&ico), "-o", p(&o)], &[(var, value)]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(says), "{stderr}");
    }
    // One tessellated element past a pass: the level that fits is advised, --level drawing
    // uniformly, --max-level (a power of two, as the draw glides) adaptively. Level 30 makes
    // 1350 triangles of 120 bytes, level 12 216, level 8 96.
    let o = tmp("capture_cap.obj");
    for (extra, advice) in [
        (&["--level", "30"][..], "use --level 12 or lower"),
        (&["--pixel-error", "1"][..], "use --max-level 8 or lower"),
    ] {
        let mut args = vec!["export", p(&ico), "-o", p(&o), "--driver", "tess"];
        args.extend(extra);
        let out = meshrefine_env(&args, &[("MESHREFINE_MAX_CAPTURE_BYTES", "30000")]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("tessellated triangles of one element")
                && stderr.trim_end().ends_with(advice),
            "{stderr}"
        );
    }
}

/// Loop's vertices sum their face's control points: the slow-frame warning counts a face of
/// many (around a vertex of high valence) as that many times a regular face's 12, and says so.
/// A bicone of two valence-500 poles at level 8: 256,000 triangles, about a second on lavapipe,
/// where the triangles alone would say a tenth of that.
#[test]
fn slow_frame_warnings_count_loop_control_points() {
    let obj = common::bicone_obj(500);
    let mesh = tmp("bicone500.obj");
    std::fs::write(&mesh, obj).unwrap();
    let png = tmp("bicone500.png");
    let render = |surface: &str| {
        #[rustfmt::skip]
        let out = meshrefine(&[
            "render", p(&mesh), "-o", p(&png), "--surface", surface, "--level", "8",
            "--width", "64", "--height", "48",
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{surface}: {stderr}");
        stderr
    };
    let stderr = render("loop");
    let warning = stderr
        .lines()
        .find(|l| l.contains("refined triangles per frame"));
    let warning = warning.unwrap_or_else(|| panic!("{stderr}"));
    assert!(
        warning.starts_with("warning: 256000 refined triangles"),
        "{warning}"
    );
    assert!(
        warning.contains("times that on average here: a vertex sums its Loop face's control points, up to 506 on this mesh against 12 on a regular face); a lower --level draws faster"),
        "{warning}"
    );
    // As PN: 1000 elements of 64 triangles, no warning.
    let stderr = render("pn");
    assert!(!stderr.contains("refined triangles per frame"), "{stderr}");
}

/// `scripts/demo.sh` passes its arguments to `view` and keeps only the defaults they do not
/// replace (docs/window.md's example `--surface pn --wireframe both`; `--level` instead of the
/// pixel error), and `view` accepts what it passes.
#[test]
fn demo_script_arguments_replace_its_defaults() {
    let demo = |args: &[&str]| -> Vec<String> {
        let out = Command::new("bash")
            .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/demo.sh"))
            .args(args)
            .env("MESHREFINE_DEMO_PRINT", "1")
            .output()
            .expect("run bash");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(String::from)
            .collect()
    };
    let joined = |v: Vec<String>| v.join(" ");
    assert_eq!(
        joined(demo(&[])),
        "--surface loop --wireframe cage --pixel-error 1"
    );
    assert_eq!(
        joined(demo(&["--surface", "pn", "--wireframe", "both"])),
        "--pixel-error 1 --surface pn --wireframe both"
    );
    assert_eq!(
        joined(demo(&["--surface=flat", "--level", "2", "x.obj"])),
        "--wireframe cage --surface=flat --level 2 x.obj"
    );
    assert_eq!(
        joined(demo(&["--lod", "--wireframe=both"])),
        "--surface loop --lod --wireframe=both"
    );
    // After `--`, arguments are not options.
    assert_eq!(
        joined(demo(&["--", "--surface"])),
        "--surface loop --wireframe cage --pixel-error 1 -- --surface"
    );
    let png = tmp("demo.png");
    let mut args = demo(&["--surface", "pn", "--wireframe", "both"]);
    args.extend(
        [
            "--width",
            "64",
            "--height",
            "36",
            "--headless-output",
            p(&png),
        ]
        .map(String::from),
    );
    let mut view = vec!["view"];
    view.extend(args.iter().map(String::as_str));
    let out = ok(&view);
    assert!(out.contains("adaptive at 1 px"), "{out}");
}

/// Where a mesh's normal field vanishes (corner normals pointing opposite ways: a fold whose
/// computed normals cancel, a pentagram (a polygon crossing itself, fanned), explicit opposite
/// normals), every exported normal is still unit length and every position finite, on every
/// surface, displaced or not (the field is what displacement moves along).
#[test]
fn vanishing_normal_fields_export_unit_normals() {
    let fold = write(
        "fold.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 1 4\n",
    );
    let mut star = String::new();
    for k in 0..5 {
        let a = k as f64 * 0.8 * std::f64::consts::PI;
        star += &format!("v {} {} 0\n", a.cos(), a.sin());
    }
    star += "f 1 2 3 4 5\n";
    let star = write("star.obj", star.as_bytes());
    let opposite = write(
        "opposite.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//2 3//1\n",
    );
    let out = tmp("vanishing.obj");
    let runs: [(&Path, &str, &str, &str); 8] = [
        (&fold, "flat", "sine", "pattern"),
        (&fold, "pn", "none", "tess"),
        (&fold, "loop", "sine", "pattern"),
        (&star, "phong", "noise", "pattern"),
        (&star, "loop", "none", "tess"),
        (&opposite, "stpn", "sine", "tess"),
        (&opposite, "pn", "noise", "pattern"),
        (&opposite, "flat", "none", "pattern"),
    ];
    for (mesh, surface, displace, driver) in runs {
        let args = [
            "export",
            p(mesh),
            "--surface",
            surface,
            "--displace",
            displace,
            "--driver",
            driver,
            "--level",
            "4",
            "-o",
            p(&out),
        ];
        ok(&args);
        let text = std::fs::read_to_string(&out).unwrap();
        let mut normals = 0;
        for line in text.lines() {
            let values = |tag: &str| -> Option<Vec<f32>> {
                let rest = line.strip_prefix(tag)?;
                Some(
                    rest.split_whitespace()
                        .map(|x| x.parse().unwrap())
                        .collect(),
                )
            };
            if let Some(v) = values("v ") {
                assert!(v.iter().all(|x| x.is_finite()), "{args:?}: {line}");
            } else if let Some(n) = values("vn ") {
                let length = n.iter().map(|x| x * x).sum::<f32>().sqrt();
                assert!((length - 1.0).abs() < 1e-3, "{args:?}: {line}");
                normals += 1;
            }
        }
        assert!(normals > 0, "{args:?}: no normals written");
    }
}

/// The README's quick start, every `meshrefine` line of it run as shown (comments aside) from a
/// folder holding the repository's `assets`, with no display: so its `view` lines render
/// headlessly (the window's own tests are tests/window.rs). Each ends with status 0 and no
/// validation message, writes what it names, and `export`'s file for a camera carries its
/// header lines.
#[test]
fn the_readme_quick_start_runs_as_shown() {
    let readme = include_str!("../README.md");
    let start = readme.find("## Quick start").expect("no quick start");
    let lines: Vec<&str> = readme[start..]
        .split("```")
        .nth(3)
        .expect("no second block")
        .lines()
        .map(|l| l.split(" # ").next().unwrap().trim())
        .filter(|l| l.starts_with("meshrefine "))
        .collect();
    assert!(lines.len() >= 15, "{lines:?}");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let assets = model_path("spot_tri.obj");
    let assets = assets.parent().unwrap().parent().unwrap();
    std::os::unix::fs::symlink(assets, dir.join("assets")).unwrap();
    for line in &lines {
        let args: Vec<&str> = line.split_whitespace().skip(1).collect();
        let out = {
            let _guard = common::gpu_lock();
            bin()
                .args(&args)
                .current_dir(&dir)
                .env_remove("DISPLAY")
                .env_remove("WAYLAND_DISPLAY")
                .output()
                .expect("run meshrefine")
        };
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{line}: {stderr}");
        assert!(!stderr.contains("validation"), "{line}: {stderr}");
        // What it writes is there: `-o FILE`, `--out PREFIX`'s three files.
        if let Some(i) = args.iter().position(|a| *a == "-o") {
            assert!(dir.join(args[i + 1]).is_file(), "{line}");
        }
        if let Some(i) = args.iter().position(|a| *a == "--out") {
            for ext in ["md", "csv", "json"] {
                assert!(
                    dir.join(format!("{}.{ext}", args[i + 1])).is_file(),
                    "{line}"
                );
            }
        }
    }
    let close = std::fs::read_to_string(dir.join("close.obj")).unwrap();
    assert!(close.contains("\n# camera eye ") && close.contains("\n# levels "));
    assert!(dir.join("meshrefine-view.png").is_file());
}
