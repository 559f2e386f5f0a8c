//! Meshes and cameras far from the origin, from the command line: `info` and `export` choose the
//! levels `render` draws (all in the drawn frame, centred and at unit radius), the same as for
//! the mesh and camera moved to the origin; an eye far from the mesh culls nothing it sees; an
//! eye or target too far to place is refused with its own sentence, naming the values given.

mod common;

use common::model_path;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn meshrefine(args: &[&str]) -> Output {
    let _guard = common::gpu_lock();
    Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_VALIDATE", "1")
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run meshrefine")
}

fn ok(args: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `args` fail with status 1 and one error line holding every one of `needles`.
fn expect_error(args: &[&str], needles: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
    for n in needles {
        assert!(errors[0].contains(n), "{args:?}: no '{n}' in {stderr}");
    }
    stderr
}

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("far_offsets");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The tetrahedron with every vertex moved by `offset` in x, y and z.
fn shifted_tetrahedron(offset: f64) -> PathBuf {
    let text = std::fs::read_to_string(model_path("tetrahedron.obj")).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        match line.strip_prefix("v ") {
            Some(v) => {
                let c: Vec<f64> = v.split_whitespace().map(|x| x.parse().unwrap()).collect();
                let [x, y, z] = [c[0] + offset, c[1] + offset, c[2] + offset];
                out.push_str(&format!("v {x} {y} {z}\n"));
            }
            None => out.push_str(&format!("{line}\n")),
        }
    }
    let path = tmp(&format!("tetrahedron-{offset:e}.obj"));
    std::fs::write(&path, out).unwrap();
    path
}

/// What each command chose: (render's histogram, culled), (info's), export's `# levels` with
/// culling and without, and the triangles export wrote with culling.
struct Chosen {
    render: (String, u64),
    info: (String, u64),
    export_culled: String,
    export_all: String,
    exported_triangles: u64,
}

fn chosen(mesh: &Path, offset: f64) -> Chosen {
    let eye = format!("{},{},{}", offset + 3.0, offset + 2.0, offset + 4.0);
    let target = format!("{offset},{offset},{offset}");
    let camera = [
        "--pixel-error",
        "1",
        "--eye",
        &eye,
        "--look-at",
        &target,
        "--width",
        "160",
        "--height",
        "100",
    ];
    let with = |head: &[&str]| ok(&[head, &camera[..]].concat());
    let png = tmp(&format!("far-{offset:e}.png"));
    let out = with(&["render", p(mesh), "-o", p(&png)]);
    // "adaptive at 1 px, max level 64: levels (level:elements) 16:4; culled 0"
    let line = out.lines().find(|l| l.contains("levels (")).unwrap();
    let (hist, culled) = line
        .split_once("(level:elements) ")
        .unwrap()
        .1
        .split_once("; culled ")
        .unwrap();
    let render = (hist.to_string(), culled.trim().parse().unwrap());
    let out = with(&["info", p(mesh)]);
    let after = |start: &str| -> String {
        let l = out.lines().find(|l| l.trim_start().starts_with(start));
        let l = l.unwrap_or_else(|| panic!("no '{start}' in {out}"));
        l.split_once("): ").unwrap().1.trim().to_string()
    };
    let info = (after("levels ("), after("culled").parse().unwrap());
    let obj = tmp(&format!("far-{offset:e}.obj"));
    let export = |cull: &str| -> (String, u64) {
        with(&["export", p(mesh), "-o", p(&obj), "--cull", cull]);
        let text = std::fs::read_to_string(&obj).unwrap();
        let levels = text.lines().find_map(|l| l.strip_prefix("# levels "));
        let counts = text.lines().find(|l| l.ends_with(" triangles")).unwrap();
        let triangles = counts.rsplit(", ").next().unwrap();
        (
            levels.unwrap_or_else(|| panic!("{text:.600}")).to_string(),
            triangles.split(' ').next().unwrap().parse().unwrap(),
        )
    };
    let (export_culled, exported_triangles) = export("on");
    let (export_all, _) = export("off");
    Chosen {
        render,
        info,
        export_culled,
        export_all,
        exported_triangles,
    }
}

#[test]
fn info_and_export_choose_renders_levels_far_from_the_origin() {
    let at_origin = chosen(&shifted_tetrahedron(0.0), 0.0);
    assert_eq!(at_origin.render.1, 0, "{:?}", at_origin.render);
    for offset in [1e5, 1e7] {
        let far = chosen(&shifted_tetrahedron(offset), offset);
        let what = format!("offset {offset:e}");
        assert_eq!(far.render, at_origin.render, "{what}: render");
        assert_eq!(far.info, far.render, "{what}: info against render");
        assert_eq!(far.export_culled, far.render.0, "{what}: export --cull on");
        assert_eq!(
            far.export_all, at_origin.export_all,
            "{what}: export --cull off"
        );
        assert_eq!(far.export_all, far.render.0, "{what}: export --cull off");
        assert_eq!(
            far.exported_triangles, at_origin.exported_triangles,
            "{what}: triangles exported"
        );
        assert!(far.exported_triangles > 0, "{what}");
    }
}

