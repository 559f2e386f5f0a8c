//! One default camera everywhere: `info`, `bench`, `render` and adaptive `export` choose their
//! levels for the same camera (fitted to the surface as drawn, displacement included) and cull
//! alike, and `--fov` without `--eye` fits that camera at the field of view given. Run as a user
//! would, with the validation layer on.

mod common;

use common::model_path;
use std::path::PathBuf;
use std::process::Output;

/// The binary, validated, without a display.
fn meshrefine(args: &[&str]) -> Output {
    common::validated_cli(args)
}

fn tmp(name: &str) -> String {
    common::tmp_file("cli-camera", name)
}

/// Runs `args`, expects success without a validation message; returns stdout.
fn ok(args: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `info`'s `levels (level:...): L:n ...` histogram.
fn info_histogram(stdout: &str) -> String {
    let line = (stdout.lines())
        .find(|l| l.trim_start().starts_with("levels ("))
        .unwrap_or_else(|| panic!("no levels line in:\n{stdout}"));
    line.split_once("): ").unwrap().1.trim().to_string()
}

/// `info`'s count after `name: ` (0 when the line is not printed).
fn info_count(stdout: &str, name: &str) -> u64 {
    (stdout.lines())
        .find_map(|l| l.trim().strip_prefix(&format!("{name}: ")))
        .map_or(0, |rest| {
            rest.split_whitespace().next().unwrap().parse().unwrap()
        })
}

/// The `# levels` header line of an exported OBJ.
fn export_histogram(obj: &str) -> String {
    let text = std::fs::read_to_string(obj).unwrap();
    let line = (text.lines().take(12))
        .find_map(|l| l.strip_prefix("# levels "))
        .unwrap_or_else(|| panic!("no levels header in {obj}"));
    line.trim().to_string()
}

/// render's `levels (level:elements) H; culled N` as (H, N).
fn render_histogram(stdout: &str) -> (String, u64) {
    let line = (stdout.lines())
        .find_map(|l| l.split_once("levels (level:elements) ").map(|(_, r)| r))
        .unwrap_or_else(|| panic!("no adaptive line in:\n{stdout}"));
    let (h, culled) = line.split_once("; culled ").unwrap();
    (h.trim().to_string(), culled.trim().parse().unwrap())
}

/// The `level_histogram` column of every row of a bench CSV.
fn bench_histograms(csv: &str) -> Vec<String> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|c| *c == "level_histogram").unwrap();
    // The first field (the device) is quoted and holds commas: count from the end.
    let from_end = header.len() - column;
    lines
        .map(|l| {
            let fields: Vec<&str> = l.split(',').collect();
            fields[fields.len() - from_end].to_string()
        })
        .collect()
}

