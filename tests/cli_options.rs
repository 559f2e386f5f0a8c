//! The command line's options, run as a user would: values out of range and meaningless
//! requests refused in one sentence, options that do not apply warned about and ignored, device
//! limits, `--help`'s groups, outputs' paths, the camera options' edge cases.

mod common;

use common::cli::*;

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
            if command[0] == "info" {
                // Found once the levels' camera is fitted, after the statistics are made:
                // still the one sentence alone.
                let out = meshrefine(&args);
                assert!(
                    out.stdout.is_empty(),
                    "{}",
                    String::from_utf8_lossy(&out.stdout)
                );
            }
        }
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
    // A height map bench would not read is not read (it need not exist), with one warning.
    let mut args = [bench.as_slice(), &size].concat();
    args.extend(["--heightmap", "/nonexistent/map.png"]);
    assert_eq!(
        warnings_of(&args),
        ["warning: --heightmap applies only to --displace heightmap, not to --displacements none: it is ignored"]
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

/// An export whose refined size passes the documented limit is refused before anything is
/// evaluated, naming the estimate and the highest level that fits (once the level is one the
/// driver draws on this device).
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
    // Up front: with no Vulkan driver at all, the size's sentence, not the driver's.
    let env = [("VK_DRIVER_FILES", "/nonexistent/no-driver.json")];
    let out = meshrefine_env(
        &["export", p(&spot), "-o", p(&obj), "--level", "1024"],
        &env,
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("would export") && !stderr.contains("Vulkan driver"),
        "{stderr}"
    );
    // Past the tessellator's limit too: that limit is said, not a size remedy (level 915 for
    // the icosahedron) the driver would then refuse.
    let out = meshrefine(&[
        "export",
        p(&model_path("icosahedron.obj")),
        "-o",
        p(&obj),
        "--level",
        "1024",
        "--driver",
        "tess",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("level 1024 is beyond this device's maxTessellationGenerationLevel")
            && !stderr.contains("would export"),
        "{stderr}"
    );
    assert!(!obj.exists());
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
            &["--pixel-error 1e39 is not a finite number > 0 in single precision (it is beyond f32's largest, about 3.4e38)"],
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
    let refusals: [(&[&str], String); 4] = [
        (&["export", "-o", p(&obj), "--driver", "tess", "--pixel-error", "1", "--max-level", "100"],
         format!("error: cannot export 'the default mesh (spot)': {past}")),
        (&["export", "-o", p(&obj), "--pixel-error", "1", "--max-level", "48"],
         // A value every device refuses: checked before the mesh is read, as --pixel-error's.
         "error: --max-level 48 is not a power of two".into()),
        (&["info", "--driver", "tess", "--pixel-error", "1", "--max-level", "100"],
         format!("error: {past}")),
        // info's --help: a power of two for the pattern driver, as render's.
        (&["info", "--pixel-error", "1", "--max-level", "7"],
         "error: --max-level 7 is not a power of two, as the pattern driver's largest level must be".into()),
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
    // The default is 4 samples where the device offers them (lavapipe does).
    let explicit = tmp("msaa-4.png");
    let mut args = vec!["render", "-o", p(&explicit), "--msaa", "4"];
    args.extend(small);
    ok(&args);
    assert_eq!(
        std::fs::read(&explicit).unwrap(),
        b,
        "the default is not --msaa 4"
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