/// An eye 1e8 bounding radii from Spot sees all of it (a speck): nothing is culled for being
/// outside the view, only the faces facing away, the same ones as from 1e3 radii in the same
/// direction (Spot is closed and wound outwards: info culls them as render does).
#[test]
fn a_distant_eye_culls_nothing_in_view() {
    let culled = |out: &str| -> u64 {
        (out.lines())
            .find_map(|l| {
                l.trim()
                    .strip_prefix("culled (outside the view or facing away): ")
            })
            .unwrap_or_else(|| panic!("no culled line: {out}"))
            .parse()
            .unwrap()
    };
    let near = culled(&ok(&["info", "--pixel-error", "1", "--eye", "1e3,0,0"]));
    assert!(near > 0 && near < 372 / 2, "{near}");
    for eye in ["1e7,0,0", "1e8,0,0", "1e11,0,0"] {
        let out = ok(&["info", "--pixel-error", "1", "--eye", eye]);
        assert_eq!(culled(&out), near, "--eye {eye}: {out}");
        assert!(
            out.contains(&format!(
                "levels (level:coarse triangles): 1:{}\n",
                372 - near
            )),
            "--eye {eye}: {out}"
        );
        let all = ok(&["info", "--pixel-error", "1", "--eye", eye, "--cull", "off"]);
        assert!(
            all.contains("levels (level:coarse triangles): 1:372\n"),
            "--eye {eye}: {all}"
        );
    }
}

/// An eye or target too far from the mesh to place: one sentence with the values as given and
/// the limit, from every command (never "no view direction" with re-mapped values), and by info
/// before it prints anything.
#[test]
fn an_eye_or_target_too_far_away_is_refused_as_given() {
    let png = tmp("too-far.png");
    let obj = tmp("too-far.obj");
    for (option, value) in [("--eye", "1e20,0,0"), ("--look-at", "1e20,0,0")] {
        for head in [
            &["render", "-o", p(&png), "--width", "160", "--height", "100"][..],
            &["info", "--pixel-error", "1"],
            &["export", "-o", p(&obj), "--pixel-error", "1"],
        ] {
            let args = [head, &[option, value]].concat();
            let stderr = expect_error(
                &args,
                &[
                    &format!("{option} 1e20,0,0 is 7.3e19 bounding radii"),
                    "at most 1e12 are supported",
                ],
            );
            assert!(!stderr.contains("view direction"), "{args:?}: {stderr}");
        }
        // Refused before anything is printed, as info's other camera errors are: no mesh
        // statistics first.
        let out = meshrefine(&["info", "--pixel-error", "1", option, value]);
        assert!(
            out.stdout.is_empty(),
            "{}",
            String::from_utf8_lossy(&out.stdout)
        );
    }
}

/// A look-at far beyond the mesh, in the same direction from the eye as one at its centre,
/// draws the same image, uniform and adaptive (the depth range holds the mesh, not a sphere
/// grown around the far target, whose near plane cut the whole mesh away). The two view
/// matrices are made from different points, so they may differ in their last bits: a pixel or
/// two on a triangle's edge may then differ by a shade (seen on a CPU whose llvmpipe code
/// rounds otherwise), where the cut, or a depth range that loses precision, changes hundreds.
#[test]
fn a_far_look_at_draws_what_a_near_one_does() {
    for level in [&["--level", "2"][..], &[]] {
        let mut images = Vec::new();
        for (i, target) in ["0,0,0", "0,0,10000"].iter().enumerate() {
            let png = tmp(&format!("look-at-{i}.png"));
            #[rustfmt::skip]
            let args = [&["render", "-o", p(&png), "--width", "160", "--height", "100",
                "--eye", "0,0,-3", "--look-at", target][..], level].concat();
            ok(&args);
            images.push(common::cli::rgba_of(&png));
        }
        let (a, b) = (&images[0], &images[1]);
        assert_eq!(a.len(), b.len());
        let differing: Vec<(usize, u8)> = (a.chunks(4).zip(b.chunks(4)).enumerate())
            .filter(|(_, (x, y))| x != y)
            .map(|(i, (x, y))| {
                let most = x.iter().zip(y).map(|(u, v)| u.abs_diff(*v)).max();
                (i, most.unwrap_or(0))
            })
            .collect();
        assert!(
            differing.len() <= 4 && differing.iter().all(|&(_, d)| d <= 8),
            "{level:?}: pixels (index, largest channel difference) {differing:?}"
        );
    }
}

/// A mesh 1e20 from its origin, whose squared distance is past f32's range, takes a
/// displacement within every limit of errors.md ("Displacement limits": a reach of 1e-2 radii,
/// phases under 2^22 radians): drawn, not refused as reaching infinity. Further out the f32
/// range itself refuses it, naming the real distance.
#[test]
fn a_mesh_whose_squared_distance_overflows_f32_takes_a_displacement() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let moved = |offset: f64| {
        let mut out = String::new();
        for line in text.lines() {
            match line.strip_prefix("v ") {
                Some(v) => {
                    let c: Vec<f64> = v.split_whitespace().map(|x| x.parse().unwrap()).collect();
                    let [x, y, z] = [c[0] * 1e14 + offset, c[1] * 1e14, c[2] * 1e14];
                    out.push_str(&format!("v {x:e} {y:e} {z:e}\n"));
                }
                None => out.push_str(&format!("{line}\n")),
            }
        }
        let path = tmp(&format!("far-displaced-{offset:e}.obj"));
        std::fs::write(&path, out).unwrap();
        path
    };
    let mesh = moved(1e20);
    let png = tmp("far-displaced.png");
    let displace = [
        "--displace",
        "sine",
        "--frequency",
        "1e-14",
        "--amplitude",
        "1e12",
    ];
    let size = ["--width", "64", "--height", "48", "--level", "2"];
    let args = [&["render", p(&mesh), "-o", p(&png)][..], &size, &displace].concat();
    ok(&args);
    // 1e38 from the origin: past a quarter of f32::MAX.
    let edge = moved(1e38);
    let args = [&["render", p(&edge), "-o", p(&png)][..], &size, &displace].concat();
    expect_error(&args, &["beyond the range of f32", "from the origin"]);
}
