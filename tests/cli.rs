//! The command line, run as a user would: bad input gets one clear sentence and a non-zero exit
//! status, never a panic, a hang or a validation message; good input works with the validation
//! layer on (`--validate` makes any validation message or leak an error).

mod common;

use common::model_path;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn meshrefine(args: &[&str]) -> Output {
    let _guard = common::gpu_lock();
    Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("run meshrefine")
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
        &["65", "maxTessellationGenerationLevel"],
    );
    expect_error(
        &[
            "render",
            p(&model_path("spot_tri.obj")),
            "--driver",
            "static",
            "--level",
            "512",
            "-o",
            p(&out),
        ],
        &["maxMemoryAllocationSize", "level 512"],
    );
    expect_error(
        &["render", "--device", "no-such-gpu-anywhere", "-o", p(&out)],
        &["no-such-gpu-anywhere", "available"],
    );
    expect_error(&["render", "-o", p(&out), "--width", "0"], &["0x720"]);
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

#[test]
fn info_reports_topology_and_footprint() {
    let s = ok(&["info", p(&model_path("nonmanifold_edge.obj"))]);
    assert!(s.contains("non-manifold edges: 1"), "{s}");
    let s = ok(&["info", p(&model_path("grid_open_8x8.obj")), "--level", "64"]);
    assert!(s.contains("vertices: 81"), "{s}");
    assert!(s.contains("triangles: 128"), "{s}");
    assert!(s.contains("boundary edges: 32"), "{s}");
    assert!(s.contains("valence histogram"), "{s}");
    // 128 coarse triangles x 4096 = 524288 refined triangles; static holds 128 x 2145 vertices.
    assert!(s.contains("524288 refined triangles"), "{s}");
    let static_bytes = 128u64 * 2145 * 24 + (128 * (4287 + 1) - 1) * 4;
    assert!(
        s.contains(&format!("static {static_bytes:>15}")) || s.contains(&static_bytes.to_string()),
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
    // A display that cannot be reached: the same fallback, saying so.
    std::fs::remove_file(&view_png).unwrap();
    let _guard = common::gpu_lock();
    let o = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args(["view", "--headless-output", p(&view_png), "--level", "3"])
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
    for variant in [
        "static",
        "pattern/push",
        "pattern/ubo",
        "pattern/instanced",
        "tess",
    ] {
        let rows = s
            .lines()
            .filter(|l| l.contains(&format!("| {variant} |")))
            .count();
        assert_eq!(rows, 2, "{variant}: one row per level in\n{s}");
    }
    // static is the reference of the ratios.
    assert!(
        s.lines()
            .filter(|l| l.contains("| static |"))
            .all(|l| l.contains("| 1.00 | 1.00 |")),
        "{s}"
    );
}
