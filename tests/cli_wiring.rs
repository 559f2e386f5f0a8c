//! What the command line promises about its own wiring, run as a user would: that `--validate`
//! and `MESHREFINE_VALIDATE` really ask for the validation layer, that the surface options'
//! defaults are the values `--help` and docs/cli.md name (the same export as with the value
//! written out, a different one with another), that `devices` shows the limits the environment
//! lowers, and that a Wayland display that cannot be reached falls back to the headless render.

mod common;

use common::cli::*;

/// Exports `mesh` with `args` to `name` and returns what it wrote (less the command line).
fn export(mesh: &str, name: &str, args: &[&str]) -> String {
    let obj = tmp(&format!("wiring-{name}"));
    ok(&[&["export", &model_arg(mesh), "-o", p(&obj)][..], args].concat());
    without_command(&obj)
}

/// The binary run with `args` where the Vulkan loader finds no validation layer (explicit
/// layers searched in an empty folder only, the validation layer disabled by name, nothing
/// asking for it through the loader's own variables), with `MESHREFINE_VALIDATE` set to
/// `validate` or unset; no display, one at a time with the other GPU work of this process.
fn without_the_layer(args: &[&str], validate: Option<&str>) -> Output {
    let empty = tmp("no-layers");
    std::fs::create_dir_all(&empty).unwrap();
    let _guard = common::gpu_lock();
    let mut command = bin();
    command.env_remove("MESHREFINE_VALIDATE");
    for var in [
        "DISPLAY",
        "WAYLAND_DISPLAY",
        "VK_LOADER_LAYERS_ENABLE",
        "VK_INSTANCE_LAYERS",
        "VK_ADD_LAYER_PATH",
    ] {
        command.env_remove(var);
    }
    command
        .env("VK_LAYER_PATH", &empty)
        .env("VK_LOADER_LAYERS_DISABLE", "*validation*");
    if let Some(v) = validate {
        command.env("MESHREFINE_VALIDATE", v);
    }
    command.args(args).output().expect("run meshrefine")
}

/// With the validation layer hidden from the Vulkan loader, `--validate` and
/// `MESHREFINE_VALIDATE=1` each fail in one sentence naming the layer and its package, so both
/// ask for it (every validated test relies on that); without either, or with the variable `0`,
/// the command runs.
#[test]
fn validate_flag_and_variable_ask_for_the_layer() {
    let refused = |out: Output, how: &str| {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{how}: {stderr}");
        assert_eq!(
            stderr.trim_end(),
            "error: the Vulkan validation layer VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)",
            "{how}"
        );
    };
    refused(
        without_the_layer(&["--validate", "devices"], None),
        "--validate",
    );
    refused(
        without_the_layer(&["devices"], Some("1")),
        "MESHREFINE_VALIDATE=1",
    );
    for validate in [None, Some("0")] {
        let out = without_the_layer(&["devices"], validate);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{validate:?}: {stderr}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("(default)"));
    }
}

/// Exports `mesh` with `base`, then with `option documented` and `option other` added:
/// the first two must be equal, the third must differ; returns the default's and the other's.
fn default_is(
    mesh: &str,
    base: &[&str],
    option: &str,
    documented: &str,
    other: &str,
) -> (String, String) {
    let name = |v: &str| format!("{}-{v}.obj", option.trim_start_matches('-'));
    let with = |v: &str| export(mesh, &name(v), &[base, &[option, v]].concat());
    let default = export(mesh, &name("default"), base);
    assert_eq!(default, with(documented), "{option} {documented}");
    let other = with(other);
    assert_ne!(default, other, "{option} {other}");
    (default, other)
}

/// `--pn-seams` defaults to `closed` (crack-free at split normals): the cylinder with hard
/// normals exports as with `--pn-seams closed`, and differently from `open`, which keeps each
/// side's own geometry (more distinct positions: the cracks).
#[test]
fn pn_seams_default_is_closed() {
    let cylinder = "cylinder_hard_normals.obj";
    let pn = ["--surface", "pn", "--level", "2"];
    let (closed, open) = default_is(cylinder, &pn, "--pn-seams", "closed", "open");
    let positions = |text: &str| {
        let mut p: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
        p.sort_unstable();
        p.dedup();
        p.len()
    };
    assert!(
        positions(&open) > positions(&closed),
        "{} distinct positions open, {} closed",
        positions(&open),
        positions(&closed)
    );
}

