//! Adaptive drawing from the command line (`--pixel-error`), run as a user would: `info`'s levels
//! for a camera and where the bound is not met, adaptive renders and exports (their header
//! lines, closed meshes, the capture holding only the levels drawn, sizes refused before any
//! work), culling, and the notes where the pixel error is not met.

mod common;

use common::cli::*;

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

/// Where the pixel error is not met, elements are counted by their own bounds: those drawn at
/// the largest level only because a neighbour holds the eye meet it there (neither `near` nor
/// `capped`), and those no uniform level meets are the same whichever lattice driver's
/// transitions raise the others (the tessellator's, whose rings' diagonals bend more, at least
/// as many).
/// The benchmark's close-up (docs/benchmarks.md, "Adaptive refinement"): at integer levels
/// (`--geomorph off`, and `static`) Spot as `pn` takes at most 0.35x the triangles of the
/// smallest uniform level meeting the bound at every pixel error the benchmark times (the
/// lift's doing: without it 0.36x at 0.5 and 1 px); gliding, at powers of two and with edges
/// lifted to the insides beside them, it takes more, at most 0.65x.
#[test]
fn the_close_up_at_integer_levels_takes_at_most_0_35x_the_uniform_triangles() {
    let spot = model_path("spot_control_tri.obj");
    #[rustfmt::skip]
    let camera = [
        "--surface", "pn", "--eye", "0.35,0.65,-1.3", "--look-at", "0,0.5,-0.5", "--fov", "45",
        "--width", "1920", "--height", "1080", "--max-level", "64",
    ];
    for px in ["0.5", "1", "2", "4"] {
        let report = |extra: &[&str]| {
            let mut args = vec!["info", p(&spot), "--pixel-error", px];
            args.extend(camera);
            args.extend(extra);
            let (adaptive, uniform, ..) = adaptive_report(&ok(&args));
            (adaptive, uniform)
        };
        for extra in [&["--geomorph", "off"][..], &["--driver", "static"]] {
            let (adaptive, uniform) = report(extra);
            assert!(
                adaptive * 100 <= uniform * 35,
                "{px} px {extra:?}: {adaptive} triangles against {uniform}"
            );
        }
        let (adaptive, uniform) = report(&[]);
        assert!(
            adaptive * 100 > uniform * 35 && adaptive * 100 <= uniform * 65,
            "{px} px gliding: {adaptive} triangles against {uniform}"
        );
    }
}

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

/// `loop`'s bounds for gliding levels hold at powers of two alone: `info` compares a gliding
/// frame with the smallest power of two meeting them (from those bounds read as any integer,
/// level 54 here), and at integer levels (`static`) with the integer level its own bounds ask.
#[test]
fn info_compares_gliding_loop_with_a_power_of_two() {
    let ico = model_path("icosahedron.obj");
    let uniform = |driver: &str| -> u32 {
        #[rustfmt::skip]
        let out = ok(&[
            "info", p(&ico), "--surface", "loop", "--driver", driver,
            "--eye", "-0.525731112,0.850650808,0", "--look-at", "0,0,0", "--pixel-error", "1",
        ]);
        let (_, after) = out.split_once("at uniform level ").expect(&out);
        after.split_whitespace().next().unwrap().parse().unwrap()
    };
    assert_eq!(uniform("pattern"), 64);
    assert_eq!(uniform("tess"), 64);
    assert_eq!(uniform("static"), 64);
    #[rustfmt::skip]
    let out = ok(&[
        "info", p(&ico), "--surface", "loop", "--driver", "pattern",
        "--pixel-error", "1", "--max-level", "1024",
    ]);
    let (_, after) = out.split_once("at uniform level ").expect(&out);
    let level: u32 = after.split_whitespace().next().unwrap().parse().unwrap();
    assert!(level.is_power_of_two(), "{out}");
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
    // In that sentence alone: no note before it on levels it does not draw.
    let stderr = String::from_utf8_lossy(&meshrefine(&high("0.01")).stderr).into_owned();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
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
    // Loop's elements are M1's faces, named beside the triangles the sentence counts.
    #[rustfmt::skip]
    let loop_away = ["render", "-o", p(&png), "--width", "32", "--height", "32",
        "--surface", "loop", "--eye", "3,0,0", "--look-at", "6,0,0"];
    expect_error(
        &loop_away,
        &[
            "any of the 372 triangle(s)",
            "culling removed all 1488 elements (M1's faces, four to a triangle)",
        ],
    );
    // An open surface shows its back side: its elements facing away are not culled, and the
    // open grid, seen from below by the framing camera, is drawn.
    let grid = model_path("grid_open_8x8.obj");
    #[rustfmt::skip]
    let below = ok(&["render", p(&grid), "-o", p(&png), "--pixel-error", "1", "--cull", "on",
        "--width", "160", "--height", "100"]);
    assert!(below.contains("culled 0"), "{below}");
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
