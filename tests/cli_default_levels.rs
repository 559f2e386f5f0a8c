//! `render` and the headless `view` draw adaptively by default (1 px, the driver's largest
//! level), `--level` draws uniformly, and where adaptive drawing cannot apply a default falls
//! back to the uniform default level with a note, never an error. Run as a user would, with the
//! validation layer on.

mod common;

use std::path::PathBuf;
use std::process::{Command, Output};

/// The binary, validated, without a display.
fn meshrefine(args: &[&str]) -> Output {
    let _guard = common::gpu_lock();
    Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .env("MESHREFINE_VALIDATE", "1")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args(args)
        .output()
        .expect("run meshrefine")
}

fn tmp(name: &str) -> String {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-default-levels");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name).to_str().unwrap().to_string()
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
    // --level asks for one level everywhere, and the camera options are then ignored.
    let mut uniform = args.clone();
    uniform.extend(["--level", "4", "--fov", "30"]);
    let (stdout, stderr) = ok(&uniform);
    assert!(!stdout.contains("adaptive at"), "{stdout}");
    assert!(
        stderr.contains("--fov applies only with --pixel-error"),
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
}

#[test]
fn a_default_that_cannot_be_adaptive_draws_uniformly_with_a_note() {
    let png = tmp("static.png");
    let args = [
        "render", "-o", &png, "--width", "96", "--height", "64", "--driver", "static",
    ];
    let (stdout, stderr) = ok(&args);
    assert!(!stdout.contains("adaptive at"), "{stdout}");
    let notes: Vec<&str> = stderr.lines().filter(|l| l.starts_with("note:")).collect();
    assert_eq!(notes.len(), 1, "{stderr}");
    assert!(
        notes[0].contains("drawing uniformly at level 16 (the default --level)")
            && notes[0].contains("static"),
        "{stderr}"
    );
    // Asked for explicitly, it is an error.
    let out = meshrefine(&[
        "render",
        "-o",
        &png,
        "--driver",
        "static",
        "--pixel-error",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(1));
}