/// `--normal-field` defaults to `vlachos`, `--octaves` to 1, `--bias` to 0 and `--bft-level`
/// to 5, as `--help` says.
#[test]
fn surface_defaults_are_the_documented_ones() {
    let spot = "spot_control_tri.obj";
    let pn = ["--surface", "pn", "--level", "2"];
    default_is(spot, &pn, "--normal-field", "vlachos", "paper");
    let noise = ["--surface", "flat", "--displace", "noise", "--level", "4"];
    default_is(spot, &noise, "--octaves", "1", "3");
    let height = ["--surface", "flat", "--displace", "heightmap"];
    default_is("grid_uv_8x8.obj", &height, "--bias", "0", "0.5");
    let tetrahedron = model_arg("tetrahedron.obj");
    let table = |extra: &[&str]| {
        let args = [&["info", &tetrahedron, "--surface", "loop"][..], extra].concat();
        let out = ok(&args);
        let line = out.lines().find(|l| l.starts_with("table level: "));
        line.unwrap_or_else(|| panic!("{out}")).to_string()
    };
    assert!(table(&[]).starts_with("table level: 5 (32 segments"));
    assert!(table(&["--bft-level", "3"]).starts_with("table level: 3 (8 segments"));
}

/// `MESHREFINE_MAX_STORAGE_BUFFER_RANGE` and `MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE` lower the
/// limits meshrefine respects, and `devices` shows the values seen; a range under one
/// element's bytes still draws (every chunk holds an element), saying what it cannot draw.
#[test]
fn the_limit_variables_are_respected_and_shown() {
    let png = tmp("wiring-range-1.png");
    let args = ["render", "-o", p(&png), "--width", "64", "--height", "64"];
    let stderr = succeeds(&args, &[("MESHREFINE_MAX_STORAGE_BUFFER_RANGE", "1")]);
    assert!(
        stderr.contains("over maxStorageBufferRange (1): draw uniformly"),
        "{stderr}"
    );
    let out = meshrefine_env(
        &["devices"],
        &[
            ("MESHREFINE_MAX_STORAGE_BUFFER_RANGE", "4096"),
            ("MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE", "1000000"),
        ],
    );
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(
        stdout.contains("(maxStorageBufferRange): 4096 bytes; largest allocation: 1000000 bytes"),
        "{stdout}"
    );
}

/// With only `WAYLAND_DISPLAY` set, to a display that cannot be reached, `view` renders the
/// scene headlessly, says why and where, and succeeds.
#[test]
fn an_unreachable_wayland_display_falls_back_to_the_headless_render() {
    let png = tmp("wiring-wayland.png");
    let _ = std::fs::remove_file(&png);
    let out = meshrefine_env(
        &[
            "view",
            "--level",
            "1",
            "--width",
            "64",
            "--height",
            "48",
            "--headless-output",
            p(&png),
        ],
        &[("WAYLAND_DISPLAY", "meshrefine-nowhere")],
    );
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");
    assert_eq!(
        stdout.trim_end(),
        format!(
            "cannot connect to the display 'meshrefine-nowhere': rendered the scene headlessly to {}",
            png.display()
        )
    );
    assert!(png.is_file());
}

