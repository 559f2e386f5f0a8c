//! Defaults and output formats that docs/cli.md and `--help` promise, run as a user would (the
//! validation layer on, no display): where the headless `view` writes its image, what `bench`
//! times when told nothing, export's header lines, and the displacement and Phong defaults.

mod common;

use common::cli::model_arg as model;
use std::process::Output;

fn meshrefine(args: &[&str]) -> Output {
    common::validated_cli(args)
}

fn tmp(name: &str) -> String {
    common::tmp_file("cli-defaults", name)
}

/// The fields of a CSV line (quoted fields hold commas; `""` is a quote).
fn fields(line: &str) -> Vec<String> {
    let (mut out, mut field, mut quoted) = (Vec::new(), String::new(), false);
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    out.push(field);
    out
}

/// Runs `args`, expects success without a validation message; returns standard output.
fn ok(args: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The vertex positions of an OBJ file.
fn positions(path: &str) -> Vec<[f64; 3]> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// The largest coordinate difference between two exports of the same vertices.
fn largest_difference(a: &str, b: &str) -> f64 {
    let (a, b) = (positions(a), positions(b));
    assert_eq!(a.len(), b.len());
    (a.iter().zip(&b))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, f64::max)
}

/// Without a display and without `--headless-output`, `view` writes `meshrefine-view.png` in
/// the current folder and says where, in full.
#[test]
fn headless_view_writes_meshrefine_view_png_by_default() {
    let dir = std::path::PathBuf::from(tmp("view-default"));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("meshrefine-view.png");
    let _ = std::fs::remove_file(&png);
    let _guard = common::gpu_lock();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .current_dir(&dir)
        .env("MESHREFINE_VALIDATE", "1")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args(["view", "--level", "1", "--width", "64", "--height", "48"])
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");
    assert!(png.exists(), "{stdout}");
    // The path is said in full: the current folder joined.
    let said = stdout
        .trim_end()
        .split_once("rendered the scene headlessly to ");
    let said = said.map(|(_, p)| std::path::PathBuf::from(p));
    assert!(
        said.is_some_and(|p| p.is_absolute() && p.ends_with("view-default/meshrefine-view.png")),
        "{stdout}"
    );
}

/// `bench` told nothing but the mesh and where to write times levels 8, 16, 32 and 64 of the
/// flat surface without displacement, five timed frames each, on every driver.
#[test]
fn bench_defaults_are_the_documented_ones() {
    let prefix = tmp("bench-defaults");
    let out = ok(&[
        "bench",
        &model("tetrahedron.obj"),
        "--width",
        "32",
        "--height",
        "32",
        "--out",
        &prefix,
    ]);
    let csv = std::fs::read_to_string(format!("{prefix}.csv")).unwrap();
    let mut lines = csv.lines();
    let header = fields(lines.next().unwrap());
    let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let rows: Vec<Vec<String>> = lines.map(fields).collect();
    let mut levels: Vec<&str> = rows.iter().map(|r| r[column("level")].as_str()).collect();
    levels.dedup();
    assert_eq!(levels, ["8", "16", "32", "64"], "{csv}");
    assert!(rows.iter().all(|r| r[column("surface")] == "flat"), "{csv}");
    assert!(
        rows.iter().all(|r| r[column("displace")] == "none"),
        "{csv}"
    );
    // Every driver: static, the pattern driver's three submissions and tess, at every level.
    assert_eq!(rows.len(), 4 * 5, "{csv}");
    let md = std::fs::read_to_string(format!("{prefix}.md")).unwrap();
    assert!(md.contains("of 5 timed frames"), "{md}");
    // The summary is wrapped at 120 columns, where a device's name puts the breaks.
    let said = out.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(said.contains("of 5 timed frames"), "{out}");
}

/// Export's first lines name the mesh, the technique and the device, then the counts written;
/// an adaptive export adds its camera and levels.
#[test]
fn export_header_names_mesh_technique_and_device() {
    let obj = tmp("header.obj");
    ok(&[
        "export",
        &model("tetrahedron.obj"),
        "--driver",
        "tess",
        "--surface",
        "flat",
        "--level",
        "3",
        "-o",
        &obj,
    ]);
    let text = std::fs::read_to_string(&obj).unwrap();
    let head: Vec<&str> = text.lines().take(3).collect();
    assert_eq!(
        head[0],
        "# meshrefine export of 'tetrahedron': surface flat, displacement none, driver tess, level 3"
    );
    assert!(
        head[1].starts_with("# evaluated on ") && head[1].len() > 20,
        "{}",
        head[1]
    );
    let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
    assert_eq!(
        head[2],
        format!(
            "# {} vertices, {} normals, {} triangles",
            count("v "),
            count("vn "),
            count("f ")
        )
    );
    // The tessellator's rings at level 3: 13 triangles a patch, 4 patches.
    assert_eq!(count("f "), 52);
    // Last, the command line that made it, options and all.
    let command = text
        .lines()
        .take_while(|l| l.starts_with('#'))
        .last()
        .unwrap();
    assert!(
        command.starts_with("# command: meshrefine export "),
        "{command}"
    );
    assert!(
        command.ends_with(&format!("--level 3 -o {obj}")),
        "{command}"
    );
    ok(&[
        "export",
        &model("tetrahedron.obj"),
        "--surface",
        "pn",
        "--displace",
        "sine",
        "--pixel-error",
        "2",
        "-o",
        &obj,
    ]);
    let text = std::fs::read_to_string(&obj).unwrap();
    let first = text.lines().next().unwrap();
    assert_eq!(
        first,
        "# meshrefine export of 'tetrahedron': surface pn, displacement sine, driver pattern/instanced, max level 64"
    );
    assert!(text.lines().any(|l| l.starts_with("# camera eye ")));
    assert!(text.lines().any(|l| l.starts_with("# levels ")));
}

