//! `render` and the headless `view` draw adaptively by default (1 px, the driver's largest
//! level), with every driver (static: refined on the CPU); `--level` draws uniformly. Run as a
//! user would, with the validation layer on.

mod common;

use std::process::Output;

/// The binary, validated, without a display.
fn meshrefine(args: &[&str]) -> Output {
    common::validated_cli(args)
}

fn tmp(name: &str) -> String {
    common::tmp_file("cli-default-levels", name)
}

/// Runs `args`, expects success without a validation message; returns (stdout, stderr).
fn ok(args: &[&str]) -> (String, String) {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    (String::from_utf8_lossy(&out.stdout).into_owned(), stderr)
}

const ADAPTIVE_LINE: &str = "adaptive at 1 px, max level 64: levels (level:elements) ";

#[test]
fn render_and_headless_view_are_adaptive_unless_level_is_given() {
    let small = ["--width", "96", "--height", "64"];
    let png = tmp("default.png");
    let mut args = vec!["render", "-o", &png];
    args.extend(small);
    let (stdout, stderr) = ok(&args);
    assert!(stdout.contains(ADAPTIVE_LINE), "{stdout}");
    assert!(!stderr.contains("note:"), "{stderr}");
    // The tessellator's levels are integers up to its limit (lavapipe: 64).
    let mut tess = args.clone();
    tess.extend(["--driver", "tess"]);
    let (stdout, _) = ok(&tess);
    assert!(stdout.contains(ADAPTIVE_LINE), "{stdout}");
    // --level asks for one level everywhere: the level options are then ignored, the camera
    // is not.
    let mut uniform = args.clone();
    uniform.extend(["--level", "4", "--fov", "30", "--max-level", "8"]);
    let (stdout, stderr) = ok(&uniform);
    assert!(!stdout.contains("adaptive at"), "{stdout}");
    assert!(!stderr.contains("--fov applies"), "{stderr}");
    assert!(
        stderr.contains("--max-level applies only when drawing adaptively (with --pixel-error, or by default without --level)"),
        "{stderr}"
    );
    // The camera options apply by default, so they are checked then too.
    let mut bad = args.clone();
    bad.extend(["--fov", "0"]);
    let out = meshrefine(&bad);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: --fov 0"), "{stderr}");

    // The headless view as the window: adaptive unless --level or --lod.
    let view_png = tmp("view.png");
    let (stdout, _) = ok(&["view", "--headless-output", &view_png]);
    assert!(stdout.contains(ADAPTIVE_LINE), "{stdout}");
    assert!(stdout.contains("rendered the scene headlessly"), "{stdout}");
    for uniform in ["--level", "--lod"] {
        let mut args = vec!["view", "--headless-output", &view_png, uniform];
        if uniform == "--level" {
            args.push("4");
        }
        let (stdout, _) = ok(&args);
        assert!(!stdout.contains("adaptive at"), "{args:?}: {stdout}");
    }
    // Uniform, it draws from the camera given too.
    let framed = std::fs::read(&view_png).unwrap();
    let close = ["--eye", "0.35,0.65,-1.3", "--look-at", "0,0.5,-0.5"];
    let args = [
        &["view", "--headless-output", &view_png, "--lod"],
        &close[..],
    ]
    .concat();
    let (_, stderr) = ok(&args);
    // Only --lod's own warning (the window's level by distance; the image uniform at --level).
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].starts_with("warning: --lod chooses levels by distance only in the window"),
        "{stderr}"
    );
    assert_ne!(std::fs::read(&view_png).unwrap(), framed, "--eye ignored");
}