/// Sine and noise displacement are functions of the point in the file's own coordinates, with
/// the amplitude and frequency in its units, whatever frame the mesh is drawn in (centred, unit
/// size): the 8x8 grid scaled by 7 and moved to z = 5, off the origin, exports every vertex
/// displaced along the plane's normal by the height the CPU displacement gives at its point in
/// the file's coordinates (within 2e-3 of the amplitude and 1e-5, as the GPU's `sin` is held to
/// in tests/gpu_mirror.rs; a wrong origin, scale or frequency moves points by a sizeable share
/// of the 0.2 amplitude).
#[test]
fn displacement_is_measured_in_the_files_coordinates() {
    use meshrefine::surface::{displace, Displace, SurfaceParams};
    let grid = std::fs::read_to_string(model_path("grid_open_8x8.obj")).unwrap();
    let moved: String = (grid.lines())
        .map(|l| match l.strip_prefix("v ") {
            Some(xyz) => {
                let c: Vec<f64> = xyz.split_whitespace().map(|x| x.parse().unwrap()).collect();
                assert_eq!(c[2], 0.0);
                format!("v {} {} 5\n", 7.0 * c[0] + 3.0, 7.0 * c[1] - 2.0)
            }
            None => format!("{l}\n"),
        })
        .collect();
    let mesh = write("wiring-moved-grid.obj", moved.as_bytes());
    for (d, displace_name) in [(Displace::Sine, "sine"), (Displace::Noise, "noise")] {
        let obj = tmp(&format!("wiring-moved-grid-{displace_name}.obj"));
        #[rustfmt::skip]
        ok(&[
            "export", p(&mesh), "-o", p(&obj), "--surface", "flat", "--level", "4",
            "--displace", displace_name, "--amplitude", "0.2", "--frequency", "3", "--octaves", "2",
        ]);
        let params = SurfaceParams {
            amplitude: 0.2,
            frequency: 3.0,
            octaves: 2,
            ..SurfaceParams::default()
        };
        let text = std::fs::read_to_string(&obj).unwrap();
        let mut worst = 0.0f64;
        let mut seen = 0;
        for xyz in text.lines().filter_map(|l| l.strip_prefix("v ")) {
            let v: Vec<f64> = xyz.split_whitespace().map(|x| x.parse().unwrap()).collect();
            let at = glam::Vec3::new(v[0] as f32, v[1] as f32, 5.0);
            let h = displace::height(d, &params, at).0 as f64;
            worst = worst.max((v[2] - 5.0 - h).abs());
            seen += 1;
        }
        // 8 x 8 quads, each edge in 4 at level 4: 33 x 33 points, each written once.
        assert_eq!(seen, 33 * 33, "{displace_name}");
        let tolerance = 2e-3 * 0.2 + 1e-5;
        assert!(
            worst <= tolerance,
            "{displace_name}: {worst} from the file's own height"
        );
    }
}

/// docs/loop.md's memory table is what `info --surface loop` prints for each bundled mesh it
/// names: the configurations (and the tables they fill) and the basis function tables' bytes.
#[test]
fn loop_table_memory_is_what_info_prints() {
    let doc =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/loop.md")).unwrap();
    let mut checked = 0;
    for row in doc
        .lines()
        .filter(|l| l.starts_with("| ") && l.contains(" bytes |"))
    {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (mesh, configurations, bytes) = (cells[1], cells[2], cells[4]);
        // The default mesh is Spot; sphere960 is not bundled.
        let file = match mesh.split_whitespace().next().unwrap() {
            "torus" => Some("torus_16x8".to_string()),
            "Spot" => None,
            "sphere960" => continue,
            name => Some(name.to_string()),
        };
        let mut args = vec!["info".to_string(), "--surface".into(), "loop".into()];
        args.extend(file.map(|f| model_arg(&format!("{f}.obj"))));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = ok(&args);
        let line = |prefix: &str| {
            let l = out.lines().find(|l| l.starts_with(prefix));
            l.unwrap_or_else(|| panic!("{mesh}: no {prefix:?} in {out}"))
                .to_string()
        };
        let tables = if let Some(c) = configurations.strip_suffix(" tables") {
            c.to_string()
        } else {
            format!("{configurations} in {configurations}")
        };
        assert!(
            line("configurations: ").starts_with(&format!("configurations: {tables} tables")),
            "{mesh}: {row}"
        );
        let bytes = bytes.trim_end_matches(" bytes").replace(',', "");
        assert_eq!(
            line("basis function tables: "),
            format!("basis function tables: {bytes} bytes"),
            "{mesh}: {row}"
        );
        checked += 1;
    }
    assert_eq!(
        checked, 8,
        "rows of bundled meshes in docs/loop.md's memory table"
    );
}

