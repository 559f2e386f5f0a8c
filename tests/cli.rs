//! The command line, run as a user would: bad input gets one clear sentence and a non-zero exit
//! status, never a panic, a hang or a validation message; good input works with the validation
//! layer on (`--validate` makes any validation message or leak an error).

mod common;

use common::model_path;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The binary, with the validation layer on for every GPU run (a validation message then fails
/// the command, see `check_messages` in main.rs).
fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_meshrefine"));
    c.env("MESHREFINE_VALIDATE", "1");
    c
}

fn meshrefine(args: &[&str]) -> Output {
    let _guard = common::gpu_lock();
    bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("run meshrefine")
}

/// An export's text without its `# command:` line (which names its own output path).
fn without_command(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("# command: "))
        .collect();
    assert!(
        kept.len() < text.lines().count(),
        "no command line in {}",
        path.display()
    );
    kept.join("\n")
}

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn write(name: &str, text: &[u8]) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs and expects failure with exactly one `error: ...` line containing every `needles` entry.
fn expect_error(args: &[&str], needles: &[&str]) {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "{args:?} succeeded; stderr: {stderr}"
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{args:?}: exit status {:?}; stderr: {stderr}",
        out.status
    );
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert!(
        !stderr.contains("validation"),
        "{args:?}: validation message: {stderr}"
    );
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(
        errors.len(),
        1,
        "{args:?}: expected one error line, got: {stderr}"
    );
    for n in needles {
        assert!(
            errors[0].contains(n),
            "{args:?}: error line lacks {n:?}: {}",
            errors[0]
        );
    }
}