#[test]
fn info_bench_render_and_export_choose_the_same_levels() {
    let spot = model_path("spot_control_tri.obj");
    let torus = model_path("torus_16x8.obj");
    let grid = model_path("grid_uv_8x8.obj");
    let size = ["--width", "160", "--height", "120"];
    // A plain surface, displaced ones (the camera fits the displaced surface; the height map
    // read at the mesh's texture coordinates), a field of view (the camera is fitted at it)
    // and a lone eye (completed from the fitted camera).
    // And the other roundings: the tessellator's, the pattern driver's integer levels.
    let cases: [(&PathBuf, &[&str]); 7] = [
        (&spot, &["--pixel-error", "1"]),
        (&torus, &["--pixel-error", "1", "--displace", "sine"]),
        (&grid, &["--pixel-error", "0.5", "--displace", "heightmap"]),
        (&spot, &["--pixel-error", "2", "--fov", "70"]),
        (&torus, &["--pixel-error", "1", "--eye", "0.5,2,3"]),
        (&spot, &["--pixel-error", "1", "--driver", "tess"]),
        (&torus, &["--pixel-error", "1", "--geomorph", "off"]),
    ];
    for (i, (mesh, options)) in cases.into_iter().enumerate() {
        let mesh = mesh.to_str().unwrap();
        let with = |command: &str, extra: &[&str]| -> Vec<String> {
            [&[command, mesh][..], options, &size, extra]
                .concat()
                .into_iter()
                .map(String::from)
                .collect()
        };
        let run = |args: Vec<String>| ok(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let info = run(with("info", &[]));
        let levels = info_histogram(&info);
        let culled = info_count(&info, "culled (outside the view or facing away)");
        // render: its adaptive line (culling on, as info's default).
        let png = tmp(&format!("same-{i}.png"));
        let (drawn, render_culled) = render_histogram(&run(with("render", &["-o", &png])));
        assert_eq!(
            (&drawn, render_culled),
            (&levels, culled),
            "{options:?}:\n{info}"
        );
        // Adaptive export culls only with --cull on: then its header is info's histogram.
        let obj = tmp(&format!("same-{i}.obj"));
        run(with("export", &["--cull", "on", "-o", &obj]));
        assert_eq!(export_histogram(&obj), levels, "{options:?}");
        // Without culling on either side, every element is counted.
        let all = info_histogram(&run(with("info", &["--cull", "off"])));
        run(with("export", &["-o", &obj]));
        assert_eq!(export_histogram(&obj), all, "{options:?}");
        // bench draws the same view: its histogram column on every pattern row.
        let prefix = tmp(&format!("same-{i}"));
        let bench = with(
            "bench",
            &[
                "--frames",
                "1",
                "--surfaces",
                "pn",
                "--drivers",
                "pattern",
                "--no-bound-levels",
                "--out",
                &prefix,
            ],
        );
        let mut bench = bench;
        // bench names its surfaces, displacements and drivers in the plural.
        if let Some(d) = bench.iter().position(|a| a == "--displace") {
            bench[d] = "--displacements".into();
        }
        if let Some(d) = bench.iter().position(|a| a == "--driver") {
            let pattern = bench.iter().position(|a| a == "--drivers").unwrap();
            bench.drain(pattern..pattern + 2);
            bench[d] = "--drivers".into();
        }
        run(bench);
        let rows = bench_histograms(&format!("{prefix}.csv"));
        assert!(!rows.is_empty());
        for row in rows {
            assert_eq!(row, levels, "{options:?}");
        }
    }
}

#[test]
fn info_culls_faces_facing_away_as_render_does() {
    // Spot is closed and wound outwards: from the default camera some elements face away,
    // and info counts them culled unless --cull off, as render does.
    let spot = model_path("spot_control_tri.obj");
    let spot = spot.to_str().unwrap();
    let info = ok(&["info", spot, "--pixel-error", "1"]);
    let culled = info_count(&info, "culled (outside the view or facing away)");
    assert!(culled > 0, "{info}");
    let off = ok(&["info", spot, "--pixel-error", "1", "--cull", "off"]);
    assert_eq!(
        info_count(&off, "culled (outside the view or facing away)"),
        0
    );
    // An open mesh shows its back side: nothing faces away.
    let grid = model_path("wavy_grid_10x10.obj");
    let grid = ok(&["info", grid.to_str().unwrap(), "--pixel-error", "1"]);
    assert_eq!(
        info_count(&grid, "culled (outside the view or facing away)"),
        0
    );
    // The options that change the drawn surface are read only with --pixel-error.
    let out = meshrefine(&["info", spot, "--displace", "sine", "--cull", "off"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("--displace applies only with --pixel-error")
            && stderr.contains("--cull applies only with --pixel-error"),
        "{stderr}"
    );
    // Bad values are one sentence, status 1.
    let out = meshrefine(&[
        "info",
        spot,
        "--pixel-error",
        "1",
        "--displace",
        "sine",
        "--amplitude",
        "nan",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        stderr.trim(),
        "error: --amplitude nan is not a finite number",
        "{stderr}"
    );
}

/// Decoded RGBA pixels of a PNG and its size.
fn decode(path: &str) -> (Vec<u8>, u32, u32) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba, "{path}");
    buf.truncate(info.buffer_size());
    (buf, info.width, info.height)
}

/// The bounding box (x0, x1, y0, y1) of the pixels unlike the top-left one (the background),
/// and their count.
fn covered_box(path: &str) -> ((u32, u32, u32, u32), usize) {
    let (px, w, h) = decode(path);
    let at = |x: u32, y: u32| &px[((y * w + x) * 4) as usize..][..4];
    let background = at(0, 0).to_vec();
    let (mut b, mut n) = ((u32::MAX, 0, u32::MAX, 0), 0);
    for y in 0..h {
        for x in 0..w {
            if at(x, y) != background.as_slice() {
                b = (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y));
                n += 1;
            }
        }
    }
    (b, n)
}