/// `sine` around its centre has no finite bound (its curvature is unbounded at the origin):
/// the 8x8 grid through the origin draws the elements whose bounds hold it at the largest
/// level (at integer levels those alone; gliding, their neighbours too) and `info` counts them
/// as unbounded; with amplitude zero, or noise of frequency zero,
/// nothing is displaced: the grid is all level 1, and Spot's cage as `pn` gets the levels and
/// the culling (normal cones) of `--displace none`.
#[test]
fn sine_at_its_centre_is_unbounded_and_a_zero_displacement_is_none() {
    let grid = model_arg("grid_open_8x8.obj");
    let info = |mesh: Option<&str>, surface: &str, extra: &[&str]| {
        let mut args = vec!["info", "--surface", surface, "--pixel-error", "1"];
        args.extend(mesh);
        args.extend(extra);
        let out = ok(&args);
        let lines: Vec<String> = (out.lines())
            .filter(|l| {
                l.starts_with("  levels ")
                    || l.starts_with("  culled ")
                    || l.starts_with("  unbounded:")
            })
            .map(str::to_string)
            .collect();
        lines
    };
    let sine = info(Some(&grid), "flat", &["--displace", "sine"]);
    let unbounded = sine.iter().find(|l| l.starts_with("  unbounded: "));
    let n: u32 = (unbounded.unwrap_or_else(|| panic!("{sine:?}")))
        .trim_start_matches("  unbounded: ")
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        n >= 6,
        "the six triangles around the origin at least: {sine:?}"
    );
    // Gliding, their neighbours' edges are lifted to them (src/lod/frame/lift.rs): those
    // neighbours draw at 64 too; at integer levels only the unbounded elements do.
    let at_64 = |levels: &str| {
        (levels.split_whitespace())
            .find_map(|t| t.strip_prefix("64:"))
            .map_or(0, |k| k.parse::<u32>().unwrap())
    };
    assert!(at_64(&sine[0]) > n, "{sine:?}");
    let integer = info(
        Some(&grid),
        "flat",
        &["--displace", "sine", "--geomorph", "off"],
    );
    assert_eq!(at_64(&integer[0]), n, "{integer:?}");
    let flat = info(
        Some(&grid),
        "flat",
        &["--displace", "sine", "--amplitude", "0"],
    );
    assert_eq!(
        flat[0], "  levels (level:coarse triangles): 1:128",
        "{flat:?}"
    );
    assert!(!flat.iter().any(|l| l.contains("unbounded")), "{flat:?}");
    let none = info(None, "pn", &["--displace", "none"]);
    assert!(!none[1].ends_with(" 0"), "nothing culled: {none:?}");
    for zero in [
        ["--displace", "sine", "--amplitude", "0"],
        ["--displace", "noise", "--frequency", "0"],
    ] {
        assert_eq!(info(None, "pn", &zero), none, "{zero:?}");
    }
}