fn ok(args: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Every exported face winds counter-clockwise around its vertex normals (outward on a sphere).
fn assert_faces_agree_with_normals(mesh: &meshrefine::mesh::Mesh) {
    for t in &mesh.triangles {
        let [a, b, c] = t.p.map(|i| mesh.positions[i as usize]);
        let n: glam::Vec3 = t.n.iter().map(|&i| mesh.normals[i as usize]).sum();
        assert!(
            (b - a).cross(c - a).dot(n) > 0.0,
            "face {t:?} winds against its normals"
        );
    }
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

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
fn device_limits_and_options_are_checked() {
    let out = tmp("limits.png");
    // lavapipe's maxTessellationGenerationLevel is 64.
    expect_error(
        &[
            "render",
            "--driver",
            "tess",
            "--level",
            "65",
            "-o",
            p(&out),
            "--width",
            "64",
            "--height",
            "64",
        ],
        &[
            "65",
            "maxTessellationGenerationLevel",
            // The one level policy's sentence (`driver::check_level`), as for --max-level.
            "level 65 is beyond this device's maxTessellationGenerationLevel (64): the tess driver cannot draw it (use a level up to 64, or the pattern driver, which this limit does not bind)",
        ],
    );
    // A benchmark that can draw none of its variants fails, saying why.
    expect_error(
        &[
            "bench",
            p(&model_path("tetrahedron.obj")),
            "--levels",
            "128",
            "--drivers",
            "tess",
            "--frames",
            "1",
        ],
        &[
            "nothing was measured",
            "level 128 is beyond this device's maxTessellationGenerationLevel (64)",
        ],
    );
    // An export at a level whose capture is also too large says the level first.
    let obj = tmp("tess1024.obj");
    let tet = model_path("tetrahedron.obj");
    expect_error(
        &[
            "export",
            p(&tet),
            "--driver",
            "tess",
            "--level",
            "1024",
            "-o",
            p(&obj),
        ],
        &["level 1024 is beyond this device's maxTessellationGenerationLevel (64)"],
    );
    let spot_tri = model_path("spot_tri.obj");
    let too_big = [
        "render",
        p(&spot_tri),
        "--driver",
        "static",
        "--level",
        "512",
        "-o",
        p(&out),
    ];
    expect_error(&too_big, &["maxMemoryAllocationSize", "level 512"]);
    // Refused before the warning that such frames would be slow: one sentence.
    let stderr = String::from_utf8_lossy(&meshrefine(&too_big).stderr).into_owned();
    assert!(!stderr.contains("warning"), "{stderr}");
    expect_error(
        &["render", "--device", "no-such-gpu-anywhere", "-o", p(&out)],
        &["no-such-gpu-anywhere", "available"],
    );
    // An image side outside 1..=16384 is a usage error (clap: status 2) in every command.
    for command in [
        &["render", "-o", p(&out)][..],
        &["view", "--headless-output", p(&out)],
        &["export", "-o", "x.obj"],
        &["info"],
        &["bench"],
    ] {
        for bad in [["--width", "0"], ["--height", "16385"]] {
            let args: Vec<&str> = command.iter().chain(&bad).copied().collect();
            let out = meshrefine(&args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
            assert!(
                stderr.contains(&format!("invalid value '{}' for '{}", bad[1], bad[0])),
                "{args:?}: {stderr}"
            );
        }
    }
    // lavapipe's largest image (16384 per side) at its default 4 samples per pixel: 4 GiB per
    // attachment, over its 2 GiB maxMemoryAllocationSize; refused before anything is allocated.
    expect_error(
        &["render", "-o", p(&out), "--width", "16384", "--height", "16384"],
        &[
            "a 16384x16384 image at 4 sample(s) per pixel needs 4096 MiB per attachment, over the 2048 MiB this device allocates at once (maxMemoryAllocationSize): fewer samples per pixel (--msaa) or a smaller image fits",
        ],
    );
    // export offers only the drivers whose evaluation can be read back (clap: exit status 2).
    let out = meshrefine(&["export", "--driver", "static", "-o", "s.obj"]);
    assert_eq!(out.status.code(), Some(2));
    // clap rejects a level outside 1..=1024 before anything runs.
    let out = meshrefine(&["render", "--level", "0", "-o", "x.png"]);
    assert_eq!(out.status.code(), Some(2));
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
            stderr.contains("no Vulkan device matches --device 'no-such-gpu'"),
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
fn bench_reports_every_variant_with_ratios() {
    let tet = model_path("tetrahedron.obj");
    let args = [
        "--validate",
        "bench",
        p(&tet),
        "--levels",
        "2,4",
        "--frames",
        "1",
        "--width",
        "64",
        "--height",
        "64",
    ];
    // Outputs never create folders: the test makes it.
    std::fs::create_dir_all(tmp("bench-out")).unwrap();
    let prefix = tmp("bench-out/tet");
    let mut args = args.to_vec();
    args.extend(["--out", p(&prefix)]);
    let s = ok(&args);
    let md = std::fs::read_to_string(tmp("bench-out/tet.md")).unwrap();
    assert!(
        md.starts_with("Command: `meshrefine --validate bench"),
        "{md}"
    );
    let csv = std::fs::read_to_string(tmp("bench-out/tet.csv")).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + 2 * 5,
        "header + 2 levels x 5 variants:\n{csv}"
    );
    assert!(std::fs::read_to_string(tmp("bench-out/tet.json"))
        .unwrap()
        .contains("\"rows\""));
    assert!(s.contains("llvmpipe") || s.contains("Device:"), "{s}");
    // The terminal gets the summary, every line within 120 characters, and where the full
    // table went (its path on a line of its own, whole).
    let path = format!("{}.md", prefix.display());
    assert!(s.lines().any(|l| l == path), "{s}");
    let mut others = s.lines().filter(|l| *l != path);
    assert!(others.all(|l| l.chars().count() <= 120), "{s}");
    let (header, rows) = summary_table(&s);
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    for variant in [
        "static",
        "pattern/push",
        "pattern/ubo",
        "pattern/instanced",
        "tess",
    ] {
        let in_summary = rows.iter().filter(|r| r[column("variant")] == variant);
        assert_eq!(
            in_summary.count(),
            2,
            "{variant}: one row per level in\n{s}"
        );
        let in_table = md.lines().filter(|l| l.contains(&format!("| {variant} |")));
        assert_eq!(in_table.count(), 2, "{variant}: one row per level in\n{md}");
    }
    // static is the reference of the ratios.
    let mut statics = rows.iter().filter(|r| r[column("variant")] == "static");
    assert!(statics.all(|r| r[column("vs static")] == "1.00"), "{s}");
    assert!(
        md.lines()
            .filter(|l| l.contains("| static |"))
            .all(|l| l.contains("| 1.00 | 1.00 |")),
        "{md}"
    );
}

/// `bench --view plain` times frames drawn in one unlit colour and says so above the table and
/// in the JSON; the default is the lit surface, and the JSON says that too.
#[test]
fn bench_view_plain_is_recorded() {
    let tet = model_path("tetrahedron.obj");
    std::fs::create_dir_all(tmp("bench-view")).unwrap();
    for (view, note) in [("plain", true), ("shaded", false)] {
        let prefix = tmp(&format!("bench-view/{view}"));
        let mut args = vec![
            "--validate",
            "bench",
            p(&tet),
            "--surfaces",
            "pn",
            "--drivers",
            "static,tess",
            "--levels",
            "2",
            "--frames",
            "1",
            "--width",
            "64",
            "--height",
            "64",
            "--out",
            p(&prefix),
        ];
        if view == "plain" {
            args.extend(["--view", "plain"]);
        }
        ok(&args);
        let md = std::fs::read_to_string(format!("{}.md", prefix.display())).unwrap();
        assert_eq!(
            md.contains("the `plain` view: one colour, unlit"),
            note,
            "{md}"
        );
        let json = std::fs::read_to_string(format!("{}.json", prefix.display())).unwrap();
        assert!(json.contains(&format!("\"view\":\"{view}\"")), "{json}");
    }
}

/// The header and rows of `bench`'s summary table: the line above the rule of dashes, split
/// at runs of two or more spaces, and the lines below it up to the first blank one.
fn summary_table(s: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let lines: Vec<&str> = s.lines().collect();
    let rule = lines
        .iter()
        .position(|l| l.starts_with("---") && l.chars().all(|c| c == '-' || c == ' '))
        .unwrap_or_else(|| panic!("no summary table in\n{s}"));
    let header = lines[rule - 1]
        .split("  ")
        .map(str::trim)
        .filter(|h| !h.is_empty())
        .map(str::to_owned)
        .collect();
    let rows = lines[rule + 1..]
        .iter()
        .take_while(|l| !l.is_empty())
        .map(|l| l.split_whitespace().map(str::to_owned).collect())
        .collect();
    (header, rows)
}

// ---- Issue 7: what a hostile user found -------------------------------------------------------

/// Runs meshrefine with the given stdout and stderr.
fn meshrefine_with(args: &[&str], stdout: Stdio, stderr: Stdio) -> std::process::ExitStatus {
    let _guard = common::gpu_lock();
    bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stdout(stdout)
        .stderr(stderr)
        .status()
        .expect("run meshrefine")
}

/// Runs with stdout on a pipe whose reading end is closed before meshrefine writes anything.
fn with_closed_stdout(args: &[&str]) -> Output {
    let _guard = common::gpu_lock();
    let mut child = bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("RUST_BACKTRACE", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run meshrefine");
    drop(child.stdout.take());
    child.wait_with_output().expect("wait for meshrefine")
}

/// Waits at most `limit` for a child, killing it if it is still running then.
fn wait_at_most(mut child: std::process::Child, limit: Duration) -> Option<Output> {
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().expect("poll meshrefine").is_some() {
            return Some(child.wait_with_output().expect("collect meshrefine"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().ok();
    child.wait().ok();
    None
}

fn stdout_commands() -> Vec<Vec<String>> {
    let cube = model_path("cube_tri.obj").display().to_string();
    let tet = model_path("tetrahedron.obj").display().to_string();
    let png = tmp("stdout.png").display().to_string();
    let obj = tmp("stdout.obj").display().to_string();
    let small = ["--width", "32", "--height", "32"];
    let mut render = vec!["render", &cube, "-o", &png, "--level", "2"];
    render.extend(small);
    let mut bench = vec!["bench", &tet, "--levels", "2", "--frames", "1"];
    bench.extend(small);
    [
        vec!["info", &cube, "--level", "4"],
        render,
        vec!["export", &cube, "-o", &obj, "--level", "2"],
        bench,
        vec!["--help"],
    ]
    .iter()
    .map(|a| a.iter().map(|s| s.to_string()).collect())
    .collect()
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
    // A full stderr while warning: warnings are dropped, the command still succeeds.
    let degenerate = model_path("degenerate_faces.obj");
    let full = || Stdio::from(std::fs::File::create("/dev/full").unwrap());
    let status = meshrefine_with(&["info", p(&degenerate)], Stdio::null(), full());
    assert_eq!(status.code(), Some(0));
    // ... and an error still gives status 1 (not a panic's 101).
    let status = meshrefine_with(&["info", "no-such.obj"], Stdio::null(), full());
    assert_eq!(status.code(), Some(1));
}

#[test]
fn unbounded_inputs_are_refused_up_front() {
    let start = Instant::now();
    expect_error(&["info", "/dev/zero"], &["/dev/zero", "character device"]);
    expect_error(
        &["info", "/dev/urandom"],
        &["/dev/urandom", "character device"],
    );
    let dir = tmp("a-directory.obj");
    std::fs::create_dir_all(&dir).unwrap();
    expect_error(&["info", p(&dir)], &["a-directory.obj", "directory"]);
    // 20 GB of NUL bytes, sparse: refused by its size without reading.
    let huge = tmp("huge-sparse.obj");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(20 << 30).unwrap();
    drop(f);
    expect_error(
        &["info", p(&huge)],
        &["huge-sparse.obj", "21474836480 bytes", "1073741824"],
    );
    std::fs::remove_file(&huge).ok();
    // Under the limit, 512 MB of NUL bytes: refused at the first chunk.
    let zeros = tmp("zeros.obj");
    let f = std::fs::File::create(&zeros).unwrap();
    f.set_len(512 << 20).unwrap();
    drop(f);
    expect_error(
        &["render", p(&zeros), "-o", "z.png"],
        &["zeros.obj", "line 1", "NUL"],
    );
    std::fs::remove_file(&zeros).ok();
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "{:?}",
        start.elapsed()
    );
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

/// A regular tetrahedron's vertices scaled by `scale` and moved by `offset`, as OBJ text.
fn tetrahedron(scale: f64, offset: f64) -> String {
    let mut s = String::new();
    for v in [
        [1.0, 1.0, 1.0],
        [-1.0, -1.0, 1.0],
        [-1.0, 1.0, -1.0],
        [1.0, -1.0, -1.0],
    ] {
        let c = v.map(|c: f64| (c * scale + offset) as f32);
        s += &format!("v {:e} {:e} {:e}\n", c[0], c[1], c[2]);
    }
    s + "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n"
}

/// Pixels of a PNG written by meshrefine that are not the clear colour.
fn covered(png_path: &Path) -> usize {
    let decoder = png::Decoder::new(std::fs::File::open(png_path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgba).unwrap();
    rgba.truncate(info.buffer_size());
    meshrefine::render::covered_pixels(&meshrefine::gpu::Readback {
        width: info.width,
        height: info.height,
        rgba,
    })
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

/// A value out of its range is refused even where nothing drawn reads the option: one error,
/// never a warning that it is ignored before it (the value shown as typed).
#[test]
fn bad_values_of_unread_options_are_refused_alone() {
    let tet = model_path("tetrahedron.obj");
    for (option, value, needle) in [
        ("--alpha", "7", "--alpha 7 is not within [0, 1]"),
        ("--octaves", "99", "--octaves 99 is not within [1, 8]"),
        (
            "--crease-angle",
            "nan",
            "--crease-angle nan is not within (0, 180) degrees",
        ),
        (
            "--crease-angle",
            "1e-50",
            "--crease-angle 1e-50 is not within (0, 180) degrees",
        ),
    ] {
        let args = ["info", p(&tet), option, value];
        expect_error(&args, &[needle]);
        let stderr = String::from_utf8_lossy(&meshrefine(&args).stderr).into_owned();
        assert!(!stderr.contains("warning"), "{stderr}");
    }
}

/// An `--eye` at the default camera's target names that target as the default's, not as a
/// `--look-at` never given; so does a `--look-at` at the default eye. Read back from `info`'s
/// line, the point maps into the drawn frame a rounding away from the default's on some meshes
/// (a single triangle, the octahedron): still no view direction, in every command, rather than
/// one made of rounding (an export wrote such a camera in its header).
#[test]
fn an_eye_on_the_default_target_names_the_default() {
    let tri = write("eye-tri.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let size = ["--width", "160", "--height", "90"];
    for mesh in [
        model_path("tetrahedron.obj"),
        model_path("octahedron.obj"),
        tri,
    ] {
        let mut args = vec!["info", p(&mesh), "--pixel-error", "1"];
        args.extend(size);
        let info = ok(&args);
        let point = |after: &str| {
            let rest = info.split(after).nth(1).unwrap();
            rest.split(',').next().unwrap().replace(' ', ",")
        };
        let (eye, target) = (point(" eye "), point(", look-at "));
        let out = tmp("eye-on-target.obj");
        let commands: [&[&str]; 4] = [
            &["render"],
            &["export", "-o", p(&out), "--pixel-error", "1"],
            &["info", "--pixel-error", "1"],
            // bench fits its camera once it has the device: the same sentence then.
            &[
                "bench",
                "--pixel-error",
                "1",
                "--surfaces",
                "pn",
                "--drivers",
                "static",
                "--frames",
                "1",
            ],
        ];
        for command in commands {
            let on_target = format!("--eye={target}");
            let mut args = vec![command[0], p(&mesh), &on_target];
            args.extend(&command[1..]);
            args.extend(size);
            expect_error(
                &args,
                &[&format!(
                    "--eye {target} and the default camera's target ({target}) give no view direction"
                )],
            );
            let on_eye = format!("--look-at={eye}");
            args[2] = &on_eye;
            expect_error(
                &args,
                &[&format!(
                    "the default camera's eye ({eye}) and --look-at {eye} give no view direction"
                )],
            );
        }
    }
}

/// Where several surfaces are timed, each with its own fitted camera, a `--look-at` at one's
/// default eye names the surface whose camera it was; with both points given, no surface.
#[test]
fn bench_names_the_fitted_camera_of_several_surfaces() {
    let info = ok(&[
        "info",
        "--pixel-error",
        "1",
        "--width",
        "32",
        "--height",
        "18",
    ]);
    let rest = info.split(" eye ").nth(1).unwrap();
    let eye = rest.split(',').next().unwrap().replace(' ', ",");
    let bench = [
        "bench",
        "--frames",
        "1",
        "--levels",
        "2",
        "--drivers",
        "static",
    ];
    let size = ["--width", "32", "--height", "18", "--surfaces", "pn,flat"];
    let on_eye = format!("--look-at={eye}");
    let args: Vec<&str> = bench
        .iter()
        .chain(&size)
        .copied()
        .chain([on_eye.as_str()])
        .collect();
    expect_error(
        &args,
        &[&format!(
            "the default camera's eye ({eye}) and --look-at {eye} give no view direction: they are the same point (the camera fitted to the pn surface)"
        )],
    );
    let both = ["--eye", "0,0,0", "--look-at", "0,1e-5,0"];
    let args: Vec<&str> = bench.iter().chain(&size).chain(&both).copied().collect();
    expect_error(
        &args,
        &["--eye 0,0,0 and --look-at 0,1e-5,0 give no view direction: they are too close together for one"],
    );
    let out = meshrefine(&args);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("fitted"));
}

/// `bench` refuses a surface and displacement that cannot go together before timing anything
/// (with no Vulkan driver at all, its sentence, not the driver's), whatever else it times.
#[test]
fn bench_refuses_incompatible_displacements_up_front() {
    let env = [("VK_DRIVER_FILES", "/nonexistent/no-driver.json")];
    let grid = model_path("grid_uv_8x8.obj");
    let spot_heightmap = ["bench", "--displacements", "none,sine,heightmap"];
    let loop_heightmap = [
        "bench",
        p(&grid),
        "--surfaces",
        "pn,loop",
        "--displacements",
        "heightmap",
    ];
    let cases: [(&[&str], &str); 2] = [
        (
            &spot_heightmap,
            "cannot benchmark 'the default mesh (spot)': the mesh has no texture coordinates (vt on every face): the heightmap displacement reads the map there",
        ),
        (
            &loop_heightmap,
            "the loop surface has no texture coordinates: the heightmap displacement needs them (leave loop out of --surfaces, or heightmap out of --displacements)",
        ),
    ];
    for (command, needle) in cases {
        let mut args = command.to_vec();
        args.extend(["--frames", "1", "--levels", "2"]);
        let out = meshrefine_env(&args, &env);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(needle), "{stderr}");
    }
}

/// An `--eye` and a `--look-at` both given, a hair apart (well under `1e-4` radii of the
/// surface): no view direction, rather than one made of rounding.
#[test]
fn an_eye_a_hair_from_the_look_at_gives_no_direction() {
    let png = tmp("hair.png");
    #[rustfmt::skip]
    expect_error(
        &[
            "render", "-o", p(&png), "--width", "64", "--height", "48", "--eye", "0.1,0.2,0.3",
            "--look-at", "0.1,0.2,0.30001",
        ],
        &["--eye 0.1,0.2,0.3 and --look-at 0.1,0.2,0.30001 give no view direction: they are too close together for one"],
    );
    // Points named as typed, not as they read back.
    expect_error(
        &[
            "info",
            "--pixel-error",
            "1",
            "--eye",
            "1.0,2,3e0",
            "--look-at",
            "1,2.0,3",
        ],
        &["--eye 1.0,2,3e0 and --look-at 1,2.0,3 give no view direction: they are the same point"],
    );
    expect_error(
        &["info", "--pixel-error", "1", "--eye", "1.0e13,0,0"],
        &["--eye 1.0e13,0,0 is 7.3e12 bounding radii from the mesh's centre"],
    );
}

/// `bench` goes on past a row whose mesh the device cannot hold (the static driver refined at
/// level 1024: gigabytes), as past a level it refuses: the row says why, the others are timed,
/// the run succeeds.
#[test]
fn bench_goes_on_past_a_row_the_device_cannot_hold() {
    #[rustfmt::skip]
    let out = ok(&[
        "bench", "--levels", "1,1024", "--drivers", "static", "--frames", "1", "--width", "32",
        "--height", "32",
    ]);
    let out = out.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        out.contains("static: not drawn: the static driver's refined mesh at level 1024 needs"),
        "{out}"
    );
}

/// A camera farther from the mesh than supported is refused before any GPU work: with no
/// Vulkan driver at all, the camera's sentence, not the driver's (an adaptive export; render).
#[test]
fn a_camera_too_far_is_refused_before_the_device() {
    let env = [("VK_DRIVER_FILES", "/nonexistent/no-driver.json")];
    let out = tmp("far-camera.obj");
    let commands: [&[&str]; 2] = [
        &["render", "-o", "/tmp/meshrefine-far-camera.png"],
        &["export", "-o", p(&out), "--pixel-error", "1"],
    ];
    for command in commands {
        let mut args = command.to_vec();
        args.extend(["--eye", "2e12,0,0"]);
        let out = meshrefine_env(&args, &env);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("--eye 2e12,0,0 is") && stderr.contains("bounding radii"),
            "{stderr}"
        );
        assert!(!stderr.contains("Vulkan driver"), "{stderr}");
    }
}

/// `--help` groups every option of a command under a heading of its own (docs/cli.md): only
/// the global options and `--help` are left under the plain "Options".
#[test]
fn help_groups_every_option_under_a_heading() {
    // The headings docs/cli.md names ("Options"), each command's under its own name.
    let named = [
        "Output:",
        "Surface and displacement:",
        "Surface parameters:",
        "Driver and level:",
        "Window:",
        "Measurement:",
        "Camera:",
        "Camera (with --pixel-error):",
        "Adaptive drawing:",
    ];
    let mut seen = std::collections::BTreeSet::new();
    for command in ["render", "view", "export", "info", "bench", "devices"] {
        let out = meshrefine(&[command, "--help"]);
        assert!(out.status.success());
        let help = String::from_utf8_lossy(&out.stdout);
        // `meshrefine help COMMAND` prints the same.
        let help_command = meshrefine(&["help", command]);
        assert!(help_command.status.success());
        assert_eq!(help_command.stdout, out.stdout, "help {command}");
        let mut heading = "";
        for line in help.lines() {
            if !line.starts_with(' ') && line.ends_with(':') {
                heading = line;
                let plain = ["Usage:", "Arguments:", "Options:"].contains(&line);
                assert!(
                    plain || named.contains(&line),
                    "{command}: heading {line} is not among docs/cli.md's"
                );
                seen.insert(line.to_string());
            } else if let Some(option) = (line.split_whitespace())
                .find(|w| w.starts_with("--"))
                .filter(|_| line.trim_start().starts_with('-'))
            {
                let global = ["--validate", "--device", "--help"].contains(&option);
                assert!(
                    heading != "Options:" || global,
                    "{command}: {option} under the plain Options heading:\n{help}"
                );
            }
        }
    }
    for heading in named {
        assert!(seen.contains(heading), "no command's help has {heading}");
    }
}

#[test]
fn view_help_lists_the_window_keys() {
    let out = meshrefine(&["view", "--help"]);
    assert!(out.status.success());
    let words = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let help = words(&String::from_utf8_lossy(&out.stdout));
    assert!(help.contains(&words(meshrefine::app::KEY_HELP)), "{help}");
    for option in [
        "--width",
        "--fullscreen",
        "--background",
        "--screenshot-dir",
    ] {
        assert!(help.contains(option), "{option}: {help}");
    }
}

#[test]
fn meaningless_requests_are_refused() {
    let cube = model_path("cube_tri.obj");
    let jpg = tmp("x.jpg");
    expect_error(&["render", p(&cube), "-o", p(&jpg)], &["x.jpg", ".png"]);
    assert!(!jpg.exists());
    let not_obj = tmp("x.png");
    std::fs::remove_file(&not_obj).ok();
    expect_error(&["export", p(&cube), "-o", p(&not_obj)], &["x.png", ".obj"]);
    assert!(!not_obj.exists());
    expect_error(
        &["view", "--headless-output", "v.jpeg"],
        &["v.jpeg", ".png"],
    );
    expect_error(&["view", "--screenshot", "s.bmp"], &["s.bmp", ".png"]);
    expect_error(
        &["render", p(&cube), "-o", ".png"],
        &["output file '.png' has no name before its .png"],
    );
    // Only a window reads --screenshot-dir (tests/window.rs: a window refuses one that is no
    // folder before it opens): a display named but out of reach falls back to the headless
    // render and ignores it with a warning, as no display named does.
    let shown = tmp("unreachable-display.png");
    std::fs::remove_file(&shown).ok();
    let out = bin()
        .args([
            "view",
            "--screenshot-dir",
            "no/such/dir",
            "--headless-output",
            p(&shown),
        ])
        .args(["--level", "1", "--width", "64", "--height", "48"])
        .env("DISPLAY", ":4242")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        stderr.trim(),
        "warning: --screenshot-dir applies only to the window and is ignored: cannot connect to the display ':4242'"
    );
    assert!(shown.exists());
    // Zero frames, or more than bench keeps times for (100000): clap refuses the value (usage
    // error, status 2); a negative number is a value
    // clap's range refuses as such, not an unexpected argument.
    for (args, value) in [
        (vec!["bench", "--frames", "0"], "'0'"),
        (vec!["bench", "--frames", "4000000000"], "1..=100000"),
        (vec!["view", "--frames", "0"], "'0'"),
        (
            vec!["info", "--level", "-3"],
            "invalid value '-3' for '--level",
        ),
        (
            vec!["bench", "--levels", "-1e-30"],
            "invalid value '-1e-30'",
        ),
        // No whole number at all is the parser's to refuse; its range is the command's (above).
        (
            vec!["render", "--octaves", "abc"],
            "invalid value 'abc' for '--octaves <OCTAVES>': not a whole number",
        ),
        (
            vec!["render", "--octaves", "2.5"],
            "invalid value '2.5' for '--octaves <OCTAVES>': not a whole number",
        ),
    ] {
        let out = meshrefine(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(stderr.contains(value), "{args:?}: {stderr}");
        assert!(stderr.contains("try '--help'"), "{args:?}: {stderr}");
    }
    // An empty value is named as such, whatever the option takes.
    for (command, option, value, what) in [
        ("render", "--octaves", " ", "an empty value"),
        ("render", "--pixel-error", "", "an empty value"),
        ("render", "--eye", " ", "an empty value"),
        ("info", "--device", "", "an empty value"),
        ("bench", "--drivers", "tess,", "an empty item in the list"),
    ] {
        let out = meshrefine(&[command, option, value]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{option} {value:?}");
        let bad = if value.contains(',') { "" } else { value };
        let placeholder = option
            .trim_start_matches('-')
            .to_uppercase()
            .replace('-', "_");
        let placeholder = if option == "--device" {
            "NAME".into()
        } else {
            placeholder
        };
        let said = format!("invalid value '{bad}' for '{option} <{placeholder}>': {what}");
        assert!(stderr.contains(&said), "{said:?} not in {stderr}");
    }
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

/// Runs and expects success (the error output in the message otherwise).
fn expect_success(args: &[&str]) {
    let out = meshrefine(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Writes an 8-bit grayscale PNG of `w` x `h` pixels into the tests' directory.
fn gray_png(name: &str, w: u32, h: u32, pixels: &[u8]) -> PathBuf {
    let path = tmp(name);
    let mut e = png::Encoder::new(std::fs::File::create(&path).unwrap(), w, h);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::Eight);
    e.write_header().unwrap().write_image_data(pixels).unwrap();
    path
}

/// Runs `export` with `args` (after `export`), expects success, and reloads what it wrote.
fn export_and_reload(obj: &Path, args: &[&str]) -> meshrefine::mesh::Mesh {
    let mut all = vec!["export", "-o", p(obj)];
    all.extend_from_slice(args);
    expect_success(&all);
    meshrefine::mesh::Mesh::load_obj(obj).unwrap().0
}

/// Surface and displacement parameters out of range: one sentence naming the option and the
/// value as typed, exit 1.
#[test]
fn surface_parameters_out_of_range_are_errors() {
    let out = tmp("params.png");
    let o = out.to_str().unwrap();
    for (args, needle) in [
        (&["--alpha", "2"][..], "--alpha 2 is not within [0, 1]"),
        (&["--alpha", "nan"], "--alpha nan is not within [0, 1]"),
        (&["--alpha", "1e3"], "--alpha 1e3 is not within [0, 1]"),
        (&["--bias", "-inf"], "--bias -inf is not a finite number"),
        (&["--octaves", "0"], "--octaves 0 is not within [1, 8]"),
        (&["--octaves", "9"], "--octaves 9"),
        // Negative and past u32 too: the range's sentence, not the parser's.
        (&["--octaves", "-1"], "--octaves -1 is not within [1, 8]"),
        (
            &["--octaves", "99999999999999999999"],
            "--octaves 99999999999999999999 is not within [1, 8]",
        ),
        (
            &["--amplitude", "inf"],
            "--amplitude inf is not a finite number",
        ),
        (
            &["--frequency", "-1"],
            "--frequency -1 is not a finite number >= 0",
        ),
        // A negative exponent is a value too (clap's test of a negative number misses it).
        (
            &["--frequency", "-1e-30"],
            "--frequency -1e-30 is not a finite number >= 0",
        ),
    ] {
        let mut all = vec!["render", "-o", o, "--level", "2"];
        all.extend_from_slice(args);
        expect_error(&all, &[needle]);
    }
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

/// `bench --min-total-ms` must be a finite number of milliseconds >= 0.
#[test]
fn bench_min_total_ms_is_checked() {
    for v in ["nan", "-1", "inf"] {
        expect_error(
            &[
                "bench",
                "--min-total-ms",
                v,
                "--levels",
                "1",
                "--frames",
                "1",
            ],
            &[&format!("--min-total-ms {v} is not a finite number >= 0")],
        );
    }
}

/// `bench --min-total-ms` keeps timing past `--frames` until every variant has that much GPU
/// time, at most 20 x `--frames` frames, and the row's note says how many it took: a total no
/// frame reaches stops at exactly 20 x `--frames`; 0 (the default) takes exactly `--frames`.
#[test]
fn bench_min_total_ms_times_up_to_twenty_times_frames() {
    let tet = model_path("tetrahedron.obj");
    std::fs::create_dir_all(tmp("bench-min-total")).unwrap();
    for (total, note) in [
        (Some("1e12"), "40 timed frames"),
        (Some("0"), ""),
        (None, ""),
    ] {
        let prefix = tmp(&format!("bench-min-total/{}", total.unwrap_or("default")));
        #[rustfmt::skip]
        let mut args = vec![
            "--validate", "bench", p(&tet), "--drivers", "static", "--levels", "2",
            "--frames", "2", "--width", "32", "--height", "32", "--out", p(&prefix),
        ];
        if let Some(total) = total {
            args.extend(["--min-total-ms", total]);
        }
        let s = ok(&args);
        let json = std::fs::read_to_string(format!("{}.json", prefix.display())).unwrap();
        assert!(json.contains("\"frames\":2,"), "{json}");
        assert!(
            json.contains(&format!("\"note\":\"{note}\"")),
            "{total:?}: expected note {note:?} in\n{json}"
        );
        // The terminal's summary notes it under the table.
        let noted = s.contains("static: 40 timed frames");
        assert_eq!(noted, !note.is_empty(), "{total:?}: {s}");
    }
    // With --pixel-error, the adaptive row and the uniform row beside it alike.
    let prefix = tmp("bench-min-total/adaptive");
    #[rustfmt::skip]
    ok(&[
        "--validate", "bench", p(&tet), "--surfaces", "pn", "--drivers", "tess",
        "--pixel-error", "1", "--max-level", "4", "--no-bound-levels", "--levels", "2",
        "--frames", "2", "--min-total-ms", "1e12", "--width", "32", "--height", "32",
        "--out", p(&prefix),
    ]);
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let note = keys.iter().position(|k| k == "note").unwrap();
    let notes: Vec<String> = lines.map(|l| common::csv_fields(l)[note].clone()).collect();
    assert_eq!(notes.len(), 2, "{csv}");
    // The adaptive row, capped at 4, says so first (docs/benchmarks.md, `note`).
    assert!(
        notes[0].starts_with("the bound is not met on every element up to --max-level 4")
            && notes[0].contains("; 40 timed frames")
            && notes[1].starts_with("40 timed frames"),
        "{csv}"
    );
}

/// Runs and expects success; returns standard error's `warning:` lines.
fn warnings_of(args: &[&str]) -> Vec<String> {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .map(str::to_string)
        .collect()
}

/// An option that the chosen surface, displacement or driver does not read is ignored with one
/// warning naming it, what it applies to and what was chosen (one rule for every such option,
/// `--submit`, `--tags` and `--heightmap` included); where something chosen reads it, no word.
#[test]
fn options_that_do_not_apply_warn_and_are_ignored() {
    let tet = model_path("tetrahedron.obj");
    let png = tmp("inapplicable.png");
    let small = ["--width", "32", "--height", "32", "--level", "1"];
    // Every option at once; the files named are never read (they do not exist).
    let given = [
        ("--alpha", "0.5", "--surface phong, not to --surface flat"),
        (
            "--amplitude",
            "1",
            "--displace sine, noise or heightmap, not to --displace none",
        ),
        (
            "--frequency",
            "2",
            "--displace sine or noise, not to --displace none",
        ),
        ("--octaves", "2", "--displace noise, not to --displace none"),
        (
            "--bias",
            "0.1",
            "--displace heightmap, not to --displace none",
        ),
        (
            "--boundary",
            "edge-and-corner",
            "--surface loop, not to --surface flat",
        ),
        ("--bft-level", "3", "--surface loop, not to --surface flat"),
        (
            "--pn-seams",
            "open",
            "--surface phong, pn or stpn, not to --surface flat",
        ),
        (
            "--tags",
            "missing.tags",
            "--surface stpn, not to --surface flat",
        ),
        (
            "--crease-angle",
            "30",
            "--surface stpn, not to --surface flat",
        ),
        (
            "--heightmap",
            "missing.png",
            "--displace heightmap, not to --displace none",
        ),
        ("--submit", "ubo", "--driver pattern, not to --driver tess"),
    ];
    let mut args = vec!["render", p(&tet), "-o", p(&png), "--surface", "flat"];
    args.extend(small);
    args.extend(["--driver", "tess"]);
    for (option, value, _) in given {
        args.extend([option, value]);
    }
    let w = warnings_of(&args);
    assert_eq!(w.len(), given.len(), "{w:#?}");
    for (option, _, what) in given {
        let line = format!("warning: {option} applies only to {what}: it is ignored");
        assert!(w.contains(&line), "no {line:?} in {w:#?}");
    }
    // Where the surface, displacement or driver chosen reads the option: no warning.
    let mut args = vec!["render", p(&tet), "-o", p(&png), "--surface", "phong"];
    args.extend(small);
    args.extend(["--alpha", "0.5", "--displace", "noise", "--octaves", "2"]);
    args.extend(["--submit", "ubo", "--pn-seams", "open"]);
    assert_eq!(warnings_of(&args), Vec::<String>::new());
    let obj = tmp("inapplicable.obj");
    let w = warnings_of(&[
        "export",
        p(&tet),
        "-o",
        p(&obj),
        "--level",
        "1",
        "--driver",
        "tess",
        "--submit",
        "push",
    ]);
    assert_eq!(
        w,
        ["warning: --submit applies only to --driver pattern, not to --driver tess: it is ignored"]
    );
    // bench: an option applies when any surface or displacement listed reads it.
    let bench = [
        "bench",
        p(&tet),
        "--levels",
        "1",
        "--frames",
        "1",
        "--drivers",
        "static",
    ];
    let size = ["--width", "32", "--height", "32"];
    let mut args = [
        bench.as_slice(),
        &size,
        &["--surfaces", "flat,phong", "--alpha", "0.5"],
    ]
    .concat();
    assert_eq!(warnings_of(&args), Vec::<String>::new());
    args.extend(["--octaves", "3"]);
    assert_eq!(
        warnings_of(&args),
        ["warning: --octaves applies only to --displace noise, not to --displacements none: it is ignored"]
    );
    // info reads the loop options only with --surface loop, and reports only for loop.
    let w = warnings_of(&["info", p(&tet), "--bft-level", "3"]);
    assert_eq!(
        w,
        ["warning: --bft-level applies only to --surface loop, not to info without --surface: it is ignored"]
    );
    let w = warnings_of(&[
        "info",
        p(&tet),
        "--surface",
        "pn",
        "--boundary",
        "edge-and-corner",
    ]);
    assert_eq!(
        w,
        [
            "warning: info --surface reports only what --surface loop builds, not --surface pn: it is ignored",
            "warning: --boundary applies only to --surface loop, not to --surface pn: it is ignored"
        ]
    );
}

/// Adaptive options nothing reads warn too: `--geomorph` for the static driver (it refines on
/// the CPU, never glides) or tess under a --max-level that is no power of two (it draws integer
/// levels), `--no-bound-levels` and info's `--driver` without `--pixel-error`; and `view`
/// refuses `--lod` with `--pixel-error` (two ways of choosing levels).
#[test]
fn adaptive_options_nothing_reads_warn() {
    let png = tmp("geomorph-unread.png");
    let small = ["--width", "48", "--height", "32", "-o", p(&png)];
    let render = |extra: &[&str]| warnings_of(&[&["render"], &small[..], extra].concat());
    // info reports levels as render draws them: the same words.
    let info = |extra: &[&str]| warnings_of(&[&["info", "--pixel-error", "1"][..], extra].concat());
    type Warned<'a> = &'a dyn Fn(&[&str]) -> Vec<String>;
    let commands: [Warned; 2] = [&render, &info];
    for run in commands {
        // Either way.
        for g in ["on", "off"] {
            assert_eq!(
                run(&["--driver", "static", "--geomorph", g]),
                ["warning: --geomorph applies only to the pattern and tess drivers, not to the static driver: it is ignored"]
            );
        }
        assert_eq!(
            run(&["--driver", "tess", "--max-level", "12", "--geomorph", "on"]),
            ["warning: --geomorph on: the tess driver glides only under a --max-level that is a power of two; at --max-level 12 it draws integer levels without gliding"]
        );
        // Where it glides, or is off, no word.
        assert!(run(&["--driver", "tess", "--max-level", "16", "--geomorph", "on"]).is_empty());
        assert!(run(&["--driver", "tess", "--max-level", "12", "--geomorph", "off"]).is_empty());
        assert!(run(&["--driver", "pattern", "--geomorph", "off"]).is_empty());
    }
    let bench = [
        "bench",
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
    ];
    assert_eq!(
        warnings_of(&[&bench[..], &["--no-bound-levels"]].concat()),
        ["warning: --no-bound-levels applies only with --pixel-error: it is ignored"]
    );
    assert_eq!(
        warnings_of(&["info", "--driver", "tess"]),
        ["warning: --driver applies only with --pixel-error: it is ignored"]
    );
    expect_error(
        &[
            "view",
            "--lod",
            "--pixel-error",
            "1",
            "--headless-output",
            p(&png),
        ],
        &["--pixel-error and --lod are exclusive"],
    );
}

/// Displacement whose result would not be finite is refused before anything is drawn, naming
/// the option; the default camera frames a displaced surface however far it moves (a blank
/// image then comes only from a camera given on the command line, and says so).
#[test]
fn displacement_that_cannot_be_finite_is_refused_up_front() {
    let ico = model_path("icosahedron.obj");
    let obj = tmp("huge.obj");
    std::fs::remove_file(&obj).ok();
    for (extra, needle) in [
        (
            vec!["--displace", "sine", "--amplitude", "3.4e38"],
            "--amplitude 3.4e38 moves the surface up to",
        ),
        (
            vec!["--displace", "noise", "--amplitude", "-1e30"],
            "--amplitude -1e30 moves the surface",
        ),
        (
            vec!["--displace", "sine", "--frequency", "1e25"],
            "--frequency 1e25 is",
        ),
        // Named as typed, not as the number reads back.
        (
            vec!["--displace", "sine", "--frequency", "1.0e6"],
            "--frequency 1.0e6 is",
        ),
        (
            vec!["--displace", "sine", "--amplitude", "3.40e38"],
            "--amplitude 3.40e38 moves the surface up to",
        ),
        (
            vec![
                "--displace",
                "noise",
                "--frequency",
                "1e5",
                "--octaves",
                "8",
            ],
            "--frequency 1e5 is",
        ),
        (
            vec![
                "--displace",
                "noise",
                "--frequency",
                "1e5",
                "--octaves",
                "8",
            ],
            "with --octaves 8",
        ),
    ] {
        let mut args = vec!["export", p(&ico), "-o", p(&obj), "--level", "2"];
        args.extend(extra);
        expect_error(&args, &[needle, "at most 1e6"]);
        assert!(!obj.exists(), "{args:?} wrote a file");
    }
    // An amplitude not given is the mesh's default, named as such; the bias as typed.
    let grid = model_path("grid_uv_8x8.obj");
    let map = gray_png("default-amplitude.png", 2, 2, &[0, 64, 128, 255]);
    #[rustfmt::skip]
    let args = ["export", p(&grid), "-o", p(&obj), "--level", "2", "--displace", "heightmap",
        "--heightmap", p(&map), "--bias", "1.0e8"];
    expect_error(
        &args,
        &[
            "the default --amplitude ",
            " (3% of the mesh's bounding radius) with --bias 1.0e8 moves the surface",
        ],
    );
    let png = tmp("displaced-away.png");
    let displaced = [
        "render",
        p(&grid),
        "-o",
        p(&png),
        "--width",
        "32",
        "--height",
        "32",
        "--displace",
        "heightmap",
        "--amplitude",
        "0.5",
        "--bias",
        "1e4",
    ];
    let mut uniform = displaced.to_vec();
    uniform.extend(["--level", "1"]);
    let out = ok(&uniform);
    assert!(out.contains("wrote"), "{out}");
    // Looking away from the grid: nothing drawn, the image is blank and the camera blamed.
    let mut away = displaced.to_vec();
    away.extend([
        "--pixel-error",
        "1",
        "--max-level",
        "4",
        "--eye",
        "10,0,0",
        "--look-at",
        "20,0,0",
    ]);
    expect_error(
        &away,
        &[
            "is blank",
            "the camera given by --eye and --look-at sees none of them",
        ],
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

/// One rule for every output path: its folder must exist (never created), a directory is
/// refused, and a prefix output never writes beside a device. All checked before any work.
#[test]
fn outputs_follow_one_rule() {
    let cube = model_path("cube_tri.obj");
    let missing = tmp("no-such-folder");
    std::fs::remove_dir_all(&missing).ok();
    let inside = |f: &str| missing.join(f).display().to_string();
    let dir = tmp("an-output-folder");
    std::fs::create_dir_all(&dir).unwrap();
    let dir_slash = format!("{}/", dir.display());
    for (args, needles) in [
        (
            vec!["render", p(&cube), "-o", &inside("x.png")],
            vec!["-o '", "no-such-folder' does not exist"],
        ),
        (
            vec!["export", p(&cube), "-o", &inside("x.obj")],
            vec!["no-such-folder' does not exist"],
        ),
        (
            vec!["bench", p(&cube), "--out", &inside("x")],
            vec!["--out '", "no-such-folder' does not exist"],
        ),
        (
            vec!["view", p(&cube), "--screenshot", &inside("s.png")],
            vec!["--screenshot '"],
        ),
        (
            vec!["view", p(&cube), "--headless-output", &inside("v.png")],
            vec!["--headless-output '"],
        ),
        (
            vec!["bench", p(&cube), "--out", &dir_slash],
            vec!["is a directory, not a file"],
        ),
        (
            vec!["bench", p(&cube), "--out", p(&dir)],
            vec!["is a directory, not a file"],
        ),
        (
            vec!["render", p(&cube), "-o", &dir_slash],
            vec!["is a directory, not a file"],
        ),
        (
            vec!["bench", p(&cube), "--out", "/dev/full"],
            vec!["'/dev/full' is a character device", "beside it"],
        ),
    ] {
        expect_error(&args, &needles);
    }
    assert!(!missing.exists(), "a folder was created");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "files were written into the folder"
    );
    for ext in ["md", "csv", "json"] {
        assert!(
            !Path::new(&format!("/dev/full.{ext}")).exists(),
            "/dev/full.{ext} was created"
        );
    }
    // A folder that exists but takes no files is found out before anything is timed: no
    // summary on standard output.
    let out = meshrefine(&[
        "bench",
        p(&cube),
        "--levels",
        "1",
        "--out",
        "/proc/self/results",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(
        stderr.contains("--out '/proc/self/results.md': cannot write there"),
        "{stderr}"
    );
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
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

/// An export whose refined size passes the documented limit is refused before anything is
/// evaluated, naming the estimate and the highest level that fits.
#[test]
fn exports_past_the_size_limit_are_refused_up_front() {
    let spot = model_path("spot_tri.obj");
    let obj = tmp("too-big.obj");
    std::fs::remove_file(&obj).ok();
    // 5856 triangles x 1024^2; 2^24 / 5856 fits level 53.
    expect_error(
        &[
            "export",
            p(&spot),
            "-o",
            p(&obj),
            "--level",
            "1024",
            "--surface",
            "flat",
        ],
        &[
            "cannot export '",
            "spot_tri.obj': --level 1024 would export 6140461056 refined triangles",
            "at most 16777216 (2^24)",
            "use --level 53 or lower",
        ],
    );
    // Loop's elements are M1's faces: four per triangle.
    expect_error(
        &[
            "export",
            p(&spot),
            "-o",
            p(&obj),
            "--level",
            "64",
            "--surface",
            "loop",
        ],
        &["(23424 elements x 4096)", "use --level 26 or lower"],
    );
    assert!(!obj.exists());
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

/// `(adaptive triangles, uniform triangles, uniform level, culled, elements in the histogram)`
/// from `info --pixel-error`'s report.
fn adaptive_report(stdout: &str) -> (u64, u64, u32, u64, u64) {
    let line = |start: &str| {
        stdout
            .lines()
            .find(|l| l.trim_start().starts_with(start))
            .unwrap_or_else(|| panic!("no '{start}' line in:\n{stdout}"))
            .to_string()
    };
    let words = |l: String| -> Vec<String> { l.split_whitespace().map(String::from).collect() };
    let t = words(line("refined triangles:"));
    let culled = words(line("culled")).last().unwrap().parse().unwrap();
    let histogram: u64 = words(line("levels ("))[3..]
        .iter()
        .map(|pair| pair.split(':').nth(1).unwrap().parse::<u64>().unwrap())
        .sum();
    (
        t[2].parse().unwrap(),
        t[5].parse().unwrap(),
        t[9].parse().unwrap(),
        culled,
        histogram,
    )
}

#[test]
fn info_reports_adaptive_levels_for_a_camera() {
    let spot = model_path("spot_control_tri.obj");
    let spot = p(&spot);
    // The default camera: every element in view, those facing away culled (Spot is closed and
    // wound outwards: as render culls them), far fewer triangles than the uniform level that
    // meets the same bound everywhere.
    let (adaptive, uniform, level, culled, drawn) = adaptive_report(&ok(&[
        "info",
        spot,
        "--pixel-error",
        "1",
        "--surface",
        "pn",
    ]));
    assert!(culled > 0 && culled + drawn == 372, "{culled} {drawn}");
    let all = ok(&["info", spot, "--pixel-error", "1", "--cull", "off"]);
    assert_eq!(adaptive_report(&all).3, 0);
    assert_eq!(adaptive_report(&all).4, 372);
    assert!(level > 1 && adaptive < uniform, "{adaptive} {uniform}");
    assert_eq!(uniform, 372 * level as u64 * level as u64);
    // A close-up: finer levels near the eye, the rest outside the view culled.
    let close = [
        "info",
        spot,
        "--pixel-error",
        "1",
        "--surface",
        "pn",
        "--eye",
        "0.3,0.2,0.6",
        "--look-at",
        "0,0.1,0.3",
        "--width",
        "1920",
        "--height",
        "1080",
    ];
    let (a2, _, l2, culled2, drawn2) = adaptive_report(&ok(&close));
    assert!(l2 > level, "{l2} {level}");
    assert!(culled2 > 0 && culled2 + drawn2 == 372, "{culled2} {drawn2}");
    assert!(a2 > 0);
    // Four times the pixel error, fewer triangles.
    let (a4, ..) = adaptive_report(&ok(&[
        "info",
        spot,
        "--pixel-error",
        "4",
        "--surface",
        "pn",
    ]));
    assert!(a4 < adaptive, "{a4} {adaptive}");
    // The pattern driver (the default) draws powers of two; tess any integer; both the levels
    // the level pass writes (transition triangles included).
    let pattern_args = ["info", spot, "--pixel-error", "1", "--surface", "pn"];
    let pattern = ok(&pattern_args);
    assert!(pattern.contains("driver pattern"), "{pattern}");
    let tess = ok(&[
        "info",
        spot,
        "--pixel-error",
        "1",
        "--surface",
        "pn",
        "--driver",
        "tess",
        "--max-level",
        "48",
    ]);
    assert!(tess.contains("max level 48, driver tess"), "{tess}");
    let levels_of = |out: &str| -> Vec<u32> {
        let l = out.lines().find(|l| l.contains("levels (")).unwrap();
        (l.split_whitespace().skip(3))
            .map(|pair| pair.split(':').next().unwrap().parse().unwrap())
            .collect()
    };
    assert!(
        levels_of(&pattern).iter().all(|l| l.is_power_of_two()),
        "{pattern}"
    );
    assert!(
        levels_of(&tess).iter().any(|l| !l.is_power_of_two()),
        "{tess}"
    );
    let (.., tess_culled, tess_drawn) = adaptive_report(&tess);
    assert_eq!(tess_culled + tess_drawn, 372);
    // Geomorphing (the default) under a power-of-two largest level, tess draws powers of two,
    // as render does; without it, its integers. Its transitions are the tessellator's, bounded
    // for larger moves than the pattern's snapping makes: higher levels, more triangles.
    let tess_args = ["info", spot, "--pixel-error", "1", "--driver", "tess"];
    let gliding = ok(&tess_args);
    assert!(
        levels_of(&gliding).iter().all(|l| l.is_power_of_two()),
        "{gliding}"
    );
    let triangles = |out: &str| adaptive_report(out).0;
    assert!(
        triangles(&gliding) > triangles(&pattern),
        "{gliding}\n{pattern}"
    );
    // Counted as the tessellator draws them (as bench counts them), not N² an element.
    let tess_count = |out: &str| -> (u64, u64) {
        let l = out.lines().find(|l| l.contains("levels (")).unwrap();
        let (.., culled, drawn) = adaptive_report(out);
        let uniform = adaptive_report(out).2;
        let per = meshrefine::render::tess::tess_triangle_count;
        let adaptive = (l.split_whitespace().skip(3))
            .map(|pair| {
                let (level, n) = pair.split_once(':').unwrap();
                n.parse::<u64>().unwrap() * per(level.parse().unwrap()) as u64
            })
            .sum();
        (adaptive, (culled + drawn) * per(uniform) as u64)
    };
    for out in [&gliding, &tess] {
        let (adaptive, uniform, ..) = adaptive_report(out);
        assert_eq!((adaptive, uniform), tess_count(out), "{out}");
    }
    // The static driver refines on the CPU at integer levels: those the pattern driver draws
    // without geomorphing (non-nested levels cannot glide), fewer triangles than its powers of
    // two.
    let integer_pattern = ok(&[&pattern_args[..], &["--geomorph", "off"]].concat());
    assert!(
        levels_of(&integer_pattern)
            .iter()
            .any(|l| !l.is_power_of_two()),
        "{integer_pattern}"
    );
    assert!(
        triangles(&integer_pattern) < triangles(&pattern),
        "{integer_pattern}\n{pattern}"
    );
    let stat = ok(&[
        "info",
        spot,
        "--pixel-error",
        "1",
        "--surface",
        "pn",
        "--driver",
        "static",
    ]);
    assert!(stat.contains("driver static"), "{stat}");
    assert_eq!(
        adaptive_report(&stat),
        adaptive_report(&integer_pattern),
        "{stat}"
    );
    let integers = ok(&[&tess_args[..], &["--geomorph", "off"]].concat());
    assert!(
        levels_of(&integers).iter().any(|l| !l.is_power_of_two()),
        "{integers}"
    );
    expect_error(
        &["info", spot, "--pixel-error", "1", "--max-level", "48"],
        &["--max-level 48", "power of two"],
    );
    // bench measures every driver unless told: the sentence says how to time tess at 48.
    expect_error(
        &[
            "bench",
            spot,
            "--pixel-error",
            "1",
            "--max-level",
            "48",
            "--frames",
            "1",
        ],
        &[
            "--max-level 48",
            "power of two",
            "--drivers tess takes any level",
        ],
    );
    // Where --max-level keeps the bound from being met, info says on how many elements.
    assert!(!pattern.contains("capped"), "{pattern}");
    let pn = |px: &str, extra: &[&str]| {
        ok(&[
            &["info", spot, "--surface", "pn", "--pixel-error", px],
            extra,
        ]
        .concat())
    };
    // Every element drawn (culled ones are not drawn, so not capped).
    let tiny = pn("1e-6", &["--cull", "off"]);
    assert!(
        tiny.contains("capped: 372 element(s) need a level above --max-level 64"),
        "{tiny}"
    );
    let low = pn("1", &["--max-level", "8"]);
    let capped: u64 = (low.lines())
        .find_map(|l| l.trim().strip_prefix("capped: "))
        .and_then(|l| l.split_whitespace().next()?.parse().ok())
        .expect("a capped line");
    // The elements the pattern driver draws above 8 at --max-level 64, but for some drawn
    // there only for a capped neighbour's need on their shared edge (met at 8).
    let above: u64 = (pattern.lines().find(|l| l.contains("levels (")).unwrap())
        .split_whitespace()
        .skip(3)
        .map(|pair| pair.split_once(':').unwrap())
        .filter(|(l, _)| l.parse::<u32>().unwrap() > 8)
        .map(|(_, n)| n.parse::<u64>().unwrap())
        .sum();
    assert!(capped <= above && above - capped <= above / 2, "{low}");
    // The uniform level compared with is the cap, which does not meet the bound either.
    assert!(
        low.contains("at uniform level 8 (")
            && low.contains("the largest level, which does not meet the bound either)"),
        "{low}"
    );
    assert!(!pattern.contains("does not meet the bound"), "{pattern}");
    // Loop's elements are M1's faces.
    let loop_ = ok(&["info", spot, "--pixel-error", "1", "--surface", "loop"]);
    assert!(loop_.contains("level:M1 faces"), "{loop_}");
    assert_eq!(adaptive_report(&loop_).4, 4 * 372);
    // Bad values: one sentence, status 1.
    expect_error(&["info", spot, "--pixel-error", "0"], &["--pixel-error 0"]);
    expect_error(
        &["info", spot, "--pixel-error", "-1"],
        &["--pixel-error -1"],
    );
    expect_error(
        &["info", spot, "--pixel-error", "nan"],
        &["--pixel-error nan"],
    );
    expect_error(
        &["info", spot, "--pixel-error", "1", "--level", "4"],
        &["exclusive"],
    );
    expect_error(
        &[
            "info",
            spot,
            "--pixel-error",
            "1",
            "--eye",
            "1,2,3",
            "--look-at",
            "1,2,3",
        ],
        &["--eye 1,2,3", "no view direction", "the same point"],
    );
    // Points written as typed (not 39 digits), and two points f32 cannot tell apart as a
    // direction are not called the same.
    expect_error(
        &[
            "render",
            spot,
            "--eye",
            "0.5,0.5,1e-30",
            "--look-at",
            "0.5,0.5,0",
        ],
        &["--eye 0.5,0.5,1e-30 and", "too close together"],
    );
    expect_error(
        &["render", spot, "--eye", "1e38,0,0", "--look-at", "0,0,0"],
        &["--eye 1e38,0,0 is"],
    );
    expect_error(
        &["info", spot, "--pixel-error", "1", "--fov", "180"],
        &["--fov 180"],
    );
    // Camera options without --pixel-error are reported as ignored ...
    let out = meshrefine(&["info", spot, "--fov", "30"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--fov applies only with --pixel-error"));
    // ... their values checked all the same, as every ignored option's (docs/errors.md), in
    // info and in a uniform export.
    let obj = tmp("ignored-camera.obj");
    let obj = obj.to_str().unwrap();
    for cmd in [
        &["info", spot][..],
        &["export", spot, "-o", obj, "--level", "2"][..],
    ] {
        let with = |extra: &[&'static str]| -> Vec<&str> {
            cmd.iter().copied().chain(extra.iter().copied()).collect()
        };
        // One sentence, with no warning before it (as --alpha's, docs/errors.md).
        let refused = |args: &[&str], needle: &str| {
            let out = meshrefine(args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
            assert!(stderr.contains(needle), "{args:?}: {stderr}");
            assert!(
                !stderr.contains("warning"),
                "{args:?}: a warning before the refusal: {stderr}"
            );
        };
        refused(
            &with(&["--fov", "nan"]),
            "--fov nan is not within [0.01, 180) degrees",
        );
        refused(&with(&["--fov", "1e3"]), "--fov 1e3 is not within");
        refused(
            &with(&["--eye", "1,1,1", "--look-at", "1,1,1"]),
            "--eye 1,1,1 and --look-at 1,1,1 give no view direction: they are the same point",
        );
        refused(
            &with(&["--eye", "nan,0,0"]),
            "--eye nan,0,0 is not three finite numbers X,Y,Z",
        );
        refused(
            &with(&["--look-at", "0,inf,0"]),
            "--look-at 0,inf,0 is not three finite numbers X,Y,Z",
        );
        refused(
            &with(&["--eye", "1e39,0,0"]),
            "--eye 1e39,0,0 is not three finite numbers X,Y,Z in single precision",
        );
        // Checked before the warnings about what the command ignores.
        refused(
            &with(&[
                "--surface",
                "flat",
                "--alpha",
                "0.5",
                "--pixel-error",
                "nan",
            ]),
            "--pixel-error nan is not a finite number > 0",
        );
        refused(
            &with(&["--max-level", "3"]),
            "--max-level 3 is not a power of two",
        );
    }
    assert!(
        !std::path::Path::new(&obj).exists(),
        "an export refused wrote {obj}"
    );
}

/// An adaptive variant the device cannot draw (tess past its level limit, beside static,
/// which can) reports no triangles, and its uniform rows at the levels asked for are still
/// timed; one capped by --max-level says its bound's uniform level falls short too.
#[test]
fn bench_times_uniform_rows_of_a_variant_not_drawn_adaptively() {
    let prefix = tmp("bench-adaptive-not-drawn");
    let p = prefix.display().to_string();
    #[rustfmt::skip]
    ok(&[
        "bench", "--drivers", "tess,static", "--pixel-error", "2", "--max-level", "128",
        "--levels", "2", "--frames", "1", "--width", "32", "--height", "32", "--out", &p,
    ]);
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    let tess: Vec<_> = rows
        .iter()
        .filter(|r| get(r, "variant") == "tess")
        .collect();
    assert_eq!(tess.len(), 2, "{csv}");
    assert_eq!(get(tess[0], "adaptive"), "true");
    assert_eq!(get(tess[0], "refined_triangles"), "", "{csv}");
    assert!(get(tess[0], "note").contains("not drawn"), "{csv}");
    assert_eq!(
        (get(tess[1], "adaptive"), get(tess[1], "level")),
        ("false".into(), "2".into())
    );
    assert!(
        get(tess[1], "gpu_ms_median").parse::<f64>().is_ok(),
        "{csv}"
    );
    // Where --max-level keeps the bound from being met, the adaptive row says that the bound's
    // uniform level (the largest) does not meet it either.
    #[rustfmt::skip]
    let capped = ok(&[
        "bench", "--drivers", "static", "--surfaces", "pn", "--pixel-error", "1", "--max-level",
        "1", "--levels", "2", "--frames", "1", "--width", "32", "--height", "32",
    ]);
    assert!(
        capped.contains("the bound is not met on every element up to --max-level 1"),
        "{capped}"
    );
    // Where elements hold the eye in their bounds, no --max-level helps, and the note says so.
    #[rustfmt::skip]
    let near = ok(&[
        "bench", "--drivers", "static", "--surfaces", "pn", "--pixel-error", "2", "--eye",
        "0.3,0.2,0.6", "--look-at", "0,0.1,0.3", "--levels", "1", "--frames", "1", "--width",
        "32", "--height", "32", "--no-bound-levels",
    ]);
    // The summary wraps its notes: compared with single spaces.
    let near = near.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        near.contains(
            "the bound is not met on every element (elements holding the eye in their bounds, at any level)"
        ) && !near.contains("up to --max-level"),
        "{near}"
    );
}

/// Integer levels past the patterns' cap (`--geomorph off --max-level 256`) are drawn as render
/// draws them: up to the largest level the levels chosen reach, the same levels (render's line),
/// and the row says so.
#[test]
fn bench_draws_integer_levels_up_to_the_levels_reached() {
    let oct = model_path("octahedron.obj");
    let prefix = tmp("bench-integer-256");
    #[rustfmt::skip]
    let common = [
        "--pixel-error", "1", "--geomorph", "off", "--max-level", "256", "--width", "160",
        "--height", "90",
    ];
    let png = tmp("integer-256.png");
    let mut args = vec!["render", p(&oct), "-o", p(&png)];
    args.extend(common);
    let render = ok(&args);
    let histogram = render.split("(level:elements) ").nth(1).unwrap();
    let histogram = histogram.split(';').next().unwrap();
    #[rustfmt::skip]
    let mut args = vec![
        "bench", p(&oct), "--drivers", "pattern", "--surfaces", "pn", "--levels", "2",
        "--frames", "1", "--no-bound-levels", "--out", p(&prefix),
    ];
    args.extend(common);
    ok(&args);
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let adaptive: Vec<_> = rows
        .iter()
        .filter(|r| get(r, "adaptive") == "true")
        .collect();
    assert_eq!(adaptive.len(), 3, "{csv}");
    let top: u32 = (histogram.split_whitespace())
        .map(|l| l.split(':').next().unwrap().parse::<u32>().unwrap())
        .max()
        .unwrap();
    for row in adaptive {
        assert!(get(row, "gpu_ms_median").parse::<f64>().is_ok(), "{csv}");
        assert_eq!(get(row, "level_histogram"), histogram, "{csv}");
        assert_eq!(get(row, "level"), top.next_power_of_two().to_string());
        assert!(
            get(row, "note").contains(&format!(
                "drawn up to level {}, the largest its levels reach",
                top.next_power_of_two()
            )),
            "{csv}"
        );
    }
}

/// Where the pixel error is not met, elements are counted by their own bounds: those drawn at
/// the largest level only because a neighbour holds the eye meet it there (neither `near` nor
/// `capped`), and those no uniform level meets are the same whichever lattice driver's
/// transitions raise the others (the tessellator's, whose rings' diagonals bend more, at least
/// as many).
#[test]
fn info_counts_unmet_elements_by_their_own_bounds() {
    let ico = model_path("icosahedron.obj");
    #[rustfmt::skip]
    let out = ok(&[
        "info", p(&ico), "--eye", "-0.525731112,0.850650808,0", "--look-at", "0,0,0",
        "--pixel-error", "1e6", "--max-level", "1024",
    ]);
    assert!(
        out.contains("levels (level:coarse triangles): 1:10 1024:10"),
        "{out}"
    );
    assert!(out.contains("near: 5 element(s) hold the eye"), "{out}");
    assert!(!out.contains("capped"), "{out}");
    let beyond = |driver: &str| -> (u64, u64) {
        #[rustfmt::skip]
        let out = ok(&[
            "info", "--pixel-error", "1", "--eye", "0.3,0.2,0.6", "--look-at", "0,0.1,0.3",
            "--max-level", "16", "--driver", driver,
        ]);
        let line = out
            .lines()
            .find_map(|l| l.trim().strip_prefix("capped: "))
            .unwrap();
        let capped = line.split_whitespace().next().unwrap().parse().unwrap();
        // Of them, those no uniform level meets: all, some ("nor on B of them") or none.
        let of = if let Some((_, r)) = line.split_once("nor on ") {
            r.split_whitespace().next().unwrap().parse().unwrap()
        } else if line.contains("nor by any uniform level up to it") {
            capped
        } else {
            assert!(line.contains("uniform level 16 meets it on them"), "{line}");
            0
        };
        (capped, of)
    };
    let (pattern, tess, fixed) = (beyond("pattern"), beyond("tess"), beyond("static"));
    assert!(
        pattern.1 > 0 && pattern.1 == fixed.1 && tess.1 >= pattern.1,
        "{pattern:?} {tess:?} {fixed:?}"
    );
    // At integer levels a transition's corner triangles span two edges' samples: some elements
    // need more than the largest level for their transitions alone.
    assert!(fixed.0 > fixed.1, "{fixed:?}");
}

/// `bench --pixel-error` with `--levels`: per driver an adaptive row (each element at its own
/// levels; its triangles the histogram's at the inner levels, culled elements excluded), then uniform rows at the
/// levels asked for, at the smallest level meeting the same bound (`info`'s uniform level for the
/// same camera: no more than the largest level drawn) and at the next power of two where that
/// is not above the largest level (here it is: the adaptive row's note says so); the level
/// pass's CPU time on the adaptive row only. Validation on.
#[test]
fn bench_with_pixel_error_times_adaptive_and_uniform_rows() {
    let prefix = tmp("bench-adaptive");
    let spot = model_path("spot_control_tri.obj").display().to_string();
    let p = prefix.display().to_string();
    #[rustfmt::skip]
    ok(&[
        "--validate", "bench", &spot, "--surfaces", "pn", "--drivers", "tess", "--pixel-error", "1",
        "--max-level", "12", "--levels", "2", "--frames", "1", "--width", "448", "--height", "280",
        "--out", &p,
    ]);
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    let number = |r: &Vec<String>, key: &str| -> u64 { get(r, key).parse().unwrap() };
    let from: Vec<String> = rows.iter().map(|r| get(r, "level_from")).collect();
    assert_eq!(from[0], "view", "{csv}");
    let adaptive = &rows[0];
    assert_eq!(get(adaptive, "adaptive"), "true");
    assert_eq!(number(adaptive, "level"), 12);
    assert_eq!(get(adaptive, "level_pass_on"), "gpu");
    assert!(get(adaptive, "level_pass_ms").parse::<f64>().unwrap() >= 0.0);
    // Triangles: each visible element's at its inner level (tess: N² a triangle).
    let histogram: Vec<(u64, u64)> = get(adaptive, "level_histogram")
        .split(' ')
        .map(|p| {
            let (l, n) = p.split_once(':').unwrap();
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    let visible: u64 = histogram.iter().map(|(_, n)| n).sum();
    assert_eq!(
        visible + number(adaptive, "culled_elements"),
        number(adaptive, "elements")
    );
    let per = |l: u64| meshrefine::render::tess::tess_triangle_count(l as u32) as u64;
    let tris: u64 = histogram.iter().map(|&(l, n)| per(l) * n).sum();
    assert_eq!(number(adaptive, "refined_triangles"), tris);
    assert!(histogram.len() > 1, "levels differ between elements: {csv}");
    // The smallest uniform level meeting the bound: info's, for the same camera and driver
    // (integer levels, as the bench chooses them).
    #[rustfmt::skip]
    let info = ok(&[
        "info", &spot, "--surface", "pn", "--driver", "tess", "--geomorph", "off", "--pixel-error",
        "1", "--max-level", "12", "--width", "448", "--height", "280",
    ]);
    let bound = adaptive_report(&info).2 as u64;
    assert!(bound <= histogram.iter().map(|(l, _)| *l).max().unwrap());
    // One row per level, naming every reason it is timed; the power of two only up to the
    // largest level (its absence noted on the adaptive row).
    let pow2 = bound.next_power_of_two();
    assert!(
        pow2 > 12,
        "the bound {bound} is no longer under a power of two above --max-level 12"
    );
    let mut expected: Vec<(u64, String)> = Vec::new();
    let reasons = [(2, "levels"), (bound, "bound"), (pow2, "pow2")];
    for (level, from) in reasons.into_iter().filter(|r| r.0 <= 12) {
        match expected.iter_mut().find(|e| e.0 == level) {
            Some(e) => e.1 = format!("{}+{from}", e.1),
            None => expected.push((level, from.into())),
        }
    }
    let uniform: Vec<(u64, String)> = rows[1..]
        .iter()
        .map(|r| (number(r, "level"), get(r, "level_from")))
        .collect();
    assert_eq!(uniform, expected, "{csv}");
    let above = format!("uniform {pow2} (pow2, the power of two at or above the bound's {bound}) is above --max-level 12: not timed");
    assert_eq!(get(adaptive, "note").contains(&above), pow2 > 12, "{csv}");
    for r in &rows[1..] {
        assert_eq!(get(r, "adaptive"), "false");
        let l = number(r, "level");
        assert_eq!(
            number(r, "refined_triangles"),
            number(r, "elements") * per(l)
        );
        assert_eq!(get(r, "level_pass_ms"), "");
        assert!(get(r, "gpu_ms_median").parse::<f64>().is_ok(), "{csv}");
    }
}

/// `--pixel-error` and its camera on render, export, view and bench: every bad value is one
/// sentence and status 1, before anything is drawn, and a pattern driver's largest level that
/// is not a power of two.
#[test]
fn adaptive_options_refuse_bad_values() {
    let png = tmp("adaptive-bad.png");
    let obj = tmp("adaptive-bad.obj");
    let view_png = tmp("adaptive-bad-view.png");
    for f in [&png, &obj, &view_png] {
        let _ = std::fs::remove_file(f);
    }
    let commands: [Vec<&str>; 4] = [
        vec!["render", "-o", p(&png), "--driver", "tess"],
        vec!["export", "-o", p(&obj), "--driver", "tess"],
        vec![
            "view",
            "--headless-output",
            p(&view_png),
            "--driver",
            "tess",
        ],
        vec!["bench", "--drivers", "tess"],
    ];
    for base in &commands {
        let with = |extra: &[&'static str]| -> Vec<String> {
            base.iter().chain(extra).map(|s| s.to_string()).collect()
        };
        let expect_error = |args: &[String], needles: &[&str]| {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            expect_error(&args, needles)
        };
        expect_error(&with(&["--pixel-error", "0"]), &["--pixel-error 0"]);
        expect_error(&with(&["--pixel-error", "-1"]), &["--pixel-error -1"]);
        expect_error(&with(&["--pixel-error", "nan"]), &["--pixel-error nan"]);
        // What was typed, not the f32 it parses to (inf), and a negative exponent is a value.
        expect_error(
            &with(&["--pixel-error", "1e39"]),
            &["--pixel-error 1e39 is not a finite number > 0"],
        );
        expect_error(
            &with(&["--pixel-error", "-1e-30"]),
            &["--pixel-error -1e-30 is not a finite number > 0"],
        );
        expect_error(&with(&["--pixel-error", "1", "--fov", "0"]), &["--fov 0"]);
        expect_error(
            &with(&["--pixel-error", "1", "--eye", "nan,0,0"]),
            &["--eye nan,0,0 is not three finite numbers X,Y,Z"],
        );
        expect_error(
            &with(&["--pixel-error", "1", "--fov", "180"]),
            &["--fov 180"],
        );
        expect_error(
            &with(&["--pixel-error", "1", "--eye", "1,2,3", "--look-at", "1,2,3"]),
            &["--eye 1,2,3", "no view direction"],
        );
        // bench times --levels uniformly beside the adaptive rows (`bench_with_pixel_error_...`).
        if base[0] != "bench" {
            expect_error(
                &with(&["--pixel-error", "1", "--level", "4"]),
                &["--pixel-error and", "exclusive"],
            );
        }
    }
    // The static driver draws adaptively too, refining on the CPU (tests/cli_default_levels.rs
    // runs it, and bench's static adaptive rows).
    // The pattern driver's patterns split 1 to 4: its largest level is a power of two.
    expect_error(
        &[
            "render",
            "-o",
            p(&png),
            "--pixel-error",
            "1",
            "--max-level",
            "48",
        ],
        &["--max-level 48", "power of two", "use 32 or 64"],
    );
    // Past what the device's tessellator draws (lavapipe: 64), named.
    expect_error(
        &[
            "render",
            "-o",
            p(&png),
            "--driver",
            "tess",
            "--pixel-error",
            "1",
            "--max-level",
            "100",
        ],
        &[
            "--max-level 100",
            "maxTessellationGenerationLevel",
            // The same sentence as a uniform level past the limit (`driver::check_level`).
            "--max-level 100: level 100 is beyond this device's maxTessellationGenerationLevel (64): the tess driver cannot draw it (use a level up to 64, or the pattern driver, which this limit does not bind)",
        ],
    );
    // export's refusals of what the device allows name the mesh as render's do; info, which draws nothing, refuses the
    // level render refuses with the same sentence (the device's limits read, none opened).
    let past =
        "--max-level 100: level 100 is beyond this device's maxTessellationGenerationLevel (64)";
    #[rustfmt::skip]
    let refusals: [(&[&str], String); 3] = [
        (&["export", "-o", p(&obj), "--driver", "tess", "--pixel-error", "1", "--max-level", "100"],
         format!("error: cannot export 'the default mesh (spot)': {past}")),
        (&["export", "-o", p(&obj), "--pixel-error", "1", "--max-level", "48"],
         // A value every device refuses: checked before the mesh is read, as --pixel-error's.
         "error: --max-level 48 is not a power of two".into()),
        (&["info", "--driver", "tess", "--pixel-error", "1", "--max-level", "100"],
         format!("error: {past}")),
    ];
    for (args, sentence) in refusals {
        expect_error(args, &[&sentence]);
        let out = meshrefine(args);
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    assert!(!png.exists() && !obj.exists() && !view_png.exists());
    // The level options without --pixel-error are reported as ignored; the camera applies to
    // uniform drawing too (an image from it differs from the framing camera's).
    let framed = tmp("uniform-framed.png");
    let args = |out: &Path, camera: &[&'static str]| {
        let mut v = vec!["render", "-o", p(out), "--cull", "off", "--level", "2"];
        v.extend(["--width", "64", "--height", "48"]);
        v.extend(camera);
        v.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |a: Vec<String>| meshrefine(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let out = run(args(&png, &["--fov", "30", "--eye", "0.35,0.65,-1.3"]));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("--fov applies"), "{stderr}");
    assert!(!stderr.contains("--eye applies"), "{stderr}");
    assert!(
        stderr.contains("--cull applies only when drawing adaptively (with --pixel-error, or by default without --level)"),
        "{stderr}"
    );
    assert!(run(args(&framed, &[])).status.success());
    assert_ne!(
        std::fs::read(&png).unwrap(),
        std::fs::read(&framed).unwrap()
    );
    // ... so its values are checked then too.
    expect_error(
        &["render", "-o", p(&png), "--level", "2", "--fov", "0"],
        &["--fov 0 is not within [0.01, 180) degrees"],
    );
    expect_error(
        &["render", "-o", p(&png), "--fov", "1e-9"],
        &["--fov 1e-9 is not within [0.01, 180) degrees"],
    );
    expect_error(
        &["render", "-o", p(&png), "--fov", "NaN"],
        &["--fov NaN is not within [0.01, 180) degrees"],
    );
    // A value inside the range that single precision rounds onto its open end says so.
    expect_error(
        &["render", "-o", p(&png), "--fov", "179.999999"],
        &["--fov 179.999999 is not within [0.01, 180) degrees in single precision (it reads as 180)"],
    );
}

/// The two header lines of an adaptive export: the camera's numbers and `L:n` pairs.
fn adaptive_header(text: &str) -> (Vec<f32>, Vec<(u32, u64)>) {
    let camera = text
        .lines()
        .find(|l| l.starts_with("# camera "))
        .unwrap_or_else(|| panic!("no camera line"));
    let words: Vec<&str> = camera.split_whitespace().collect();
    let names = [
        "#",
        "camera",
        "eye",
        "",
        "",
        "",
        "target",
        "",
        "",
        "",
        "up",
        "",
        "",
        "",
        "fov-y",
        "",
        "size",
        "",
        "",
        "pixel-error",
        "",
    ];
    assert_eq!(words.len(), names.len(), "{camera}");
    let mut numbers = Vec::new();
    for (w, n) in words.iter().zip(names) {
        if n.is_empty() {
            numbers.push(
                w.parse::<f32>()
                    .unwrap_or_else(|_| panic!("{w} in {camera}")),
            );
        } else {
            assert_eq!(*w, n, "{camera}");
        }
    }
    let levels = text
        .lines()
        .find(|l| l.starts_with("# levels "))
        .unwrap_or_else(|| panic!("no levels line"));
    let pairs = levels["# levels ".len()..]
        .split_whitespace()
        .map(|pair| {
            let (l, n) = pair.split_once(':').unwrap();
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    (numbers, pairs)
}

/// `export --pixel-error` writes what the tess driver drew adaptively for the camera: the
/// header says which camera and how many elements at each level; without culling (export's
/// default) every element is drawn and the welded mesh is closed, with fewer triangles than the
/// largest level everywhere; a close-up with culling draws fewer elements; render, view and
/// bench draw adaptively too.
#[test]
fn pixel_error_draws_adaptively_end_to_end() {
    let spot = model_path("spot_control_tri.obj");
    let spot = p(&spot);
    let obj = tmp("adaptive.obj");
    let out = ok(&[
        "export",
        spot,
        "-o",
        p(&obj),
        "--driver",
        "tess",
        "--pixel-error",
        "2",
    ]);
    assert!(out.contains("wrote"), "{out}");
    let text = std::fs::read_to_string(&obj).unwrap();
    let (camera, levels) = adaptive_header(&text);
    // up, fov, size, pixel error.
    assert_eq!(&camera[6..], &[0.0, 1.0, 0.0, 45.0, 1280.0, 720.0, 2.0]);
    assert_eq!(levels.iter().map(|l| l.1).sum::<u64>(), 372, "{levels:?}");
    assert!(levels.len() > 2 && levels.iter().all(|&(l, _)| (1..=64).contains(&l)));
    let (mesh, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
    assert_eq!(mesh.stats().boundary_edges, 0, "adaptive export has cracks");
    let top = levels.last().unwrap().0;
    assert!(
        mesh.triangles.len() < 372 * meshrefine::render::tess::tess_triangle_count(top) as usize
    );
    // Wound like the coarse triangles (outward on a sphere), transition triangles too.
    let sphere = model_path("uvsphere12.obj");
    ok(&[
        "export",
        p(&sphere),
        "-o",
        p(&obj),
        "--driver",
        "tess",
        "--pixel-error",
        "0.5",
    ]);
    let (ball, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
    assert_eq!(ball.stats().boundary_edges, 0);
    assert_faces_agree_with_normals(&ball);
    // A close-up with culling: the camera is echoed in the mesh's coordinates; fewer elements.
    let close = ok(&[
        "export",
        spot,
        "-o",
        p(&obj),
        "--driver",
        "tess",
        "--pixel-error",
        "1",
        "--eye",
        "0.3,0.2,0.6",
        "--look-at",
        "0,0.1,0.3",
        "--fov",
        "50",
        "--cull",
        "on",
        "--max-level",
        "20",
    ]);
    assert!(close.contains("wrote"), "{close}");
    let text = std::fs::read_to_string(&obj).unwrap();
    let (camera, levels) = adaptive_header(&text);
    // Exactly as given (not mapped to the drawn frame and back).
    assert!(
        text.contains("# camera eye 0.3 0.2 0.6 target 0 0.1 0.3 up 0 1 0 fov-y 50 "),
        "{text}"
    );
    assert_eq!(&camera[..6], &[0.3, 0.2, 0.6, 0.0, 0.1, 0.3]);
    assert_eq!(camera[9], 50.0);
    // Numbers far from 1 in exponent form, as short and as exact (not 45 zeros before the 1).
    let tiny = std::env::temp_dir().join("meshrefine-export-tiny-eye.obj");
    let camera = [
        "--pixel-error",
        "1",
        "--eye",
        "1e-30,-1e-40,3",
        "--look-at",
        "1e-45,0,0",
    ];
    let mut args = vec!["export", spot, "-o", p(&tiny), "--max-level", "2"];
    args.extend(camera);
    ok(&args);
    let text = std::fs::read_to_string(&tiny).unwrap();
    assert!(
        text.contains("\n# camera eye 1e-30 -1e-40 3 target 1e-45 0 0 up 0 1 0 fov-y 45 "),
        "{text}"
    );
    assert_eq!(
        &adaptive_header(&text).0[..6],
        &[1e-30, -1e-40, 3.0, 1e-45, 0.0, 0.0]
    );
    std::fs::remove_file(&tiny).unwrap();
    // info writes the camera alike.
    let mut args = vec!["info", spot];
    args.extend(camera);
    let info = ok(&args);
    assert!(
        info.contains(", eye 1e-30 -1e-40 3, look-at 1e-45 0 0,"),
        "{info}"
    );
    let drawn: u64 = levels.iter().map(|l| l.1).sum();
    assert!(drawn > 0 && drawn < 372, "{levels:?}");
    assert!(levels.iter().all(|&(l, _)| l <= 20), "{levels:?}");
    let (mesh, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
    assert!(mesh.stats().boundary_edges > 0);
    // render, the headless view and bench.
    let png = tmp("adaptive.png");
    let out = ok(&[
        "render",
        spot,
        "-o",
        p(&png),
        "--driver",
        "tess",
        "--pixel-error",
        "2",
        "--width",
        "320",
        "--height",
        "180",
    ]);
    assert!(
        out.contains("adaptive at 2 px, max level 64: levels (level:elements) "),
        "{out}"
    );
    let view_png = tmp("adaptive-view.png");
    let out = ok(&[
        "view",
        spot,
        "--headless-output",
        p(&view_png),
        "--driver",
        "tess",
        "--pixel-error",
        "3",
    ]);
    assert!(out.contains("adaptive at 3 px"), "{out}");
    let out = ok(&small_adaptive_bench(spot, &["--drivers", "tess"]));
    assert!(out.contains("levels from") && out.contains("view"), "{out}");
}

/// `bench` of Spot's `pn` at 4 px, one frame of 160x90, with `extra` options.
fn small_adaptive_bench<'a>(spot: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["bench", spot, "--surfaces", "pn", "--pixel-error", "4"];
    args.extend(["--frames", "1", "--width", "160", "--height", "90"]);
    args.extend(extra);
    args
}

/// The pattern driver (the default) draws adaptively from the command line too: `export
/// --pixel-error` captures its hierarchical patterns and welds them closed on a closed mesh
/// (no culling by default), every element at a power of two up to 64, the header's levels
/// those the GPU's level pass wrote (with `--geomorph off` integer levels, closed as well); render says what it drew; bench without `--drivers`
/// measures the pattern driver's submissions, tess and static.
#[test]
fn pixel_error_draws_adaptively_with_the_pattern_driver() {
    let spot = model_path("spot_control_tri.obj");
    let spot = p(&spot);
    let obj = tmp("adaptive-pattern.obj");
    let out = ok(&["export", spot, "-o", p(&obj), "--pixel-error", "2"]);
    assert!(out.contains("wrote"), "{out}");
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.contains("driver pattern"), "{text:.400}");
    assert!(text.contains("max level 64"), "{text:.400}");
    let (camera, levels) = adaptive_header(&text);
    assert_eq!(&camera[6..], &[0.0, 1.0, 0.0, 45.0, 1280.0, 720.0, 2.0]);
    assert_eq!(levels.iter().map(|l| l.1).sum::<u64>(), 372, "{levels:?}");
    assert!(
        levels.len() > 1
            && (levels.iter()).all(|&(l, _)| l.is_power_of_two() && (1..=64).contains(&l)),
        "{levels:?}"
    );
    let (mesh, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
    assert_eq!(mesh.stats().boundary_edges, 0, "adaptive export has cracks");
    let top = levels.last().unwrap().0 as usize;
    assert!(
        mesh.triangles.len() < 372 * top * top,
        "{}",
        mesh.triangles.len()
    );
    // Without geomorphing: integer levels from the integer patterns, closed too, and fewer
    // triangles than at powers of two.
    let int_obj = tmp("adaptive-pattern-integer.obj");
    let int_args = [
        "export",
        spot,
        "-o",
        p(&int_obj),
        "--pixel-error",
        "2",
        "--geomorph",
        "off",
    ];
    ok(&int_args);
    let int_text = std::fs::read_to_string(&int_obj).unwrap();
    let (_, int_levels) = adaptive_header(&int_text);
    assert_eq!(int_levels.iter().map(|l| l.1).sum::<u64>(), 372);
    assert!(
        (int_levels.iter()).any(|&(l, _)| !l.is_power_of_two()),
        "{int_levels:?}"
    );
    let (int_mesh, _) = meshrefine::mesh::Mesh::load_obj(&int_obj).unwrap();
    assert_eq!(
        int_mesh.stats().boundary_edges,
        0,
        "integer export has cracks"
    );
    assert_eq!(int_mesh.stats().inconsistently_oriented_edges, 0);
    assert!(int_mesh.triangles.len() < mesh.triangles.len());
    // The integer patterns grow with the cube of the largest level: a largest level past 128
    // is drawn up to the largest level chosen where those fit (the same vertices), and
    // refused in one sentence where they do not.
    let high_obj = tmp("adaptive-pattern-integer-256.obj");
    let high = |px| {
        let out = p(&high_obj);
        let args = ["--geomorph", "off", "--max-level", "256"];
        [&["export", spot, "-o", out, "--pixel-error", px][..], &args].concat()
    };
    ok(&high("2"));
    let high_text = std::fs::read_to_string(&high_obj).unwrap();
    assert!(high_text.contains("max level 256"), "{high_text:.400}");
    // Past the first line (the largest level) and but for the command line.
    let after_first = |t: &str| {
        let rest = t.split_once('\n').unwrap().1;
        let kept = rest.lines().filter(|l| !l.starts_with("# command: "));
        kept.collect::<Vec<_>>().join("\n")
    };
    assert!(
        after_first(&high_text) == after_first(&int_text),
        "--max-level 256 wrote other vertices than the default largest level"
    );
    expect_error(
        &high("0.01"),
        &[
            "at most up to level 128, not 256",
            "--geomorph on, or --max-level 128 or a smaller power of two",
        ],
    );
    // render refuses the same in one sentence, with no warning of slow frames before it, nor a
    // note on the levels it does not draw (elements holding the eye drawn at 256, others
    // needing more).
    let high_png = tmp("adaptive-pattern-integer-256.png");
    #[rustfmt::skip]
    let render = [
        "render", spot, "-o", p(&high_png), "--pixel-error", "0.01", "--geomorph", "off",
        "--max-level", "256",
    ];
    expect_error(&render, &["at most up to level 128, not 256"]);
    let stderr = String::from_utf8_lossy(&meshrefine(&render).stderr).into_owned();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let mut close = render.to_vec();
    close.extend(["--eye", "0.3,0.2,0.6", "--look-at", "0,0.1,0.3"]);
    let stderr = String::from_utf8_lossy(&meshrefine(&close).stderr).into_owned();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("not 256"), "{stderr}");
    // So does info, which chooses the same levels; and where they fit, it prints them.
    let mut info: Vec<&str> = render.to_vec();
    info.splice(0..4, ["info", spot]);
    // (info draws nothing: the sentence names the option, not "cannot render".)
    expect_error(
        &info,
        &["error: --max-level 256: drawing integer levels", "not 256"],
    );
    let said = String::from_utf8_lossy(&meshrefine(&info).stderr).into_owned();
    assert!(!said.contains("cannot render"), "{said}");
    info[3] = "2";
    let fits = ok(&info);
    assert!(fits.contains("max level 256"), "{fits}");
    // The height map's mip level follows the largest level: render does not lower it to the
    // levels chosen, and info refuses alike.
    let grid = model_path("grid_uv_8x8.obj");
    #[rustfmt::skip]
    let mapped = ["--displace", "heightmap", "--geomorph", "off", "--max-level", "256", "--pixel-error", "4"];
    expect_error(
        &[&["info", p(&grid)][..], &mapped].concat(),
        &["at most up to level 128, not 256"],
    );
    expect_error(
        &[&["render", p(&grid), "-o", p(&high_png)][..], &mapped].concat(),
        &["at most up to level 128, not 256"],
    );
    // Wound like the coarse triangles on a sphere, closed, at both roundings.
    let sphere = model_path("uvsphere12.obj");
    for geomorph in ["on", "off"] {
        let args = ["--pixel-error", "0.5", "--geomorph", geomorph];
        ok(&[&["export", p(&sphere), "-o", p(&obj)][..], &args].concat());
        let (ball, _) = meshrefine::mesh::Mesh::load_obj(&obj).unwrap();
        assert_eq!(ball.stats().boundary_edges, 0);
        assert_faces_agree_with_normals(&ball);
    }
    let png = tmp("adaptive-pattern.png");
    let out = ok(&[
        "render",
        spot,
        "-o",
        p(&png),
        "--pixel-error",
        "2",
        "--width",
        "320",
        "--height",
        "180",
    ]);
    assert!(
        out.contains("adaptive at 2 px, max level 64: levels (level:elements) "),
        "{out}"
    );
    let out = ok(&small_adaptive_bench(spot, &[]));
    assert!(out.contains("levels from") && out.contains("view"), "{out}");
    // Without --drivers: every driver, the CPU baseline included (summary rows name the
    // variant second, after the level).
    for variant in [
        "static",
        "pattern/push",
        "pattern/ubo",
        "pattern/instanced",
        "tess",
    ] {
        assert!(
            (out.lines()).any(|l| l.split_whitespace().nth(1) == Some(variant)),
            "no {variant} row: {out}"
        );
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

/// `--msaa`: 1 is today's single-sampled image, byte for byte the same as asking for nothing
/// but one sample; a count the device does not offer for colour and depth attachments is one
/// sentence naming what it offers (lavapipe offers 1 and 4: 2 and 8 are refused there, other
/// devices may draw them); a count that is not 1, 2, 4 or 8 is a usage error.
#[test]
fn msaa_counts_render_or_are_refused_in_one_sentence() {
    let one = tmp("msaa-1.png");
    let four = tmp("msaa-default.png");
    let small = ["--width", "96", "--height", "64", "--level", "2"];
    let mut args = vec![
        "--validate",
        "render",
        "-o",
        one.to_str().unwrap(),
        "--msaa",
        "1",
    ];
    args.extend(small);
    ok(&args);
    let mut args = vec!["--validate", "render", "-o", four.to_str().unwrap()];
    args.extend(small);
    ok(&args);
    let (a, b) = (std::fs::read(&one).unwrap(), std::fs::read(&four).unwrap());
    assert_ne!(
        a, b,
        "the default (multisampled where offered) drew the 1x image"
    );
    for n in ["2", "8"] {
        let out_path = tmp(&format!("msaa-{n}.png"));
        let mut args = vec!["render", "-o", out_path.to_str().unwrap(), "--msaa", n];
        args.extend(small);
        let out = meshrefine(&args);
        if !out.status.success() {
            expect_error(
                &args,
                &[&format!("--msaa {n} is not supported by"), "(it offers 1"],
            );
        }
    }
    let out = meshrefine(&["render", "--msaa", "3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("possible values: 1, 2, 4, 8"));
}

/// Reads the RGBA pixels of a PNG meshrefine wrote.
fn rgba_of(png_path: &Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::fs::File::open(png_path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgba).unwrap();
    rgba.truncate(info.buffer_size());
    rgba
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

/// `--normal-field` on the command line: each field exports `pn` at the same positions with
/// normals of its own (the fields differ on a control cage, surfaces.md), displaces along its
/// own normals (positions differ too with `--displace`), and renders its own shading; a value
/// that is not a field is a usage error listing the fields.
#[test]
fn normal_fields_are_chosen_on_the_command_line() {
    let spot = model_path("spot_control_tri.obj");
    let export = |field: &str, extra: &[&str]| {
        let out = tmp(&format!("normal-field-{field}{}.obj", extra.len()));
        let mut args = vec!["--validate", "export", p(&spot), "-o", p(&out)];
        args.extend(["--surface", "pn", "--level", "2", "--normal-field", field]);
        args.extend(extra);
        ok(&args);
        let obj = std::fs::read_to_string(&out).unwrap();
        let lines = |key: &str| -> Vec<String> {
            let key = format!("{key} ");
            obj.lines()
                .filter(|l| l.starts_with(&key))
                .map(String::from)
                .collect()
        };
        (lines("v"), lines("vn"))
    };
    let fields = ["paper", "vlachos", "linear"];
    let plain: Vec<_> = fields.iter().map(|f| export(f, &[])).collect();
    let displaced: Vec<_> = (fields.iter())
        .map(|f| export(f, &["--displace", "sine"]))
        .collect();
    let png = |field: &str| {
        let out = tmp(&format!("normal-field-{field}.png"));
        #[rustfmt::skip]
        ok(&[
            "--validate", "render", p(&spot), "-o", p(&out), "--surface", "pn", "--level", "2",
            "--normal-field", field, "--width", "96", "--height", "64", "--msaa", "1",
        ]);
        rgba_of(&out)
    };
    let images: Vec<Vec<u8>> = fields.iter().map(|f| png(f)).collect();
    for i in 0..3 {
        for j in i + 1..3 {
            let (a, b) = (fields[i], fields[j]);
            assert_eq!(plain[i].0, plain[j].0, "{a} and {b}: positions");
            assert_ne!(plain[i].1, plain[j].1, "{a} and {b}: the same normals");
            assert_ne!(
                displaced[i].0, displaced[j].0,
                "{a} and {b}: displaced alike"
            );
            assert_ne!(images[i], images[j], "{a} and {b}: the same image");
        }
    }
    let out = meshrefine(&["export", "--normal-field", "phong", "-o", "x.obj"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("'phong'") && stderr.contains("paper, vlachos, linear"),
        "{stderr}"
    );
}

/// `meshrefine` with `args` and the environment variables `env`.
fn meshrefine_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let _guard = common::gpu_lock();
    bin()
        .args(args)
        .envs(env.iter().copied())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run meshrefine")
}

/// Runs meshrefine with `args` and `env`, expecting success; returns its standard error.
fn succeeds(args: &[&str], env: &[(&str, &str)]) -> String {
    let out = meshrefine_env(args, env);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?}: {stderr}");
    stderr
}

/// An adaptive export made in many passes runs Loop's step and the level pass once, in the
/// first, and the passes after it draw from what they wrote: the same file as one pass, on both
/// drivers (`loop` has the pre-pass; the pattern driver bins each pass from the levels).
#[test]
fn adaptive_exports_in_passes_keep_the_file() {
    let ico = model_path("icosahedron.obj");
    // Three elements a pass at the largest level (8): 64 tess triangles of 3 vertices.
    let xfb_vertex = std::mem::size_of::<meshrefine::render::XfbVertex>();
    let bytes = (3 * 64 * 3 * xfb_vertex).to_string();
    for driver in ["tess", "pattern"] {
        let one = tmp(&format!("adaptive_passes_one_{driver}.obj"));
        let many = tmp(&format!("adaptive_passes_many_{driver}.obj"));
        let run = |o: &Path, env: &[(&str, &str)]| {
            let mut a = vec!["export", p(&ico), "-o", p(o), "--surface", "loop"];
            a.extend([
                "--pixel-error",
                "0.5",
                "--max-level",
                "8",
                "--driver",
                driver,
            ]);
            succeeds(&a, env)
        };
        run(&one, &[]);
        let env = [
            ("MESHREFINE_PROGRESS_AFTER", "0"),
            ("MESHREFINE_MAX_CAPTURE_BYTES", bytes.as_str()),
            ("RUST_LOG", "meshrefine::render::headless=debug"),
        ];
        let loud = run(&many, &env);
        let passes = loud.lines().filter(|l| l.contains(" passes (")).count();
        assert!(passes >= 5, "{driver}: {passes} passes: {loud}");
        // Loop's step and the level pass run in the first pass only.
        for said in ["records the level pass", "records Loop's pre-pass"] {
            let n = loud.lines().filter(|l| l.contains(said)).count();
            assert_eq!(n, 1, "{driver}: '{said}' {n} times: {loud}");
        }
        assert!(
            without_command(&one) == without_command(&many),
            "{driver}: passes change the file"
        );
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

/// An adaptive export is sized by the levels chosen for its camera (what it really exports),
/// not by every element at the largest level, and a refusal advises the adaptive options, never
/// `--level` (exclusive with `--pixel-error`).
#[test]
fn adaptive_exports_are_sized_by_the_levels_chosen() {
    let spot = model_path("spot_tri.obj");
    let obj = tmp("adaptive-size.obj");
    std::fs::remove_file(&obj).ok();
    let export = |extra: &[&str]| -> Vec<String> {
        let mut args: Vec<String> = ["export", p(&spot), "-o", p(&obj)].map(String::from).into();
        args.extend(extra.iter().map(|s| s.to_string()));
        args
    };
    let run = |extra: &[&str], needles: &[&str]| {
        let args = export(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        expect_error(&args, needles);
        let stderr = String::from_utf8_lossy(&meshrefine(&args).stderr).to_string();
        assert!(!stderr.contains("--level "), "{stderr}");
        // One sentence: no note before it on levels it does not draw.
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(!obj.exists());
    };
    // 5856 elements at levels 1 and 2: about eleven thousand triangles, written.
    let args = export(&["--pixel-error", "4", "--width", "160", "--height", "100"]);
    let out = ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let triangles: u64 = out
        .split(" triangles")
        .next()
        .unwrap()
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((5856..4 * 5856).contains(&triangles), "{out}");
    std::fs::remove_file(&obj).unwrap();
    // Levels up to 64 on most elements: more than 2^24 triangles, the sentence docs/errors.md
    // shows (after the file's name), word for word.
    let guide =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/errors.md"))
            .unwrap();
    let shown = (guide.lines())
        .find_map(|l| l.strip_prefix("error: cannot export 'spot_tri.obj': --pixel-error 3e-4"))
        .expect("docs/errors.md shows the refusal of --pixel-error 3e-4");
    let sentence = format!("--pixel-error 3e-4{shown}");
    run(
        &["--pixel-error", "3e-4"],
        &[
            "cannot export '",
            &sentence,
            "at most 16777216 (2^24)",
            "use a larger --pixel-error, or --max-level 32 or a smaller power of two",
        ],
    );
    // The tessellator glides at powers of two (another largest level draws integer levels,
    // which make more triangles): a power of two is advised, any level without gliding.
    let tess = [
        "--driver",
        "tess",
        "--pixel-error",
        "1e-4",
        "--width",
        "160",
        "--height",
        "90",
    ];
    let advice = "use a larger --pixel-error, or --max-level 32 or a smaller power of two";
    run(&tess, &[advice]);
    let mut integer = tess.to_vec();
    integer.extend(["--geomorph", "off"]);
    run(
        &integer,
        &["use a larger --pixel-error, or --max-level 44 or lower"],
    );
}

/// The closed, consistently oriented triangles of an exported OBJ's text (each undirected edge
/// in exactly two faces, each directed edge in one), with its `# levels` histogram
/// (level, elements) and its vertex and face counts.
fn closed_adaptive_export(text: &str) -> (Vec<(u64, u64)>, usize, usize) {
    let levels: Vec<(u64, u64)> = (text.lines())
        .find_map(|l| l.strip_prefix("# levels "))
        .expect("a # levels line")
        .split_whitespace()
        .map(|b| {
            let (l, n) = b.split_once(':').expect("level:count");
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
    let faces: Vec<[usize; 3]> = (text.lines())
        .filter_map(|l| l.strip_prefix("f "))
        .map(|f| {
            let c: Vec<usize> = f
                .split_whitespace()
                .map(|c| c.split('/').next().unwrap().parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let mut undirected = std::collections::HashMap::new();
    let mut directed = std::collections::HashSet::new();
    for f in &faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            assert!(
                directed.insert((a, b)),
                "edge {a}-{b} twice in one direction"
            );
        }
    }
    let open = undirected.values().filter(|&&n| n != 2).count();
    assert_eq!(open, 0, "{open} edges not shared by exactly two faces");
    (levels, vertices, faces.len())
}

/// The pattern driver's adaptive export captures each element at the level it is drawn at
/// only, so what it holds follows the levels chosen, not the largest level: up to
/// `--max-level 1024` on Spot's 5856 elements (its finest pattern for every element would be
/// 197 GB) and loop's 23424 elements at the default largest level export, welded closed with
/// the vertex count their levels give; one element too large for a capture pass is one sentence.
#[test]
fn adaptive_pattern_exports_hold_only_the_levels_drawn() {
    let spot = model_path("spot_tri.obj");
    let obj = tmp("adaptive-packed.obj");
    let export = |extra: &[&str]| -> String {
        std::fs::remove_file(&obj).ok();
        let mut args = vec!["export", p(&spot), "-o", p(&obj), "--width", "160"];
        args.extend(["--height", "100"]);
        args.extend(extra);
        ok(&args);
        std::fs::read_to_string(&obj).unwrap()
    };
    // Every element at level 1: the coarse mesh, its 2930 vertices and 5856 faces.
    let text = export(&["--pixel-error", "4", "--max-level", "1024"]);
    assert!(text.contains("max level 1024"), "{}", &text[..200]);
    let (levels, vertices, faces) = closed_adaptive_export(&text);
    assert_eq!(levels, [(1, 5856)]);
    assert_eq!((vertices, faces), (2930, 5856));
    // Mixed levels: Spot is a sphere, so welded closed it has 2 + F/2 vertices (Euler), and
    // at most N² triangles an element at level N (fewer where snapping to a coarser edge
    // dropped degenerate ones), at least half of them.
    for extra in [
        ["--pixel-error", "0.25", "--max-level", "1024"],
        ["--pixel-error", "1", "--surface", "loop"],
    ] {
        let text = export(&extra);
        let (levels, vertices, faces) = closed_adaptive_export(&text);
        assert!(levels.len() > 1, "{extra:?}: one level only: {levels:?}");
        let elements: u64 = levels.iter().map(|l| l.1).sum();
        let expected = if extra.contains(&"loop") { 23424 } else { 5856 };
        assert_eq!(elements, expected, "{extra:?}");
        assert_eq!(vertices, 2 + faces / 2, "{extra:?}");
        let most: u64 = levels.iter().map(|(l, n)| n * l * l).sum();
        assert!(
            faces as u64 <= most && 2 * faces as u64 > most,
            "{extra:?}: {faces}"
        );
    }
    // One element at level 4 needs 15 x 64 bytes: passes of 640 cannot hold it.
    std::fs::remove_file(&obj).ok();
    let env = [("MESHREFINE_MAX_CAPTURE_BYTES", "640")];
    #[rustfmt::skip]
    let args = [
        "export", p(&spot), "-o", p(&obj), "--width", "160", "--height", "100", "--pixel-error",
        "0.25",
    ];
    let out = meshrefine_env(&args, &env);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("cannot export '")
            && stderr.contains("of one element drawn at level")
            && stderr.contains("over the capture cap MESHREFINE_MAX_CAPTURE_BYTES (640)")
            && stderr
                .contains("use a larger --pixel-error, or --max-level 2 or a smaller power of two"),
        "{stderr}"
    );
    assert!(!obj.exists());
}

/// An adaptive export whose every element is culled writes nothing and says why.
#[test]
fn an_adaptive_export_with_every_element_culled_is_an_error() {
    let obj = tmp("all-culled.obj");
    std::fs::remove_file(&obj).ok();
    #[rustfmt::skip]
    expect_error(
        &[
            "export", "-o", p(&obj), "--pixel-error", "1", "--cull", "on", "--eye", "100,0,0",
            "--look-at", "200,0,0", "--width", "160", "--height", "100",
        ],
        &[
            "cannot export 'the default mesh (spot)': every one of its 372 elements is culled",
            "nothing to export; --cull off exports them",
        ],
    );
    assert!(!obj.exists());
}

/// An adaptive render warns of slow frames from the levels it chose, not from every element at
/// the largest level.
#[test]
fn adaptive_renders_warn_of_slow_frames_from_the_levels_chosen() {
    let spot = model_path("spot_tri.obj");
    let png = tmp("adaptive-slow.png");
    #[rustfmt::skip]
    let out = meshrefine(&[
        "render", p(&spot), "-o", p(&png), "--pixel-error", "4", "--width", "160", "--height", "100",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // 3268 elements at level 1 are drawn, not 5856 x 64².
    assert!(!stderr.contains("refined triangles per frame"), "{stderr}");
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

/// bench's adaptive rows warn of slow frames from the levels chosen, as render does, not from
/// every element at --max-level: none where few triangles are drawn (or none, every element
/// culled), and where they are many, the adaptive row's own count with render's advice.
#[test]
fn bench_adaptive_rows_warn_of_slow_frames_from_the_levels_chosen() {
    let bench = |args: &[&str]| {
        let mut all = vec!["bench", "--frames", "1", "--width", "64", "--height", "48"];
        all.extend(["--levels", "1", "--no-bound-levels"]);
        all.extend(args);
        let out = meshrefine(&all);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{args:?}: {stderr}");
        (String::from_utf8_lossy(&out.stdout).to_string(), stderr)
    };
    // Spot's 372 elements at --max-level 1024 would be 390 M triangles; a few thousand are drawn.
    #[rustfmt::skip]
    let (_, stderr) = bench(&[
        "--pixel-error", "1", "--drivers", "pattern", "--surfaces", "pn", "--max-level", "1024",
    ]);
    assert!(!stderr.contains("refined triangles per frame"), "{stderr}");
    #[rustfmt::skip]
    let (_, stderr) = bench(&[
        "--pixel-error", "1", "--drivers", "tess", "--surfaces", "pn,loop", "--eye", "5,0,0",
        "--look-at", "10,0,0",
    ]);
    assert!(!stderr.contains("refined triangles per frame"), "{stderr}");
    // Every element at tess level 18 (486 triangles each): 2.8 M triangles, a second or so.
    let spot = model_path("spot_tri.obj");
    #[rustfmt::skip]
    let (stdout, stderr) = bench(&[
        p(&spot), "--pixel-error", "0.0001", "--drivers", "tess", "--surfaces", "pn",
        "--max-level", "18", "--geomorph", "off", "--cull", "off",
    ]);
    let (header, rows) = summary_table(&stdout);
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    let adaptive = &rows[0];
    assert_eq!(adaptive[column("level")], "18", "{stdout}");
    let warned = format!(
        "warning: {} refined triangles per frame on a software device",
        adaptive[column("refined tris")]
    );
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(warnings[0].starts_with(&warned), "{stderr}");
    assert!(
        warnings[0].ends_with(
            "s a frame (100 to 400 ns a triangle there); a larger --pixel-error or a smaller --max-level draws faster"
        ),
        "{stderr}"
    );
}

/// A blank image whose elements culling removed says so, without suggesting `--cull off`
/// (culling removes nothing visible: the same image is blank without it).
#[test]
fn a_blank_image_of_culled_elements_blames_culling() {
    let png = tmp("culled-away.png");
    // Spot's centre is near the origin: this camera looks away from it.
    #[rustfmt::skip]
    let args = ["render", "-o", p(&png), "--pixel-error", "1", "--width", "160", "--height", "100",
        "--eye", "3,0,0", "--look-at", "6,0,0"];
    expect_error(
        &args,
        &[
            "is blank",
            "culling removed all 372 elements: the camera given by --eye and --look-at sees none of them",
        ],
    );
    // What was chosen is said first, as for an image that shows the mesh; a camera placed by
    // one option is named by that option alone.
    let out = meshrefine(&args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        stdout.trim_end(),
        "adaptive at 1 px, max level 64: levels (level:elements) none; culled 372"
    );
    // Every element lies outside the view (none is counted as facing away: the level pass's
    // mirror tells them apart, `culling_follows_the_spheres_and_cones`), and --cull off would
    // draw the same blank image.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("--cull off") && !stderr.contains("face away"),
        "{stderr}"
    );
    let mut uncull = args.to_vec();
    uncull.extend(["--cull", "off"]);
    expect_error(&uncull, &["is blank"]);
    // Nothing drawn: a tiny image's samples did not miss anything, and --msaa is not blamed.
    #[rustfmt::skip]
    let tiny = ["render", "-o", p(&png), "--width", "2", "--height", "2", "--eye", "3,0,0",
        "--look-at", "6,0,0"];
    let out = meshrefine(&tiny);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("culling removed all 372 elements"),
        "{stderr}"
    );
    assert!(!stderr.contains("--msaa"), "{stderr}");
    #[rustfmt::skip]
    let look_away = ["render", "-o", p(&png), "--width", "64", "--height", "64",
        "--look-at", "1e11,0,0"];
    expect_error(
        &look_away,
        &["culling removed all 372 elements: the camera given by --look-at sees none of them"],
    );
    // An open surface shows its back side: its elements facing away are not culled, and the
    // open grid, seen from below by the framing camera, is drawn.
    let grid = model_path("grid_open_8x8.obj");
    #[rustfmt::skip]
    let below = ok(&["render", p(&grid), "-o", p(&png), "--pixel-error", "1", "--cull", "on",
        "--width", "160", "--height", "100"]);
    assert!(below.contains("culled 0"), "{below}");
}

/// `bench --heightmap FILE.png` times the map it names: on the textured grid at 1 px a flat
/// map draws far fewer triangles adaptively than the generated bumps; a file it cannot read is
/// one sentence naming it, exit 1.
#[test]
fn bench_reads_a_height_map_file() {
    let grid = model_path("grid_uv_8x8.obj");
    let flat = gray_png("bench-flat.png", 8, 8, &[128; 64]);
    let triangles = |extra: &[&str]| {
        let prefix = tmp(&format!("bench-hm-{}", extra.len()));
        #[rustfmt::skip]
        let mut args = vec![
            "bench", p(&grid), "--frames", "1", "--width", "160", "--height", "90",
            "--pixel-error", "1", "--surfaces", "flat", "--displacements", "heightmap",
            "--drivers", "static", "--levels", "2", "--out", p(&prefix),
        ];
        args.extend(extra);
        ok(&args);
        let csv = std::fs::read_to_string(format!("{}.csv", p(&prefix))).unwrap();
        let mut lines = csv.lines();
        let keys = common::csv_fields(lines.next().unwrap());
        let col = |key: &str| keys.iter().position(|k| k == key).unwrap();
        let row = (lines.map(common::csv_fields))
            .find(|r| r[col("adaptive")] == "true")
            .unwrap_or_else(|| panic!("no adaptive row: {csv}"));
        row[col("refined_triangles")].parse::<u64>().unwrap()
    };
    let bumps = triangles(&[]);
    let level = triangles(&["--heightmap", p(&flat)]);
    assert!(
        level * 4 < bumps,
        "flat map {level}, generated bumps {bumps}"
    );
    expect_error(
        &[
            "bench",
            p(&grid),
            "--displacements",
            "heightmap",
            "--heightmap",
            "no-such-map.png",
        ],
        &["cannot read height map 'no-such-map.png'"],
    );
}

/// A bench row's pixel error is the one given, however small: `1e-6` in the summary, the
/// markdown, the CSV and the JSON (a number there), not rounded to 0.
#[test]
fn bench_keeps_the_pixel_error_given() {
    let prefix = tmp("bench-tiny-px");
    let prefix = p(&prefix);
    let tet = model_path("tetrahedron.obj");
    #[rustfmt::skip]
    let out = ok(&[
        "bench", p(&tet), "--frames", "1", "--width", "32", "--height", "32", "--levels", "1",
        "--pixel-error", "1e-6", "--max-level", "2", "--drivers", "tess", "--out", prefix,
    ]);
    let csv = std::fs::read_to_string(format!("{prefix}.csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let col = keys.iter().position(|k| k == "pixel_error").unwrap();
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    assert!(rows.iter().any(|r| r[col] == "1e-6"), "{csv}");
    let json = std::fs::read_to_string(format!("{prefix}.json")).unwrap();
    assert!(json.contains("\"pixel_error\":1e-6"), "{json}");
    let md = std::fs::read_to_string(format!("{prefix}.md")).unwrap();
    assert!(md.contains("| 1e-6 |"), "{md}");
    // The summary names what every row shares once.
    assert!(out.contains(", px 1e-6."), "{out}");
}

/// A benchmark row whose every element was culled draws no triangle: no time per triangle, and
/// its note says why.
#[test]
fn bench_rows_with_every_element_culled_have_no_time_per_triangle() {
    let prefix = tmp("bench-culled");
    let prefix = p(&prefix);
    // A camera looking away from Spot.
    #[rustfmt::skip]
    let out = ok(&[
        "bench", "--frames", "1", "--width", "160", "--height", "90", "--levels", "2",
        "--pixel-error", "1", "--surfaces", "pn", "--drivers", "tess,static", "--out", prefix,
        "--eye", "3,0,0", "--look-at", "6,0,0",
    ]);
    let csv = std::fs::read_to_string(format!("{prefix}.csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let culled: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| get(r, "adaptive") == "true")
        .collect();
    assert_eq!(culled.len(), 2, "{csv}");
    for r in culled {
        assert_eq!(get(r, "refined_triangles"), "0", "{csv}");
        assert_eq!(get(r, "gpu_ns_per_refined_triangle"), "", "{csv}");
        assert!(get(r, "note").starts_with("every element culled"), "{csv}");
    }
    let json = std::fs::read_to_string(format!("{prefix}.json")).unwrap();
    assert!(
        json.contains("\"gpu_ns_per_refined_triangle\":null"),
        "{json}"
    );
    // The summary's cell is a dash.
    let (header, table) = summary_table(&out);
    let col = header.iter().position(|h| h == "ns/tri").unwrap();
    let dashes = table.iter().filter(|r| r[col] == "–").count();
    assert_eq!(dashes, 2, "{out}");
}

/// A camera looking straight down renders the mesh from above (the image's up is -Z), and an
/// adaptive export from it names that up in its header.
#[test]
fn a_camera_can_look_straight_down() {
    let png = tmp("top-down.png");
    let obj = tmp("top-down.obj");
    let camera = [
        "--eye",
        "0,3,0",
        "--look-at",
        "0,0,0",
        "--width",
        "160",
        "--height",
        "120",
    ];
    ok(&[&["render", "-o", p(&png)][..], &camera[..]].concat());
    assert!(covered(&png) > 1000, "{}", covered(&png));
    ok(&[
        &["export", "-o", p(&obj), "--pixel-error", "2"][..],
        &camera[..],
    ]
    .concat());
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(
        text.contains(
            "\n# camera eye 0 3 0 target 0 0 0 up 0 0 -1 fov-y 45 size 160 120 pixel-error 2\n"
        ),
        "{}",
        text.lines().take(6).collect::<Vec<_>>().join("\n")
    );
}

/// Where the pixel error cannot be met, `render` and `export` say so on standard error, with
/// the counts `info` prints: elements whose bound needs a level above `--max-level`, and those
/// at the largest level whatever the pixel error (holding the eye in their bounds, or with no
/// finite bound: Phong corners blending seam normals), checked against the levels drawn with a
/// larger cap.
#[test]
fn render_and_export_say_where_the_pixel_error_is_not_met() {
    let spot = model_path("spot_control_tri.obj");
    let spot = p(&spot);
    let camera = [
        "--eye",
        "0.3,0.2,0.6",
        "--look-at",
        "0,0.1,0.3",
        "--width",
        "320",
        "--height",
        "240",
    ];
    let run = |args: &[&str]| -> (String, String) {
        let out = meshrefine(args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{args:?}: {err}");
        assert!(!err.contains("validation"), "{args:?}: {err}");
        (String::from_utf8_lossy(&out.stdout).into_owned(), err)
    };
    let png = tmp("unmet.png");
    let obj = tmp("unmet.obj");
    // The number a note (or info line) starting with `start` and containing `has` begins with.
    let count = |text: &str, start: &str, has: &str| -> u64 {
        (text.lines())
            .filter(|l| l.contains(has))
            .find_map(|l| l.trim().strip_prefix(start))
            .and_then(|l| l.split_whitespace().next()?.parse().ok())
            .unwrap_or(0)
    };
    // The elements render draws above `level`, from its levels line.
    let above = |stdout: &str, level: u32| -> u64 {
        let line = stdout
            .lines()
            .find(|l| l.starts_with("adaptive at"))
            .unwrap();
        let pairs = line.split("(level:elements) ").nth(1).unwrap();
        (pairs.split(';').next().unwrap().split_whitespace())
            .map(|pair| pair.split_once(':').unwrap())
            .filter(|(l, _)| l.parse::<u32>().unwrap() > level)
            .map(|(_, n)| n.parse::<u64>().unwrap())
            .sum()
    };
    let pn = [&camera[..], &["--surface", "pn", "--pixel-error", "1"]].concat();
    let at = |max: &'static str| [&pn[..], &["--max-level", max]].concat();
    let (free_out, free_err) = run(&[&["render", spot, "-o", p(&png)], &at("64")[..]].concat());
    let (_, capped_err) = run(&[&["render", spot, "-o", p(&png)], &at("8")[..]].concat());
    let capped = count(&capped_err, "note: the 1 px bound is not met on", "");
    // "1 element holds the eye in its bounds", "N elements hold the eye in their bounds".
    let near = |err: &str| count(err, "note:", "the eye in");
    assert!(capped > 0, "{capped_err}");
    assert!(
        capped_err.contains(&format!("note: the 1 px bound is not met on {capped} elements: they need a level above the largest, 8 (--max-level)")),
        "{capped_err}"
    );
    // Every element needing more than 8 is drawn above 8 with the larger cap; some more are
    // drawn there only for a capped neighbour's need on their shared edge, met at 8.
    let (unmet, drawn_above) = (capped + near(&capped_err), above(&free_out, 8));
    assert!(
        unmet <= drawn_above && drawn_above - unmet <= drawn_above / 2,
        "{capped_err}\n{free_out}"
    );
    assert_eq!(
        near(&capped_err),
        near(&free_err),
        "{capped_err}\n{free_err}"
    );
    // With the larger cap only the elements the eye is all but inside stay short of the bound
    // (their free level passes 2^20): fewer than at 8.
    let capped_free = count(&free_err, "note: the 1 px bound is not met on", "");
    assert!(capped_free < capped, "{free_err}");
    // Export culling as render does says the same, and so does info (it culls as render
    // does).
    let export = ["export", spot, "-o", p(&obj), "--cull", "on"];
    let (_, export_err) = run(&[&export[..], &at("8")[..]].concat());
    assert!(
        export_err.contains(&format!("not met on {capped} elements")),
        "{export_err}"
    );
    let (info, _) = run(&[&["info", spot], &at("8")[..]].concat());
    assert_eq!(count(&info, "capped: ", ""), capped, "{info}");
    assert_eq!(count(&info, "near: ", ""), near(&capped_err), "{info}");
    // Phong tessellation whose corners blend seam normals (a mesh with hard edges): no finite
    // bound on those elements, drawn at --max-level, and the note says where to read why.
    let cylinder = model_path("cylinder_hard_normals.obj");
    let phong_args = [
        "--surface",
        "phong",
        "--pixel-error",
        "1",
        "--max-level",
        "4",
        "--width",
        "320",
        "--height",
        "240",
    ];
    let (out, err) = run(&[&["render", p(&cylinder), "-o", p(&png)], &phong_args[..]].concat());
    let line = (err.lines().find(|l| l.contains("no finite error bound")))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(
        line.contains("(docs/adaptivity.md says where none exists): they are drawn at the largest level, 4, whatever --pixel-error"),
        "{line}"
    );
    let n = count(&err, "note:", "no finite error bound");
    assert!(n > 0, "{err}");
    let levels = out.lines().find(|l| l.starts_with("adaptive at")).unwrap();
    let pairs = levels.split("(level:elements) ").nth(1).unwrap();
    let at_max: u64 = (pairs.split(';').next().unwrap().split_whitespace())
        .filter_map(|pair| pair.strip_prefix("4:")?.parse::<u64>().ok())
        .sum();
    assert!(at_max >= n, "{levels}\n{err}");
}

/// Extreme pixel errors print short, and a camera that sees nothing says so in words.
#[test]
fn info_prints_extreme_pixel_errors_and_empty_views_plainly() {
    let tiny = ok(&["info", "--pixel-error", "1e-30", "--max-level", "2"]);
    assert!(tiny.contains("adaptive pn at 1e-30 px:"), "{tiny}");
    // Up to f32's largest: level 1 everywhere, on the CPU (info) and on the GPU (export's
    // header holds the levels its level pass wrote).
    let ico = model_path("icosahedron.obj");
    let obj = tmp("huge-px.obj");
    for px in ["1e38", "2e38", "3.4e38"] {
        let args = [
            "--pixel-error",
            px,
            "--cull",
            "off",
            "--width",
            "64",
            "--height",
            "48",
        ];
        let info = ok(&[&["info", p(&ico)], &args[..]].concat());
        assert!(
            info.contains("levels (level:coarse triangles): 1:20\n"),
            "{info}"
        );
        ok(&[&["export", p(&ico), "-o", p(&obj)], &args[..]].concat());
        let text = std::fs::read_to_string(&obj).unwrap();
        assert!(text.contains("\n# levels 1:20\n"), "{px}");
    }
    let away = ok(&[
        "info",
        "--pixel-error",
        "1",
        "--eye",
        "5,0,0",
        "--look-at",
        "10,0,0",
    ]);
    assert!(
        away.contains("levels (level:coarse triangles): none (every element culled)"),
        "{away}"
    );
    assert!(
        away.contains("culled (outside the view or facing away): 372"),
        "{away}"
    );
    assert!(
        away.contains("refined triangles: none drawn") && !away.contains("0.00x"),
        "{away}"
    );
    let png = tmp("tiny.png");
    let out = meshrefine(&[
        "render",
        "-o",
        p(&png),
        "--pixel-error",
        "1e-30",
        "--max-level",
        "2",
        "--width",
        "64",
        "--height",
        "48",
    ]);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(
        stdout.contains("adaptive at 1e-30 px, max level 2"),
        "{stdout}"
    );
    assert!(
        stderr.contains("note: the 1e-30 px bound is not met on"),
        "{stderr}"
    );
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

/// A value given twice in `bench`'s lists is timed once, as a driver given twice is.
#[test]
fn bench_lists_time_each_value_once() {
    let prefix = tmp("bench-dedup");
    let p = prefix.display().to_string();
    #[rustfmt::skip]
    ok(&[
        "bench", "--surfaces", "flat,pn,flat", "--displacements", "none,none", "--levels", "2,2",
        "--drivers", "static,static", "--frames", "1", "--width", "64", "--height", "48",
        "--out", &p,
    ]);
    let csv = std::fs::read_to_string(prefix.with_extension("csv")).unwrap();
    // flat and pn, at level 2, static: two rows.
    assert_eq!(csv.lines().count(), 1 + 2, "{csv}");
}

/// What `info` says on standard error of a file `name` holding `text`, which loads.
fn info_stderr(name: &str, text: &[u8]) -> String {
    let path = write(name, text);
    let out = meshrefine(&["info", p(&path)]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{name}: {stderr}");
    stderr
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