#[test]
fn fov_without_eye_fits_the_camera_at_that_field_of_view() {
    let (w, h) = (160u32, 120u32);
    let render = |fov: &str| {
        let png = tmp(&format!("fov-{fov}.png"));
        let (ws, hs) = (w.to_string(), h.to_string());
        ok(&[
            "render", "-o", &png, "--width", &ws, "--height", &hs, "--fov", fov,
        ]);
        covered_box(&png)
    };
    // Spot at 4:3 is fitted by its height: at any field of view its silhouette spans the
    // image's height up to the margin (FIT_MARGIN of the half-height, 4.8 px here) and stays
    // clear of the side borders, as at 45 degrees.
    let margin = meshrefine::render::FIT_MARGIN * h as f32 * 0.5;
    let (_, at45) = render("45");
    for fov in ["20", "45", "90"] {
        let ((x0, x1, y0, y1), n) = render(fov);
        let near = |v: u32, want: f32| (v as f32 - want).abs() <= 3.0;
        assert!(
            near(y0, margin) && near(y1, h as f32 - 1.0 - margin),
            "--fov {fov}: rows {y0}..{y1}"
        );
        assert!(x0 > 0 && x1 < w - 1, "--fov {fov}: columns {x0}..{x1}");
        // As much of the image covered as at 45 degrees, give or take the perspective.
        assert!(n * 10 > at45 * 7, "--fov {fov}: {n} pixels against {at45}");
    }
    // Wide fields of view keep the eye outside every element's reach, so no element holds the
    // eye (no note says so) and the mesh lies wholly in front of the near plane: the eye stays
    // back, and the mesh, centred, takes a smaller part of the image the wider the angle.
    for (fov, least_rows) in [("150", 0.2), ("170", 0.05)] {
        let png = tmp(&format!("fov-{fov}.png"));
        let (ws, hs) = (w.to_string(), h.to_string());
        let out = meshrefine(&[
            "render", "-o", &png, "--width", &ws, "--height", &hs, "--fov", fov,
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "--fov {fov}: {stderr}");
        assert!(!stderr.contains("note:"), "--fov {fov}: {stderr}");
        let ((x0, x1, y0, y1), n) = covered_box(&png);
        assert!(n > 0, "--fov {fov}: blank");
        assert!(
            (y1 - y0 + 1) as f32 >= least_rows * h as f32,
            "--fov {fov}: rows {y0}..{y1}"
        );
        // Centred (on the sampled points; perspective and the silhouette between them shift
        // the drawn box a little).
        let centre = |a: u32, b: u32, size: u32| {
            ((a + b) as f32 - (size - 1) as f32).abs() <= 0.15 * size as f32
        };
        assert!(
            centre(x0, x1, w) && centre(y0, y1, h),
            "--fov {fov}: not centred: {x0}..{x1}, {y0}..{y1}"
        );
    }
    // Near 180 degrees the mesh, in front of the eye and centred, is smaller than a pixel: the
    // image is blank, which is an error that says so (and still no element holds the eye).
    let png = tmp("fov-179.99.png");
    let out = meshrefine(&[
        "render", "-o", &png, "--width", "160", "--height", "120", "--fov", "179.99",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("is blank") && !stderr.contains("note:"),
        "{stderr}"
    );
}

/// The command transcripts of docs/adaptivity.md ("Trying it") are what the commands print:
/// each `$ meshrefine ...` line of its code blocks is run (through `sh`, in a folder of its own
/// holding a link to `assets`, the validation layer on), and the lines shown under it, but for
/// `...` (lines left out), appear in its output in that order.
#[test]
fn the_adaptivity_guides_transcripts_are_what_the_commands_print() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(root.join("docs/adaptivity.md")).unwrap();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("guide-transcripts");
    std::fs::create_dir_all(&dir).unwrap();
    let assets = dir.join("assets");
    if !assets.exists() {
        std::os::unix::fs::symlink(root.join("assets"), &assets).unwrap();
    }
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_meshrefine"));
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    // (command, the lines shown under it)
    let mut runs: Vec<(String, Vec<String>)> = Vec::new();
    let mut in_block = false;
    for line in guide.lines() {
        if line.starts_with("```") {
            in_block = !in_block;
            continue;
        }
        if !in_block {
            continue;
        }
        if let Some(command) = line.strip_prefix("$ ") {
            runs.push((command.to_string(), Vec::new()));
        } else if let Some((_, shown)) = runs.last_mut() {
            shown.push(line.to_string());
        }
    }
    assert!(runs.len() >= 10, "only {} transcripts found", runs.len());
    for (command, shown) in &runs {
        assert!(command.starts_with("meshrefine "), "{command}");
        let out = {
            let _guard = common::gpu_lock();
            std::process::Command::new("sh")
                .args(["-c", command])
                .current_dir(&dir)
                .env("PATH", &path)
                .env("MESHREFINE_VALIDATE", "1")
                .env_remove("DISPLAY")
                .env_remove("WAYLAND_DISPLAY")
                .output()
                .unwrap()
        };
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{command}: {stderr}");
        assert!(!stderr.contains("validation"), "{command}: {stderr}");
        let stdout = String::from_utf8_lossy(&out.stdout);
        let mut printed = stdout.lines();
        for want in shown.iter().filter(|l| l.trim() != "...") {
            assert!(
                printed.any(|l| l == want),
                "{command}: '{want}' is not printed (in that order):\n{stdout}"
            );
        }
    }
}

/// Distance, not depth: turning the camera about its eye changes no level. From one eye,
/// looking at the mesh, away from it and sideways, culling off, `info` prints the same
/// histogram and `export` the same levels; at integer levels (`--geomorph off`) the same
/// vertices bit for bit. Gliding levels follow the eye continuously, and the camera is rebuilt
/// from its target, distance and direction (docs/cli.md), so the eye moves by single-precision
/// rounding as the target changes: their vertices agree to within 1e-5 (Spot's control mesh
/// is about 2 units across).
#[test]
fn turning_the_camera_changes_no_level() {
    let spot = model_path("spot_control_tri.obj");
    let spot = spot.to_str().unwrap();
    let eye = "0.3,0.6,-1.4";
    for geomorph in ["off", "on"] {
        let mut exports: Vec<(Vec<String>, Vec<f32>)> = Vec::new();
        let mut histograms = Vec::new();
        for (i, target) in ["0,0.5,-0.5", "0.3,0.6,-3", "2,0.6,-1.4"]
            .into_iter()
            .enumerate()
        {
            #[rustfmt::skip]
            let camera = [
                "--pixel-error", "1", "--eye", eye, "--look-at", target, "--cull", "off",
                "--width", "320", "--height", "240", "--geomorph", geomorph,
            ];
            let obj = tmp(&format!("turned-{geomorph}-{i}.obj"));
            let mut args = vec!["export", spot, "-o", &obj];
            args.extend(camera);
            ok(&args);
            let text = std::fs::read_to_string(&obj).unwrap();
            // Everything but the camera and command lines, and the coordinates apart.
            let (mut lines, mut coords) = (Vec::new(), Vec::new());
            for l in text.lines() {
                if l.starts_with("# camera") || l.starts_with("# command") {
                    continue;
                }
                match l.strip_prefix("v ") {
                    Some(v) => coords.extend(v.split(' ').map(|x| x.parse::<f32>().unwrap())),
                    None => lines.push(l.to_string()),
                }
            }
            exports.push((lines, coords));
            let mut args = vec!["info", spot];
            args.extend(camera);
            histograms.push(info_histogram(&ok(&args)));
        }
        let (lines, coords) = &exports[0];
        // Levels that differ between elements, so the same levels are no accident.
        let histogram = (lines.iter())
            .find_map(|l| l.strip_prefix("# levels "))
            .unwrap_or_else(|| panic!("no levels line: {:?}", &lines[..4]));
        assert!(histogram.split_whitespace().count() >= 3, "{histogram}");
        assert!(coords.len() > 3000, "{} coordinates", coords.len());
        for ((l, c), h) in exports.iter().zip(&histograms).skip(1) {
            assert_eq!(h, &histograms[0]);
            assert!(l == lines, "geomorph {geomorph}: other levels or triangles");
            assert_eq!(c.len(), coords.len());
            let moved = (c.iter().zip(coords))
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f32::max);
            let most = if geomorph == "off" { 0.0 } else { 1e-5 };
            assert!(
                moved <= most,
                "geomorph {geomorph}: a vertex moved by {moved}"
            );
        }
    }
}

