//! `meshrefine bench`, run as a user would: every variant timed with ratios, its lists, its
//! refusals before anything is timed, the fitted camera named, its rows with a height map, a
//! pixel error and culled elements, and its slow-frame warnings.

mod common;

use common::cli::*;

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
    // The table names the camera it drew from as the options take it: the one `export` draws
    // from by default at the same size (its header's, the same digits).
    let cameras = (md.lines())
        .find(|l| l.starts_with("Cameras (in the mesh's own coordinates"))
        .unwrap_or_else(|| panic!("{md}"));
    let obj = tmp("bench-out/tet.obj");
    #[rustfmt::skip]
    ok(&["export", p(&tet), "--surface", "flat", "--pixel-error", "1", "--width", "64", "--height", "64", "-o", p(&obj)]);
    let obj = std::fs::read_to_string(obj).unwrap();
    let w: Vec<&str> = (obj.lines())
        .find(|l| l.starts_with("# camera eye "))
        .unwrap()
        .split(' ')
        .collect();
    let want = format!(
        "tetrahedron as flat + none: `--eye {},{},{} --look-at {},{},{} --fov 45`",
        w[3], w[4], w[5], w[7], w[8], w[9]
    );
    assert!(cameras.contains(&want), "{cameras}\n{want}");
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
            "cannot benchmark 'the default mesh (spot)': the mesh has no texture coordinates (vt on every face), where the heightmap displacement reads its map",
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
    // Where the static driver's mesh refined for the levels chosen (known only once they are)
    // is over the device's allocation limit, its adaptive row is not drawn, as one the device
    // refuses up front, and every other row is still timed.
    let over = tmp("bench-adaptive-over-limit");
    let o = over.display().to_string();
    let spot = model_arg("spot_control_tri.obj");
    #[rustfmt::skip]
    succeeds(
        &[
            "bench", &spot, "--drivers", "static,pattern", "--surfaces", "pn", "--pixel-error",
            "1e-9", "--max-level", "32", "--no-bound-levels", "--levels", "1", "--frames", "1",
            "--width", "16", "--height", "16", "--out", &o,
        ],
        &[("MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE", "2000000")],
    );
    let csv = std::fs::read_to_string(over.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    let keys = common::csv_fields(lines.next().unwrap());
    let rows: Vec<Vec<String>> = lines.map(common::csv_fields).collect();
    let get = |r: &Vec<String>, key: &str| r[keys.iter().position(|k| k == key).unwrap()].clone();
    assert_eq!(rows.len(), 8, "{csv}");
    for r in &rows {
        let timed = get(r, "gpu_ms_median").parse::<f64>().is_ok();
        if get(r, "variant") == "static" && get(r, "adaptive") == "true" {
            assert!(!timed && get(r, "refined_triangles").is_empty(), "{csv}");
            assert!(
                get(r, "note")
                    .starts_with("not drawn: the static driver's adaptively refined mesh"),
                "{csv}"
            );
        } else {
            assert!(timed, "{csv}");
        }
    }
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