/// `--amplitude` defaults to 3% of the bounding radius and `--frequency` to 24 over it;
/// `--alpha` (Phong tessellation) to 0.75: the same export as with those values written out,
/// and a different one with other values.
#[test]
fn displacement_and_phong_defaults_are_the_documented_ones() {
    let tet = model("tetrahedron.obj");
    let r = common::model("tetrahedron.obj").bounding_radius() as f64;
    let export = |name: &str, extra: &[&str]| {
        let obj = tmp(name);
        let mut args = vec!["export", &tet, "--level", "4", "-o", &obj];
        args.extend_from_slice(extra);
        ok(&args);
        obj
    };
    let sine = ["--surface", "flat", "--displace", "sine"];
    let defaults = export("sine-default.obj", &sine);
    let (amplitude, frequency) = (format!("{}", 0.03 * r), format!("{}", 24.0 / r));
    let written = export(
        "sine-written.obj",
        &[
            &sine[..],
            &["--amplitude", &amplitude, "--frequency", &frequency],
        ]
        .concat(),
    );
    assert!(largest_difference(&defaults, &written) <= 1e-6 * r);
    let doubled = format!("{}", 0.06 * r);
    let other = export(
        "sine-other.obj",
        &[&sine[..], &["--amplitude", &doubled]].concat(),
    );
    assert!(largest_difference(&defaults, &other) > 1e-3 * r);
    let phong = ["--surface", "phong"];
    let defaults = export("phong-default.obj", &phong);
    let written = export(
        "phong-written.obj",
        &[&phong[..], &["--alpha", "0.75"]].concat(),
    );
    assert_eq!(positions(&defaults), positions(&written));
    let other = export(
        "phong-other.obj",
        &[&phong[..], &["--alpha", "0.25"]].concat(),
    );
    assert!(largest_difference(&defaults, &other) > 1e-3 * r);
}

/// An export is evaluated in the drawn frame (centred, unit radius, `f32`) and mapped back: at
/// level 1 of `flat` every written vertex is an input vertex within 4e-7 of the bounding radius
/// (docs/cli.md), not bit for bit.
#[test]
fn exported_corners_come_back_within_rounding_of_the_input() {
    for name in ["terrain_16x16.obj", "halfdisc17_open.obj"] {
        let obj = tmp(&format!("corners-{name}"));
        ok(&[
            "export",
            &model(name),
            "--surface",
            "flat",
            "--level",
            "1",
            "-o",
            &obj,
        ]);
        let input = positions(&model(name));
        let r = common::model(name).bounding_radius() as f64;
        let written = positions(&obj);
        assert_eq!(written.len(), input.len(), "{name}");
        let mut worst = 0.0f64;
        for w in &written {
            let d = (input.iter())
                .map(|p| (0..3).map(|k| (p[k] - w[k]).abs()).fold(0.0, f64::max))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
        assert!(
            worst <= 4e-7 * r,
            "{name}: {worst} from the input (radius {r})"
        );
    }
}

/// The outputs' long forms (`--output`, docs/cli.md), `export` refusing to run without one (a
/// usage error naming it), and the headless `view` naming a single window option it ignores.
#[test]
fn outputs_long_forms_and_a_missing_export_output() {
    let grid = model("grid_open_8x8.obj");
    let out = meshrefine(&["export", &grid, "--level", "1"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--output <FILE.obj>"), "{stderr}");
    let obj = tmp("long-form.obj");
    let _ = std::fs::remove_file(&obj);
    ok(&["export", &grid, "--level", "1", "--output", &obj]);
    assert_eq!(positions(&obj).len(), 81);
    let png = tmp("long-form.png");
    let _ = std::fs::remove_file(&png);
    let size = ["--width", "64", "--height", "48", "--level", "1"];
    ok(&[&["render", &grid, "--output", &png][..], &size[..]].concat());
    assert!(std::path::Path::new(&png).exists());
    let shown = tmp("one-window-option.png");
    let out = meshrefine(
        &[
            &["view", &grid, "--headless-output", &shown, "--fullscreen"][..],
            &size[..],
        ]
        .concat(),
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let warnings: Vec<&str> = (stderr.lines())
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(
        warnings,
        ["warning: --fullscreen applies only to the window and is ignored: no display found (DISPLAY and WAYLAND_DISPLAY are unset)"],
        "{stderr}"
    );
}