/// The pictures' captions in docs/adaptivity.md ("What it looks like") count what their
/// command draws: each caption's `render ...` command, run (from the repository, the
/// validation layer on), prints the caption's `levels L:n ...` and culls as many elements as
/// the caption says.
#[test]
fn the_adaptivity_guides_captions_count_what_their_commands_draw() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(root.join("docs/adaptivity.md")).unwrap();
    let start = guide.find("## What it looks like").unwrap();
    let end = start + guide[start..].find("\n## ").unwrap();
    let section = guide[start..end].replace('\n', " ");
    let mut checked = 0;
    for caption in section.split("*").skip(1).step_by(2) {
        let Some(cmd) = caption
            .split('`')
            .nth(1)
            .and_then(|c| c.strip_prefix("render "))
        else {
            continue;
        };
        let levels = caption
            .split("levels ")
            .filter_map(|s| s.split(')').next())
            .find(|s| s.split(' ').all(|p| p.split_once(':').is_some()))
            .unwrap_or_else(|| panic!("no levels in the caption of {cmd}"));
        let culled: u32 = caption
            .split_whitespace()
            .collect::<Vec<_>>()
            .windows(3)
            .find_map(|w| match w {
                [n, "elements", "outside"] | [n, "of", "the"] => n.parse().ok(),
                _ => None,
            })
            .unwrap_or_else(|| panic!("no culled count in the caption of {cmd}"));
        let png = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("caption.png");
        let mut args: Vec<&str> = vec!["render"];
        args.extend(cmd.split_whitespace());
        args.extend(["-o", png.to_str().unwrap()]);
        let out = {
            let _guard = common::gpu_lock();
            std::process::Command::new(env!("CARGO_BIN_EXE_meshrefine"))
                .args(&args)
                .current_dir(&root)
                .env("MESHREFINE_VALIDATE", "1")
                .output()
                .unwrap()
        };
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success() && !stderr.contains("validation"),
            "{cmd}: {stderr}"
        );
        let stdout = String::from_utf8_lossy(&out.stdout);
        let want = format!("levels (level:elements) {levels}; culled {culled}");
        assert!(stdout.contains(&want), "{cmd}: '{want}' not in\n{stdout}");
        checked += 1;
    }
    assert!(checked >= 2, "only {checked} captions found");
}