/// `MESHREFINE_HIDE_FEATURES` shows the paths a device without a feature takes (platform.md),
/// validated: a required feature missing (`tessellationShader`, `dynamicRendering`) refuses the
/// device in one sentence naming it; without `transformFeedback` only a `tess` export is
/// refused, without `vertexPipelineStoresAndAtomics` the pattern driver's (renders of every
/// driver and Loop still draw, the tessellator still exports through transform feedback, which
/// the warning and the error say only where the device has it), without
/// `fillModeNonSolid` the wireframe is off with a warning (the image is the one without it),
/// without `depthBiasClamp` the wireframe draws, without `pipelineStatisticsQuery` bench's
/// vertex invocations are left empty; `devices` says "no" for each optional one and calls the
/// device unusable without a required one; an unknown name is one sentence listing the names.
#[test]
fn hidden_features_take_the_paths_a_device_without_them_takes() {
    let hide = |feature: &str, args: &[&str]| {
        meshrefine_env(args, &[("MESHREFINE_HIDE_FEATURES", feature)])
    };
    let refused = |out: Output, says: &str| {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
        assert_eq!(errors.len(), 1, "{stderr}");
        assert!(errors[0].contains(says), "{stderr}");
        assert!(!stderr.contains("validation"), "{stderr}");
    };
    let drew = |out: Output| {
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{stderr}");
        assert!(!stderr.contains("validation"), "{stderr}");
        stderr
    };
    let (png, obj) = (tmp("wiring-hidden.png"), tmp("wiring-hidden.obj"));
    let size = ["--width", "64", "--height", "64", "--level", "2"];
    let render = |extra: &[&'static str]| [&["render", "-o", p(&png)][..], &size, extra].concat();
    let export =
        |extra: &[&'static str]| [&["export", "-o", p(&obj), "--level", "2"][..], extra].concat();
    for required in ["tessellationShader", "dynamicRendering"] {
        refused(
            hide(required, &render(&[])),
            &format!("lacks the required feature {required}"),
        );
    }
    let xfb = "has no transformFeedback (VK_EXT_transform_feedback), which reading back the tessellator's triangles needs";
    refused(
        hide("transformFeedback", &export(&["--driver", "tess"])),
        xfb,
    );
    drew(hide("transformFeedback", &export(&[])));
    drew(hide("transformFeedback", &render(&["--driver", "tess"])));
    let stores = "vertexPipelineStoresAndAtomics";
    let said = drew(hide(stores, &render(&[])));
    assert!(
        said.contains("no vertexPipelineStoresAndAtomics, evaluated vertices cannot be captured (export --driver pattern); export --driver tess still works (transform feedback)"),
        "{said}"
    );
    // No shader that draws (rather than captures) needs it: every driver and Loop render.
    for extra in [
        &["--driver", "tess"][..],
        &["--driver", "static"],
        &["--surface", "loop"],
    ] {
        drew(hide(stores, &render(extra)));
    }
    refused(
        hide(stores, &export(&["--driver", "pattern"])),
        "has no vertexPipelineStoresAndAtomics, which capturing evaluated vertices needs; --driver tess exports through transform feedback",
    );
    drew(hide(stores, &export(&["--driver", "tess"])));
    // Without transform feedback either, the warning and the error promise no tess export.
    let both = "vertexPipelineStoresAndAtomics,transformFeedback";
    let said = drew(hide(both, &render(&[])));
    assert!(
        said.contains("evaluated vertices cannot be captured (export --driver pattern)\n"),
        "{said}"
    );
    let out = hide(both, &export(&[]));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.ends_with(
            "has no vertexPipelineStoresAndAtomics, which capturing evaluated vertices needs\n"
        ),
        "{stderr}"
    );
    drew(hide("", &render(&[])));
    let plain = std::fs::read(&png).unwrap();
    let said = drew(hide("fillModeNonSolid", &render(&["--wireframe"])));
    assert!(
        said.contains("no fillModeNonSolid, the wireframe view is off"),
        "{said}"
    );
    assert!(
        std::fs::read(&png).unwrap() == plain,
        "the wireframe was drawn"
    );
    drew(hide("", &render(&["--wireframe"])));
    let wire = std::fs::read(&png).unwrap();
    assert!(wire != plain, "the wireframe changes nothing");
    drew(hide("depthBiasClamp", &render(&["--wireframe"])));
    assert!(std::fs::read(&png).unwrap() != plain, "no wireframe drawn");
    let prefix = tmp("wiring-hidden-bench");
    #[rustfmt::skip]
    let bench = [
        "bench", "--levels", "2", "--frames", "1", "--width", "64", "--height", "64",
        "--drivers", "static", "--out", p(&prefix),
    ];
    for (feature, counted) in [("", true), ("pipelineStatisticsQuery", false)] {
        drew(hide(feature, &bench));
        let csv = std::fs::read_to_string(format!("{}.csv", p(&prefix))).unwrap();
        let mut lines = csv.lines();
        let header = common::csv_fields(lines.next().unwrap());
        let column = header
            .iter()
            .position(|h| h == "vertex_invocations")
            .unwrap();
        let row = common::csv_fields(lines.next().unwrap());
        assert_eq!(!row[column].is_empty(), counted, "{feature:?}: {csv}");
    }
    // `devices` says `no` for each optional feature hidden, and a required one makes the
    // device unusable.
    let optional = meshrefine::gpu::CHECKED_FEATURES[2..].join(",");
    let out = hide(&optional, &["devices"]);
    let listed = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{listed}");
    for feature in &meshrefine::gpu::CHECKED_FEATURES[2..] {
        assert!(
            listed.contains(&format!("({feature}): no")),
            "{feature}: {listed}"
        );
    }
    let out = hide("tessellationShader", &["devices"]);
    let listed = String::from_utf8_lossy(&out.stdout);
    assert!(
        listed.contains("unusable: device '")
            && listed.contains("lacks the required feature tessellationShader"),
        "{listed}"
    );
    refused(
        hide("geometryShader", &["devices"]),
        "MESHREFINE_HIDE_FEATURES: 'geometryShader' is not a feature meshrefine checks (one of tessellationShader,",
    );
}