/// The work follows the screen, not the mesh (docs/cli.md): Spot's 5,856-triangle mesh
/// exported at level 4 (93,696 triangles) renders by default with its visible elements at
/// levels 1 and 2, more than half of them culled (outside the view or facing away).
#[test]
fn a_fine_mesh_renders_at_the_levels_its_screen_needs() {
    let fine = tmp("spot-level-4.obj");
    let spot = common::model_path("spot_tri.obj");
    ok(&[
        "export",
        spot.to_str().unwrap(),
        "--level",
        "4",
        "-o",
        &fine,
    ]);
    let png = tmp("spot-level-4.png");
    let (stdout, _) = ok(&["render", &fine, "-o", &png]);
    let histogram = (stdout.split(ADAPTIVE_LINE).nth(1))
        .unwrap_or_else(|| panic!("not adaptive: {stdout}"))
        .lines()
        .next()
        .unwrap();
    let (levels, culled) = histogram.split_once("; culled ").unwrap();
    let counts: Vec<(u32, u64)> = (levels.split_whitespace())
        .map(|t| {
            let (l, n) = t.split_once(':').unwrap();
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    let drawn: u64 = counts.iter().map(|c| c.1).sum();
    let culled: u64 = culled.trim().parse().unwrap();
    assert_eq!(drawn + culled, 93_696, "{stdout}");
    let levels: Vec<u32> = counts.iter().map(|c| c.0).collect();
    assert_eq!(levels, [1, 2], "{stdout}");
    assert!(culled > drawn, "{stdout}");
}

/// The static driver draws adaptively too, by default and with `--pixel-error`, refining on the
/// CPU; `bench` measures its CPU time and uploaded bytes on its adaptive row.
#[test]
fn the_static_driver_draws_adaptively_on_the_cpu() {
    let png = tmp("static.png");
    let small = ["--width", "96", "--height", "64", "--driver", "static"];
    let mut args = vec!["render", "-o", &png];
    args.extend(small);
    let (stdout, stderr) = ok(&args);
    assert!(stdout.contains(ADAPTIVE_LINE), "{stdout}");
    assert!(!stderr.contains("note:"), "{stderr}");
    args.extend([
        "--pixel-error",
        "2",
        "--eye",
        "0.3,0.2,0.6",
        "--look-at",
        "0,0.1,0.3",
    ]);
    let (stdout, _) = ok(&args);
    assert!(
        stdout.contains("adaptive at 2 px, max level 64"),
        "{stdout}"
    );
    // Its largest level is a power of two, as the pattern driver's.
    args.extend(["--max-level", "12"]);
    let out = meshrefine(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("--max-level 12 is not a power of two, as the static driver"),
        "{stderr}"
    );

    let prefix = tmp("bench-static");
    #[rustfmt::skip]
    ok(&[
        "bench", "--surfaces", "pn", "--drivers", "static", "--pixel-error", "1",
        "--max-level", "16", "--levels", "2", "--no-bound-levels", "--frames", "1",
        "--width", "96", "--height", "64", "--out", &prefix,
    ]);
    let csv = std::fs::read_to_string(format!("{prefix}.csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    assert_eq!(rows.len(), 2, "{csv}");
    let (adaptive, uniform) = (&rows[0], &rows[1]);
    assert_eq!(get(adaptive, "adaptive"), "true", "{csv}");
    assert_eq!(get(adaptive, "variant"), "static");
    assert_eq!(get(adaptive, "level_pass_on"), "cpu");
    assert!(
        get(adaptive, "cpu_ms").parse::<f64>().unwrap() > 0.0,
        "{csv}"
    );
    let bytes: u64 = get(adaptive, "upload_bytes").parse().unwrap();
    // Every stored vertex and index was uploaded: position and normal (24 bytes) and, since
    // pn's normal field is evaluated per fragment, the vertex's sample (16 bytes); 4 an index.
    let stored = |k| get(adaptive, k).parse::<u64>().unwrap();
    assert_eq!(
        bytes,
        stored("stored_vertices") * 40 + stored("stored_indices") * 4
    );
    assert_eq!(get(uniform, "adaptive"), "false");
    assert_eq!(get(uniform, "cpu_ms"), "");
    assert_eq!(get(uniform, "upload_bytes"), "");
}

/// The pattern driver's adaptive rows count the patterns they draw from: up to level 16 the
/// hierarchy's 153 vertices (the finest level's) and the hierarchy's 1,023 indices while geomorphing, every
/// integer level's 968 vertices and 4,488 indices without; the uniform row its own level's
/// pattern. Each with the records in `geometry_bytes`.
#[test]
fn bench_counts_the_patterns_adaptive_pattern_rows_draw_from() {
    use meshrefine::pattern::{index_count, vertex_count};
    for (geomorph, stored) in [("on", (153, 1023)), ("off", (968, 4488))] {
        let prefix = tmp(&format!("bench-pattern-{geomorph}"));
        #[rustfmt::skip]
        ok(&[
            "bench", "--surfaces", "pn", "--drivers", "pattern", "--pixel-error", "2", "--max-level", "16", "--geomorph", geomorph, "--levels", "2",
            "--no-bound-levels", "--frames", "1", "--width", "96", "--height", "64", "--out",
            &prefix,
        ]);
        let csv = std::fs::read_to_string(format!("{prefix}.csv")).unwrap();
        let mut lines = csv.lines();
        let keys = common::csv_fields(lines.next().unwrap());
        let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
        let field =
            |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
        let get = |r: &Vec<String>, key: &str| -> u64 { field(r, key).parse().unwrap() };
        // Each submission mode adaptively and at level 2.
        assert_eq!(rows.len(), 6, "{csv}");
        let uniform = (vertex_count(2) as u64, index_count(2) as u64);
        for row in &rows {
            let (v, i) = match field(row, "adaptive").as_str() {
                "true" => stored,
                _ => uniform,
            };
            let counted = (get(row, "stored_vertices"), get(row, "stored_indices"));
            assert_eq!(counted, (v, i), "geomorph {geomorph}: {csv}");
            let records = get(row, "elements") * meshrefine::surface::RECORD_BYTES as u64;
            assert_eq!(
                get(row, "geometry_bytes"),
                v * 12 + i * 4 + records,
                "{csv}"
            );
        }
    }
}

/// An adaptive `static` frame too large for one allocation is refused before the CPU refines
/// it: Spot's 5,856 triangles at 1e-5 px up to level 1024 would make about 1.2 billion
/// triangles (tens of gigabytes). Run with 12 GB of data memory (`ulimit -d`: the heap and
/// private mappings, not the address space a driver may reserve), which the refinement would
/// exhaust (an abort) before the size check after it; the sentence names the driver, the
/// largest level, a lower bound of the size and the device limit, status 1.
#[test]
fn static_refuses_an_oversized_adaptive_mesh_before_refining_it() {
    let _guard = common::gpu_lock();
    let png = tmp("static-huge.png");
    let spot = common::model_path("spot_tri.obj");
    let command = format!(
        "ulimit -d 12000000 && exec '{}' render '{}' --pixel-error 1e-5 --max-level 1024 --driver static --cull off --width 640 --height 360 -o '{png}'",
        env!("CARGO_BIN_EXE_meshrefine"),
        spot.display()
    );
    let out = std::process::Command::new("sh")
        .args(["-c", &command])
        .env("MESHREFINE_VALIDATE", "1")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    assert!(
        errors[0]
            .contains("the static driver's adaptively refined mesh (largest level 1024) needs")
            && errors[0].contains(" bytes or more, over this device's maxMemoryAllocationSize"),
        "{stderr}"
    );
    assert!(!stderr.contains("validation"), "{stderr}");
}

/// Runs `args` with the device seen with a `maxStorageBufferRange` of `range` bytes
/// (`MESHREFINE_MAX_STORAGE_BUFFER_RANGE`: a small mesh then meets the limits of a mesh of
/// millions of elements), validated; returns (status, stdout, stderr).
fn limited(range: u32, args: &[&str]) -> (Option<i32>, String, String) {
    seen_with("MESHREFINE_MAX_STORAGE_BUFFER_RANGE", range, args)
}

/// Runs `args` with the device limit knob `var` at `value`, validated; returns (status, stdout,
/// stderr).
fn seen_with(var: &str, value: impl ToString, args: &[&str]) -> (Option<i32>, String, String) {
    let _guard = common::gpu_lock();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_VALIDATE", "1")
        .env(var, value.to_string())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args(args)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    (out.status.code(), stdout, stderr)
}

/// The pattern driver's adaptive draws where the device cannot hold their indirect commands and
/// bin lists (docs/cli.md, "Size limits"), on Spot's control mesh (372 elements) with a device
/// seen with less room. While geomorphing, the bins up to level 64 take 7 levels' slots, 28 bytes
/// an element (10,416 here, counted in the test from the mesh), beside a 20-byte command each.
/// - With 10,000 bytes the draws up to 64 do not fit but those up to the largest level chosen
///   (16 for export's default camera) do: `export` writes the file it writes on the whole
///   device (but for its `# command:` line), and `render` the image that `--max-level` at its
///   largest level chosen draws on the same device.
/// - With 7,000 bytes not even level 1's commands fit: `render` by default draws uniformly at
///   the default level 16 with one `note:` naming the limit (the image `--level 16` draws),
///   and with an explicit `--pixel-error` stops with that sentence, status 1.
/// - A bad value of the variable is one sentence naming it.
#[test]
fn adaptive_draws_past_the_devices_room_fall_back_as_documented() {
    let spot = common::model_path("spot_control_tri.obj");
    let spot = spot.to_str().unwrap();
    let elements = 372u64;
    let needed = elements * 4 * 7;
    let small = ["--width", "160", "--height", "120"];

    // Export: lowered to the largest level chosen, the same vertices.
    let whole = tmp("fit-whole.obj");
    let lowered = tmp("fit-lowered.obj");
    ok(&["export", spot, "--pixel-error", "1", "-o", &whole]);
    let (status, _, stderr) = limited(
        10_000,
        &["export", spot, "--pixel-error", "1", "-o", &lowered],
    );
    assert_eq!(status, Some(0), "{stderr}");
    let body = |p: &str| -> Vec<String> {
        let text = std::fs::read_to_string(p).unwrap();
        text.lines()
            .filter(|l| !l.starts_with("# command:"))
            .map(str::to_string)
            .collect()
    };
    let (a, b) = (body(&whole), body(&lowered));
    assert!(
        a.iter()
            .any(|l| l.starts_with("# levels ") && l.contains("16:")),
        "the levels reach 16: {:?}",
        &a[..6]
    );
    assert!(a == b, "the lowered export differs from the whole device's");

    // Render: the same lowering, the image `--max-level 16` draws.
    let png_lowered = tmp("fit-lowered.png");
    let png_16 = tmp("fit-max-level.png");
    let mut args = vec!["render", spot, "-o", &png_lowered];
    args.extend(small);
    let (status, stdout, stderr) = limited(10_000, &args);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(stdout.contains(ADAPTIVE_LINE), "{stdout}");
    // The largest level of the histogram `L:n L:n ...; culled C`.
    let histogram = stdout.split(ADAPTIVE_LINE).nth(1).unwrap();
    let largest = (histogram.split(';').next().unwrap().split_whitespace())
        .map(|t| t.split(':').next().unwrap().parse::<u32>().unwrap())
        .max()
        .unwrap();
    assert!((2..64).contains(&largest), "{stdout}");
    let largest = largest.to_string();
    let mut args = vec!["render", spot, "-o", &png_16, "--max-level", &largest];
    args.extend(small);
    let (status, _, stderr) = limited(10_000, &args);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(
        std::fs::read(&png_lowered).unwrap() == std::fs::read(&png_16).unwrap(),
        "the lowered image differs from --max-level {largest}'s"
    );

    // No room even at level 1 (7,000 bytes hold 62 of the 112-byte records a chunk, six
    // chunks of bins): uniform at the default level by default, refused when asked.
    let why = format!(
        "drawing {elements} elements in chunks of 62 adaptively up to level 64 (indirect commands and bins) needs {needed} bytes, over maxStorageBufferRange (7000)"
    );
    let png_default = tmp("room-default.png");
    let png_level = tmp("room-16.png");
    let mut args = vec!["render", spot, "-o", &png_default];
    args.extend(small);
    let (status, stdout, stderr) = limited(7_000, &args);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(!stdout.contains("adaptive at"), "{stdout}");
    let notes: Vec<&str> = stderr.lines().filter(|l| l.starts_with("note:")).collect();
    assert_eq!(notes.len(), 1, "{stderr}");
    assert!(
        notes[0].starts_with(&format!(
            "note: drawing uniformly at level 16 (the default --level): {why}"
        )),
        "{stderr}"
    );
    let mut args = vec!["render", spot, "-o", &png_level, "--level", "16"];
    args.extend(small);
    let (status, _, stderr) = limited(7_000, &args);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(
        std::fs::read(&png_default).unwrap() == std::fs::read(&png_level).unwrap(),
        "the fallback image differs from --level 16's"
    );
    let mut args = vec!["render", spot, "-o", &png_default, "--pixel-error", "1"];
    args.extend(small);
    let (status, _, stderr) = limited(7_000, &args);
    assert_eq!(status, Some(1), "{stderr}");
    let errors: Vec<&str> = stderr.lines().collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    assert!(
        errors[0].starts_with("error: ") && errors[0].contains(&why),
        "{stderr}"
    );
    // 7,000 bytes over the 28 an element's bins take up to level 64.
    assert!(
        errors[0].ends_with(": draw at most about 250 elements adaptively, or draw uniformly"),
        "{stderr}"
    );
    // Where a smaller largest level fits, the refusal names it, and it draws (a close-up,
    // whose levels reach past 8; 7,920 bytes: chunks of 70, level 8's commands fill them).
    let close = ["--eye", "0.3,0.2,0.6", "--look-at", "0,0.1,0.3"];
    let mut args = vec!["render", spot, "-o", &png_default, "--pixel-error", "1"];
    args.extend(small.iter().chain(&close));
    let (status, _, stderr) = limited(7_920, &args);
    assert_eq!(status, Some(1), "{stderr}");
    assert!(
        stderr.trim_end().ends_with(
            ": use --max-level 8, draw at most about 282 elements adaptively, or draw uniformly"
        ),
        "{stderr}"
    );
    args.extend(["--max-level", "8"]);
    let (status, stdout, stderr) = limited(7_920, &args);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(stdout.contains("adaptive at 1 px, max level 8"), "{stdout}");
    // Integer levels bin by every level: the level offered is still a power of two, as the
    // pattern driver's largest level must be, and geomorphing is offered where it fits.
    let mut args = vec!["render", spot, "-o", &png_default, "--pixel-error", "1"];
    args.extend(small.iter().chain(&close).chain(&["--geomorph", "off"]));
    let (status, _, stderr) = limited(11_000, &args);
    assert_eq!(status, Some(1), "{stderr}");
    assert!(
        stderr.trim_end().ends_with(
            ": use --max-level 4, use --geomorph on, draw at most about 42 elements adaptively, or draw uniformly"
        ),
        "{stderr}"
    );
    for remedy in [["--max-level", "4"], ["--geomorph", "on"]] {
        let mut args = args.clone();
        if remedy[0] == "--geomorph" {
            args.truncate(args.len() - 2);
        }
        args.extend(remedy);
        let (status, _, stderr) = limited(11_000, &args);
        assert_eq!(status, Some(0), "{remedy:?}: {stderr}");
    }

    let (status, _, stderr) = limited(1, &["info"]);
    assert_eq!(status, Some(0), "{stderr}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_MAX_STORAGE_BUFFER_RANGE", "lots")
        .args(["info"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr).trim_end(),
        "error: MESHREFINE_MAX_STORAGE_BUFFER_RANGE must be a positive number of bytes, at most 4294967295, not 'lots'"
    );
}

/// The level pass where its bounds do not fit one allocation (docs/adaptivity.md, "Levels per
/// frame"): Spot's 5,856 elements need 2,810,880 bytes of bounds (480 an element); with the
/// device seen with a `maxMemoryAllocationSize` of 1,000,000 bytes the CPU chooses the levels
/// instead, with one warning, and `render` draws the same image and `export` writes the same
/// file (but for its `# command:` line) as on the whole device.
#[test]
fn levels_past_one_allocation_are_chosen_on_the_cpu_alike() {
    let spot = common::model_path("spot_tri.obj");
    let spot = spot.to_str().unwrap();
    let var = "MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE";
    let warning = format!(
        "warning: the level pass's bounds buffer needs {} bytes, over this device's maxMemoryAllocationSize (1000000)",
        5856 * 480
    );
    let size = ["--width", "320", "--height", "180"];
    let (whole, cpu) = (tmp("alloc-whole.png"), tmp("alloc-cpu.png"));
    let mut args = vec!["render", spot, "-o", &whole];
    args.extend(size);
    let (line, stderr) = ok(&args);
    assert!(!stderr.contains("warning"), "{stderr}");
    let mut args = vec!["render", spot, "-o", &cpu];
    args.extend(size);
    let (status, stdout, stderr) = seen_with(var, 1_000_000, &args);
    assert_eq!(status, Some(0), "{stderr}");
    let first = |s: &str| s.lines().next().unwrap_or_default().to_string();
    assert_eq!(first(&stdout), first(&line));
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(warnings[0].starts_with(&warning), "{stderr}");
    assert!(
        std::fs::read(&whole).unwrap() == std::fs::read(&cpu).unwrap(),
        "the image differs with the levels chosen on the CPU"
    );
    let (whole, cpu) = (tmp("alloc-whole.obj"), tmp("alloc-cpu.obj"));
    ok(&["export", spot, "--pixel-error", "1", "-o", &whole]);
    let (status, _, stderr) = seen_with(
        var,
        1_000_000,
        &["export", spot, "--pixel-error", "1", "-o", &cpu],
    );
    assert_eq!(status, Some(0), "{stderr}");
    assert!(stderr.starts_with(&warning), "{stderr}");
    let body = |p: &str| -> Vec<String> {
        (std::fs::read_to_string(p).unwrap().lines())
            .filter(|l| !l.starts_with("# command:"))
            .map(str::to_string)
            .collect()
    };
    assert!(
        body(&whole) == body(&cpu),
        "the export differs with the levels chosen on the CPU"
    );
}

/// An image past one allocation is refused with its need and the limit apart: in MiB to a tenth
/// (the need rounded up, the limit down), in bytes under 1 MiB.
#[test]
fn an_image_past_one_allocation_names_both_sizes_apart() {
    let var = "MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE";
    let png = tmp("alloc-image.png");
    for (limit, side, says) in [
        (
            2_000_000,
            "1000",
            "needs 3.9 MiB per attachment, over the 1.9 MiB this device",
        ),
        (
            4_000,
            "40",
            "needs 6400 bytes per attachment, over the 4000 bytes this device",
        ),
    ] {
        let args = [
            "render", "-o", &png, "--width", side, "--height", side, "--msaa", "1",
        ];
        let (status, _, stderr) = seen_with(var, limit, &args);
        assert_eq!(status, Some(1), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(says), "{stderr}");
    }
}
