//! The window demo under a virtual X display (Xvfb, installed by scripts/setup.sh): it opens a
//! window, presents frames through the swapchain with the validation layer on, exits after
//! `--frames`, and its `--screenshot` shows the mesh.

mod common;

use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    /// Starts a server on a display number it chooses itself (`-displayfd`): the server takes
    /// the first number whose lock it can create, so tests running in parallel (and other
    /// servers on the machine) never race for one, and stale locks are the server's business.
    fn start() -> Self {
        use std::io::BufRead;
        let mut child = Command::new("Xvfb")
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1280x1024x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb is not installed: run scripts/setup.sh (apt-get install xvfb)");
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = std::io::BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        let line = rx.recv_timeout(Duration::from_secs(30)).unwrap_or_default();
        let Ok(n) = line.trim().parse::<u32>() else {
            let _ = child.kill();
            panic!("Xvfb did not report a display within 30 s (printed {line:?})");
        };
        Self {
            child,
            display: format!(":{n}"),
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // A server that ended on its own (a test stopped it) removed its files itself, and its
        // display may be another test's server's by now: nothing of it is left to remove.
        if self.child.try_wait().is_ok_and(|s| s.is_some()) {
            return;
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        // A killed server leaves its lock file and socket behind; remove them, or repeated runs
        // on one machine fill /tmp with them.
        let n = &self.display[1..];
        let _ = std::fs::remove_file(format!("/tmp/.X{n}-lock"));
        let _ = std::fs::remove_file(format!("/tmp/.X11-unix/X{n}"));
    }
}

/// Runs `view` for 24 frames with a screenshot; returns its stderr.
fn run_view(display: &str, extra: &[&str], shot: &std::path::Path) -> String {
    run_view_frames(display, "24", extra, shot)
}

/// [`run_view`] for `frames` frames.
fn run_view_frames(display: &str, frames: &str, extra: &[&str], shot: &std::path::Path) -> String {
    let mut child = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args([
            "--validate",
            "view",
            "--frames",
            frames,
            "--screenshot",
            shot.to_str().unwrap(),
        ])
        .args(extra)
        .env("DISPLAY", display)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > Duration::from_secs(180) {
            let _ = child.kill();
            panic!("meshrefine view {extra:?} did not exit after --frames {frames}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "view {extra:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "view {extra:?}: {stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("saved"));
    stderr.into_owned()
}

/// Pixels in the central third that differ from the top-left (background) pixel.
fn covered(shot: &std::path::Path) -> (usize, usize) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(shot).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let (w, h) = (info.width as usize, info.height as usize);
    let px = |x: usize, y: usize| &buf[(y * w + x) * 4..(y * w + x) * 4 + 3];
    let bg = px(0, 0).to_vec();
    let mut n = 0;
    let mut total = 0;
    for y in h / 3..2 * h / 3 {
        for x in w / 3..2 * w / 3 {
            total += 1;
            if px(x, y) != &bg[..] {
                n += 1;
            }
        }
    }
    (n, total)
}

#[test]
fn window_demo_presents_and_screenshots() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, extra) in [
        // Multisampled by default (the panel then draws over the resolved image); one sample too.
        ("pattern", vec!["--wireframe", "--animate"]),
        ("pattern-1x", vec!["--wireframe", "--msaa", "1"]),
        ("tess", vec!["--driver", "tess", "--level", "8"]),
        // Adaptive, animated: the level pass writes the levels every frame (bounds again for
        // every animated mesh), both drivers.
        (
            "tess-adaptive",
            vec!["--driver", "tess", "--pixel-error", "2", "--animate"],
        ),
        ("pattern-adaptive", vec!["--pixel-error", "2", "--animate"]),
        ("static", vec!["--driver", "static", "--level", "4"]),
        // Loop, animated: the M0 -> M1 passes run every frame before the draws.
        (
            "loop",
            vec!["--surface", "loop", "--animate", "--level", "4"],
        ),
        (
            "loop-tess",
            vec!["--surface", "loop", "--driver", "tess", "--level", "4"],
        ),
        // 372 x 1024² triangles a frame would take minutes on lavapipe: the demo lowers the
        // level to keep frames under a second, and says so.
        ("budget", vec!["--level", "1024"]),
        // The same adaptively (noise at 0.25 px: about 12 million triangles up to level 256):
        // the largest level is lowered instead.
        (
            "budget-adaptive",
            vec![
                "--displace",
                "noise",
                "--pixel-error",
                "0.25",
                "--max-level",
                "256",
            ],
        ),
        // A bound no level meets: the window says so on standard error, as render does.
        ("unmet", vec!["--pixel-error", "0.25", "--max-level", "8"]),
    ] {
        let shot = dir.join(format!("{name}.png"));
        let _ = std::fs::remove_file(&shot);
        let stderr = run_view(&x.display, &extra, &shot);
        if name.ends_with("-adaptive") {
            assert!(
                !stderr.contains("instead of adaptively"),
                "{name}: {stderr}"
            );
        }
        if name == "unmet" {
            // Said once (the kinds do not change), not every frame.
            let said = "px bound is not met on ";
            assert_eq!(stderr.matches(said).count(), 1, "{stderr}");
            assert!(
                stderr.contains("note: the 0.25 px bound is not met on ")
                    && stderr.contains("they need a level above the largest, 8 (--max-level)"),
                "{stderr}"
            );
        }
        if name == "budget-adaptive" {
            assert!(
                stderr.contains(
                    "max level 256 would take over a second a frame on this software device at 0.25 px: drawing up to level "
                ),
                "{stderr}"
            );
        }
        if name == "budget" {
            assert!(
                stderr.contains("level 1024 would take over a second a frame")
                    && stderr.contains("drawing level 64"),
                "{stderr}"
            );
        }
        let (n, total) = covered(&shot);
        assert!(
            n > total / 5,
            "{name}: the screenshot's centre shows only {n} of {total} mesh pixels"
        );
    }
}

/// The frame budget counts Loop's faces by their control points (a vertex sums its face's):
/// on a bicone of two valence-500 poles, uniform level 16 (1,024,000 triangles, which the
/// triangles alone put under half a second, and about 15 s a frame on lavapipe) is lowered
/// before the first frame is drawn at it (one frame: no slow frame has been measured).
#[test]
fn the_frame_budget_counts_loop_control_points() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let obj = common::bicone_obj(500);
    let mesh = dir.join("bicone500.obj");
    std::fs::write(&mesh, obj).unwrap();
    let shot = dir.join("bicone500.png");
    #[rustfmt::skip]
    let stderr = run_view_frames(&x.display, "1", &[
        mesh.to_str().unwrap(), "--surface", "loop", "--level", "16",
    ], &shot);
    let said = "level 16 would take over a second a frame on this software device: drawing level ";
    let at = stderr.find(said).unwrap_or_else(|| panic!("{stderr}"));
    let drawn: u32 = stderr[at + said.len()..]
        .split(|c: char| !c.is_ascii_digit())
        .next()
        .and_then(|d| d.parse().ok())
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!(drawn < 8, "{stderr}");
}

/// A window reads `--screenshot-dir`: one that is no folder is refused before the window
/// opens, in one sentence (without a reachable display it is ignored with a warning instead:
/// tests/cli_options.rs).
#[test]
fn a_window_refuses_a_screenshot_dir_that_is_no_folder() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let out = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args(["view", "--screenshot-dir", "no/such/dir", "--frames", "1"])
        .env("DISPLAY", &x.display)
        .env_remove("WAYLAND_DISPLAY")
        .env("MESHREFINE_VALIDATE", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(
        stderr.trim(),
        "error: --screenshot-dir 'no/such/dir' is not a directory (the screenshot key writes meshrefine-<n>.png there)"
    );
}

/// The panel is laid out and opaque in the very first frame (a `--frames 1 --screenshot` run
/// saves it): egui gets the passes a new panel takes to size itself, and it does not fade in.
/// On the light background the panel is dark: most of its corner of the image is (the lit mesh
/// is mostly light where it shows there).
#[test]
fn the_first_frame_shows_the_panel() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("first-frame.png");
    let _ = std::fs::remove_file(&shot);
    let args = ["--background", "light", "--width", "640", "--height", "480"];
    run_view_frames(&x.display, "1", &args, &shot);
    let (dark, total) = dark_corner(&shot);
    assert!(
        dark > total / 2,
        "only {dark} of {total} pixels of the panel's corner are dark"
    );
    // --hide-panel: the corner shows the light background and the lit mesh alone.
    let _ = std::fs::remove_file(&shot);
    run_view_frames(
        &x.display,
        "1",
        &[&args[..], &["--hide-panel"]].concat(),
        &shot,
    );
    let (dark, total) = dark_corner(&shot);
    assert!(
        dark < total / 10,
        "{dark} of {total} pixels of the corner are dark without the panel"
    );
}

/// The dark pixels of a screenshot's top-left corner, where the panel sits, and all of them.
fn dark_corner(shot: &std::path::Path) -> (usize, usize) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(shot).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let w = info.width as usize;
    let (mut dark, mut total) = (0, 0);
    for y in 60..300 {
        for x in 20..280 {
            let p = &buf[(y * w + x) * 4..(y * w + x) * 4 + 3];
            total += 1;
            dark += usize::from(p.iter().all(|&c| c < 80));
        }
    }
    (dark, total)
}

fn xdotool(display: &str, args: &[&str]) -> String {
    let out = Command::new("xdotool")
        .args(args)
        .env("DISPLAY", display)
        .output()
        .expect("xdotool is not installed: run scripts/setup.sh (apt-get install xdotool)");
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// A running `meshrefine --validate view ARGS` on `x`'s display, with its window found and
/// focused (no window manager gives it focus; winit ignores synthetic keys, so the tests type
/// through XTEST into the focused window).
struct Demo<'a> {
    x: &'a Xvfb,
    child: Child,
    window: String,
}

impl<'a> Demo<'a> {
    fn start(x: &'a Xvfb, args: &[&str]) -> Self {
        Self::start_with(x, args, &[])
    }

    /// [`Demo::start`] with environment variables `env` set for the demo.
    fn start_with(x: &'a Xvfb, args: &[&str], env: &[(&str, &str)]) -> Self {
        Self::start_in(x, args, env, None)
    }

    /// [`Demo::start_with`], the demo's current directory `dir` where given.
    fn start_in(
        x: &'a Xvfb,
        args: &[&str],
        env: &[(&str, &str)],
        dir: Option<&std::path::Path>,
    ) -> Self {
        let mut command = Command::new(env!("CARGO_BIN_EXE_meshrefine"));
        if let Some(dir) = dir {
            command.current_dir(dir);
        }
        let mut child = command
            .args(["--validate", "view"])
            .args(args)
            .env("DISPLAY", &x.display)
            .envs(env.iter().copied())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let mut window = String::new();
        while window.is_empty() && start.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(200));
            let found = xdotool(&x.display, &["search", "--name", "^meshrefine"]);
            window = found.lines().next().unwrap_or("").to_string();
            // A demo that ended without a window: say how, at once.
            if window.is_empty() && child.try_wait().unwrap().is_some() {
                break;
            }
        }
        if window.is_empty() {
            let _ = child.kill();
            let out = child.wait_with_output().unwrap();
            panic!(
                "the demo's window never appeared ({args:?}, {}): {}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
        }
        xdotool(&x.display, &["windowfocus", "--sync", &window]);
        Self { x, child, window }
    }

    fn xdotool(&self, args: &[&str]) -> String {
        xdotool(&self.x.display, args)
    }

    /// The window's title once it contains `want` (the title is the HUD), within a minute.
    fn wait_title(&self, want: &str) -> String {
        let t0 = Instant::now();
        loop {
            let title = self.xdotool(&["getwindowname", &self.window]);
            if title.contains(want) {
                return title;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "title never showed {want:?}: {title}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// Waits (at most two minutes from the call: a test's earlier steps may take long on a
    /// loaded machine) for the demo to end on its own after `what`; returns its status and
    /// stderr.
    fn ended_after(mut self, what: &str) -> (Option<i32>, String) {
        let t0 = Instant::now();
        while self.child.try_wait().unwrap().is_none() {
            if t0.elapsed() > Duration::from_secs(120) {
                let _ = self.child.kill();
                panic!("the demo did not end after {what}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let out = self.child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), stderr)
    }

    /// Press Esc and expect a clean exit: status 0, no validation message. Returns stderr.
    fn quit(mut self) -> String {
        self.xdotool(&["key", "Escape"]);
        // Timed from the key (the frame under way and the last one, saved, may each be slow).
        let t0 = Instant::now();
        while self.child.try_wait().unwrap().is_none() {
            if t0.elapsed() > Duration::from_secs(180) {
                let _ = self.child.kill();
                panic!("Esc did not end the demo");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let out = self.child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        assert!(!stderr.contains("validation"), "{stderr}");
        stderr.into_owned()
    }
}

/// A PNG's RGBA pixels and size; None while it is missing or not completely written.
fn decoded(shot: &std::path::Path) -> Option<(Vec<u8>, (u32, u32))> {
    let file = std::fs::File::open(shot).ok()?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .ok()?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).ok()?;
    Some((buf, (info.width, info.height)))
}

/// Waits (at most a minute) until F12's PNG `shot` decodes whole: the demo writes it after the
/// frame's fence.
fn wait_for_screenshot(shot: &std::path::Path) {
    let t0 = Instant::now();
    while decoded(shot).is_none() {
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "F12 wrote no {shot:?}"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// The pixel at `(x, y)` of a PNG (RGB) and its size.
fn pixel(shot: &std::path::Path, x: u32, y: u32) -> ([u8; 3], (u32, u32)) {
    let (buf, (w, h)) = decoded(shot).unwrap_or_else(|| panic!("{shot:?} is not a PNG"));
    let i = ((y * w + x) * 4) as usize;
    ([buf[i], buf[i + 1], buf[i + 2]], (w, h))
}

/// Whether `px` is `background`'s colour (within 2/255 a channel).
fn is_background(px: [u8; 3], background: meshrefine::render::Background) -> bool {
    let want = meshrefine::render::background_srgb8(background);
    (0..3).all(|c| px[c].abs_diff(want[c]) <= 2)
}

#[test]
fn window_resizes_and_quits_with_escape() {
    // `--width`/`--height` size the window and `--fullscreen` fills the screen (Xvfb's
    // 1280x1024, without a window manager); F11 returns to the window's size (the one given,
    // then the one it was resized to), and the swapchain follows each resize. F12 saves the frame as meshrefine-<n>.png in `--screenshot-dir`, on
    // `--background light` (one it cannot write is said, and the demo goes on); B toggles the
    // background. Esc ends the demo after one last frame
    // that `--screenshot` saves: its size is the window's size then.
    use meshrefine::render::Background;
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window/shots");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.parent().unwrap().join("resized.png");
    let _ = std::fs::remove_file(&shot);
    let demo = Demo::start(
        &x,
        &[
            "--level",
            "4",
            "--width",
            "800",
            "--height",
            "500",
            "--fullscreen",
            "--background",
            "light",
            "--screenshot-dir",
            dir.to_str().unwrap(),
            "--screenshot",
            shot.to_str().unwrap(),
        ],
    );
    let wait_size = |want: (u32, u32)| {
        let t0 = Instant::now();
        loop {
            let geometry = demo.xdotool(&["getwindowgeometry", "--shell", &demo.window]);
            let value = |key: &str| {
                (geometry.lines())
                    .find_map(|l| l.strip_prefix(key))
                    .and_then(|v| v.parse::<u32>().ok())
            };
            if (value("WIDTH="), value("HEIGHT=")) == (Some(want.0), Some(want.1)) {
                return;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "the window never became {want:?}: {geometry}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    };
    wait_size((1280, 1024));
    // The swapchain is recreated at the next frame; the key's frame is drawn after it.
    std::thread::sleep(Duration::from_secs(1));
    demo.xdotool(&["key", "F12"]);
    let first = dir.join("meshrefine-1.png");
    wait_for_screenshot(&first);
    let (corner, size) = pixel(&first, 1279, 1023);
    assert_eq!(
        size,
        (1280, 1024),
        "the fullscreen frame is the screen's size"
    );
    assert!(is_background(corner, Background::Light), "{corner:?}");
    let (n, total) = covered(&first);
    assert!(
        n > total / 5,
        "F12's frame shows {n} of {total} mesh pixels"
    );
    // A screenshot the key cannot write is said, and the demo goes on.
    std::fs::remove_dir_all(&dir).unwrap();
    demo.xdotool(&["key", "F12"]);
    demo.xdotool(&["key", "b"]);
    demo.xdotool(&["key", "F11"]);
    wait_size((800, 500));
    demo.xdotool(&["windowsize", &demo.window, "640", "400"]);
    wait_size((640, 400));
    // Fullscreen again and back: to the size the window had then, not to --width x --height.
    demo.xdotool(&["key", "F11"]);
    wait_size((1280, 1024));
    demo.xdotool(&["key", "F11"]);
    wait_size((640, 400));
    std::thread::sleep(Duration::from_millis(500));
    let stderr = demo.quit();
    assert!(
        stderr.contains("cannot write") && stderr.contains("meshrefine-1.png"),
        "{stderr}"
    );
    assert!(!dir.exists());
    let (corner, size) = pixel(&shot, 639, 399);
    assert_eq!(
        size,
        (640, 400),
        "the last frame was not drawn at the new size"
    );
    assert!(is_background(corner, Background::Dark), "B: {corner:?}");
}

/// Without `--screenshot-dir`, F12 writes `meshrefine-1.png` into the current directory
/// (window.md).
#[test]
fn f12_writes_into_the_current_directory_by_default() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window/cwd");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let demo = Demo::start_in(&x, &["--level", "2"], &[], Some(&dir));
    // The key's frame is drawn after the first ones.
    std::thread::sleep(Duration::from_secs(1));
    demo.xdotool(&["key", "F12"]);
    let first = dir.join("meshrefine-1.png");
    wait_for_screenshot(&first);
    demo.quit();
    let (n, total) = covered(&first);
    assert!(
        n > total / 5,
        "F12's frame shows {n} of {total} mesh pixels"
    );
}

/// `H` hides the panel and shows it again: F12's frames show the panel's corner dark, then the
/// light background there, then the panel again.
#[test]
fn h_hides_and_shows_the_panel() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window/panel-key");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[rustfmt::skip]
    let args = ["--background", "light", "--level", "2", "--width", "640", "--height", "480"];
    let demo = Demo::start_in(&x, &args, &[], Some(&dir));
    let mut shots = Vec::new();
    for (n, key) in [(1, None), (2, Some("h")), (3, Some("h"))] {
        if let Some(key) = key {
            demo.xdotool(&["key", key]);
        }
        // The key's frame is drawn after the first ones.
        std::thread::sleep(Duration::from_secs(1));
        demo.xdotool(&["key", "F12"]);
        let shot = dir.join(format!("meshrefine-{n}.png"));
        wait_for_screenshot(&shot);
        shots.push(dark_corner(&shot));
    }
    demo.quit();
    let [(shown, total), (hidden, _), (again, _)] = shots[..] else {
        unreachable!()
    };
    assert!(shown > total / 2, "panel shown: {shown} of {total} dark");
    assert!(
        hidden < total / 10,
        "panel hidden: {hidden} of {total} dark"
    );
    assert!(
        again > total / 2,
        "panel shown again: {again} of {total} dark"
    );
}

#[test]
fn switching_to_loop_on_a_mesh_it_refuses_shows_pn() {
    // The file loads for the other surfaces (its degenerate face dropped with a warning), but
    // Loop would subdivide a hole: S from stpn to loop says why and shows pn instead.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("loop_refused.obj");
    let cube = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/models/cube_tri.obj"
    ))
    .unwrap();
    std::fs::write(&obj, format!("{cube}\nf 1 2 2\n")).unwrap();
    let demo = Demo::start(
        &x,
        &[obj.to_str().unwrap(), "--surface", "stpn", "--level", "4"],
    );
    // Loop is refused when a frame prepares it: the first frame drawn before the key, then
    // pn shown in its place.
    demo.wait_title("| stpn + none |");
    demo.xdotool(&["key", "s"]);
    demo.wait_title("| pn + none |");
    // S goes on from loop, not from the pn shown: flat, phong, pn, stpn, then loop again.
    for _ in 0..4 {
        demo.xdotool(&["key", "s"]);
        std::thread::sleep(Duration::from_secs(2));
    }
    let stderr = demo.quit();
    assert!(stderr.contains("dropped 1 degenerate face"), "{stderr}");
    assert!(
        stderr.contains("the loop surface cannot subdivide it")
            && stderr.contains("repeats a vertex index")
            && stderr.contains("showing pn instead"),
        "{stderr}"
    );
    assert_eq!(stderr.matches("showing pn instead").count(), 1, "{stderr}");
    // The file is named once in the warning.
    let line = stderr.lines().find(|l| l.contains("showing pn")).unwrap();
    assert_eq!(line.matches("loop_refused.obj").count(), 1, "{line}");
}

#[test]
fn switching_to_stpn_with_three_crease_corners_names_the_file() {
    // Creases derived at 30° give some of Spot's triangles three crease corners, which stpn
    // cannot take; started as pn, S to stpn names the file and the remedy, and shows pn.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let spot = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/models/spot_control_tri.obj"
    );
    let demo = Demo::start(
        &x,
        &[
            spot,
            "--surface",
            "pn",
            "--crease-angle",
            "30",
            "--level",
            "4",
        ],
    );
    demo.xdotool(&["key", "s"]);
    std::thread::sleep(Duration::from_secs(4));
    let stderr = demo.quit();
    assert!(
        stderr.contains("spot_control_tri.obj'")
            && stderr.contains("three crease vertices")
            && stderr.contains("start the demo with --surface stpn")
            && stderr.contains("showing pn instead"),
        "{stderr}"
    );
}

/// Keys past their ends say they change nothing (`[` at 0.25 px, `-` at level 1), the notes on
/// an unmet pixel error are said again when what is drawn changes (`D` onto sine: other elements
/// miss it), and a height map asked for on a mesh without texture coordinates blames the mesh,
/// promising no surface that takes it back.
#[test]
fn keys_at_their_ends_and_notes_follow_what_is_drawn() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    #[rustfmt::skip]
    let args = [
        "--pixel-error", "0.25", "--max-level", "4", "--displace", "heightmap", "--width", "480",
        "--height", "320",
    ];
    let demo = Demo::start(&x, &args);
    demo.wait_title("| pn + none |");
    demo.xdotool(&["key", "bracketleft"]);
    demo.xdotool(&["key", "d"]);
    demo.wait_title("| pn + sine |");
    demo.xdotool(&["key", "m"]);
    demo.wait_title("level 16");
    for _ in 0..6 {
        demo.xdotool(&["key", "minus"]);
    }
    demo.wait_title("level 1 ");
    let stderr = demo.quit();
    let said = "px bound is not met on ";
    assert_eq!(stderr.matches(said).count(), 2, "{stderr}");
    for line in [
        "'[' changes nothing: the pixel error is at its smallest, 0.25 px",
        "'-' changes nothing: 1 is the smallest level",
        "the mesh has no texture coordinates (vt on every face), where the heightmap displacement reads its map: showing no displacement\n",
    ] {
        assert!(stderr.contains(line), "{line:?} not in {stderr}");
    }
}

/// `]` doubles the pixel error up to 16 px and past it says it changes nothing; a key marked
/// for the other mode says so (`L` in adaptive mode, `G` in uniform mode).
#[test]
fn keys_at_the_top_and_of_the_other_mode_say_so() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    #[rustfmt::skip]
    let args = ["--pixel-error", "8", "--max-level", "4", "--width", "320", "--height", "240"];
    let demo = Demo::start(&x, &args);
    demo.wait_title("adaptive 8 px");
    demo.xdotool(&["key", "bracketright"]);
    demo.wait_title("adaptive 16 px");
    demo.xdotool(&["key", "bracketright"]);
    demo.xdotool(&["key", "l"]);
    demo.xdotool(&["key", "m"]);
    demo.wait_title("level 16");
    demo.xdotool(&["key", "g"]);
    let stderr = demo.quit();
    for line in [
        "']' changes nothing: the pixel error is at its largest, 16 px",
        "'l' (LOD by distance) acts in uniform mode only (M switches to it)",
        "'g' acts in adaptive mode only (M switches to it)",
    ] {
        assert!(stderr.contains(line), "{line:?} not in {stderr}");
    }
}

/// The title names the surface and displacement (and geomorphing where it is off); `S` onto
/// `loop`, which cannot take the height map, switches the displacement off with a warning,
/// and the next surface that takes it shows it again.
#[test]
fn surfaces_that_cannot_take_the_height_map_drop_it_until_one_can() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let grid = common::model_path("grid_uv_8x8.obj");
    let args = [grid.to_str().unwrap(), "--displace", "heightmap"];
    let demo = Demo::start(&x, &[&args[..], &["--geomorph", "off"]].concat());
    let title = demo.wait_title("| pn + heightmap |");
    assert!(title.contains("geomorph off"), "{title}");
    for want in ["stpn + heightmap", "loop + none", "flat + heightmap"] {
        demo.xdotool(&["key", "s"]);
        demo.wait_title(&format!("| {want} |"));
    }
    let stderr = demo.quit();
    assert!(
        stderr.contains("the loop surface has no texture coordinates")
            && stderr
                .contains("the heightmap displacement comes back with a surface that takes it")
            && stderr
                .contains("the flat surface takes the heightmap displacement: showing it again"),
        "{stderr}"
    );
}

#[test]
fn keys_switch_driver_level_and_views() {
    // Typed keys reach the demo and change what it draws; the title (the HUD) reports it.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    // Mesa's on-disk shader cache would make the tessellator's first draw quick where an
    // earlier run compiled the same shaders, and the title's compiling note too brief to see.
    // The keys' levels are drawn as asked: the frame budget, which lowers a level whose frames
    // it measures at over a second on a software device (lavapipe's tessellator at level 16 on
    // a slow machine), depends on the machine's speed and has tests of its own
    // (`slow_wireframe_frames_lower_the_level`, `the_frame_budget_counts_loop_control_points`).
    let demo = Demo::start_with(
        &x,
        &["--level", "8", "--no-frame-budget"],
        &[("MESA_SHADER_CACHE_DISABLE", "true")],
    );
    demo.wait_title("pattern/instanced level 8");
    // The camera, reported last in the title as `--eye X,Y,Z --look-at X,Y,Z`: a right drag
    // pans (the look-at moves), R returns to the start, the wheel zooms and a middle drag pans,
    // Z frames the mesh again (from the start's direction: the start framing), and after an
    // orbit and a pan Home frames it from the new direction (another eye and look-at).
    let camera = |title: &str| {
        let c = title.rsplit(" | ").next().unwrap().to_string();
        let look_at = c.split(" --look-at ").nth(1).unwrap_or("").to_string();
        (c, look_at)
    };
    let wait_camera = |what: &str, ok: &dyn Fn(&(String, String)) -> bool| {
        let t0 = Instant::now();
        loop {
            let title = demo.xdotool(&["getwindowname", &demo.window]);
            let c = camera(&title);
            if ok(&c) {
                return c;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "{what}: the camera never changed so: {title}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    };
    let start = wait_camera("start", &|(c, _)| c.starts_with("--eye "));
    // Over the panel (anchored top-left) the wheel scrolls the panel, and a right drag that
    // starts there pans nothing, though it ends over the mesh: the camera stays the start's
    // once the key typed after them has been drawn (events are handled in order).
    demo.xdotool(&["mousemove", "--window", &demo.window, "150", "300"]);
    for _ in 0..3 {
        demo.xdotool(&["click", "5"]);
    }
    demo.xdotool(&["mousedown", "3"]);
    demo.xdotool(&["mousemove", "--window", &demo.window, "900", "400"]);
    demo.xdotool(&["mouseup", "3"]);
    demo.xdotool(&["key", "k"]);
    let title = demo.wait_title("level 8 cage");
    assert_eq!(
        camera(&title),
        start,
        "the panel's events moved the camera: {title}"
    );
    demo.xdotool(&["key", "k"]);
    wait_camera("cage off", &|_| {
        !demo
            .xdotool(&["getwindowname", &demo.window])
            .contains("cage")
    });
    let drag = |button: &str, to: &str| {
        demo.xdotool(&["mousemove", "--window", &demo.window, "900", "400"]);
        demo.xdotool(&["mousedown", button]);
        demo.xdotool(&["mousemove", "--window", &demo.window, to, "440"]);
        demo.xdotool(&["mouseup", button]);
    };
    drag("3", "960");
    wait_camera("right drag", &|(c, l)| *c != start.0 && *l != start.1);
    demo.xdotool(&["key", "r"]);
    wait_camera("R", &|c| *c == start);
    for _ in 0..3 {
        demo.xdotool(&["click", "5"]);
    }
    wait_camera("wheel", &|(c, l)| *c != start.0 && *l == start.1);
    drag("2", "850");
    wait_camera("middle drag", &|(_, l)| *l != start.1);
    demo.xdotool(&["key", "z"]);
    wait_camera("Z", &|c| *c == start);
    drag("1", "1000");
    wait_camera("orbit", &|(c, _)| *c != start.0);
    drag("3", "960");
    let panned = wait_camera("pan after the orbit", &|(_, l)| *l != start.1);
    demo.xdotool(&["key", "Home"]);
    wait_camera("Home", &|(c, l)| {
        *c != start.0 && *c != panned.0 && *l != panned.1
    });
    // The tessellator's pipelines are new here: while the frame waits for them (compiled at
    // their first draw on lavapipe) the title says so.
    demo.xdotool(&["key", "3"]);
    demo.wait_title("compiling this frame's new pipelines");
    for (key, want) in [
        ("3", "tess level 8"),
        // Beyond the level the demo started at.
        ("plus", "tess level 16"),
        ("minus", "tess level 8"),
        ("minus", "tess level 4"),
        ("w", "level 4 wire"),
        ("u", "pattern/ubo level 4 wire"),
        ("p", "pattern/push level 4 wire"),
        ("i", "pattern/instanced level 4 wire"),
        // `=` and `_` are `+` and `-` without the shift key (and with it).
        ("equal", "pattern/instanced level 8 wire"),
        ("underscore", "pattern/instanced level 4 wire"),
        ("k", "pattern/instanced level 4 wire cage"),
        ("1", "static level 4 wire cage"),
        ("2", "pattern/instanced level 4 wire cage"),
        ("1", "static level 4 wire cage"),
        ("l", "(LOD)"),
        ("a", "animated"),
    ] {
        let title = {
            demo.xdotool(&["key", key]);
            demo.wait_title(want)
        };
        if want == "(LOD)" {
            // LOD chooses among the levels up to the one it was turned on at (4).
            let level: u32 = (title.split(" level ").nth(1))
                .and_then(|t| t.split(' ').next()?.parse().ok())
                .unwrap_or_else(|| panic!("{title}"));
            assert!(level <= 4, "{title}");
        }
    }
    // Adaptive mode's keys change nothing in uniform mode (and say so): switching to it shows
    // culling on and the levels not frozen, as they were.
    demo.xdotool(&["key", "c"]);
    demo.xdotool(&["key", "f"]);
    demo.xdotool(&["key", "m"]);
    let title = demo.wait_title("adaptive");
    assert!(
        title.contains("cull on") && !title.contains("frozen"),
        "{title}"
    );
    let stderr = demo.quit();
    assert!(
        stderr.contains("'c' acts in adaptive mode only (M switches to it)"),
        "{stderr}"
    );
}

#[test]
fn a_window_destroyed_by_another_client_ends_the_demo_with_a_sentence() {
    // `xdotool windowclose` destroys the window under winit's feet (X then answers BadDrawable
    // where winit expects a geometry): one sentence and status 1, no panic, no hang.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let demo = Demo::start(&x, &["--level", "2"]);
    demo.xdotool(&["windowclose", &demo.window]);
    let (status, stderr) = demo.ended_after("its window was destroyed");
    assert_eq!(status, Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    // window.md's sentence, whichever noticed first (winit, or the lost Vulkan surface).
    assert!(
        stderr.ends_with("error: cannot show 'the default mesh (spot)': the window system failed: the window was closed by another program, or its display went away\n"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("validation") && !stderr.contains("unwrap"),
        "{stderr}"
    );
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
}

/// On a device without `fillModeNonSolid` (`MESHREFINE_HIDE_FEATURES`) the wireframe is off,
/// `--wireframe` too: said once at the start, and `W` says it changes nothing, validated.
#[test]
fn w_without_line_fill_says_it_changes_nothing() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let hidden = [("MESHREFINE_HIDE_FEATURES", "fillModeNonSolid")];
    #[rustfmt::skip]
    let args = ["--level", "2", "--wireframe", "--width", "320", "--height", "240"];
    let demo = Demo::start_with(&x, &args, &hidden);
    demo.wait_title("level 2");
    demo.xdotool(&["key", "w"]);
    // The cage is a line list, which needs no fillModeNonSolid: it still shows.
    demo.xdotool(&["key", "k"]);
    let title = demo.wait_title(" cage |");
    assert!(!title.contains(" wire"), "{title}");
    let stderr = demo.quit();
    for line in [
        "no fillModeNonSolid, the wireframe view is off",
        "'w' changes nothing here: the device has no fillModeNonSolid, which the wireframe's lines need",
    ] {
        assert_eq!(stderr.matches(line).count(), 1, "{line:?} in {stderr}");
    }
}

/// The window starts in the state its options ask for (`--lod`, `--wireframe cage`, `--driver
/// tess` with `--submit push`, which its keys use once they switch to `pattern`), and warns of
/// no option it does not read yet (`--alpha` on `pn`: its keys may switch to `phong`).
#[test]
fn the_window_starts_as_its_options_say() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    #[rustfmt::skip]
    let args = [
        "--lod", "--level", "4", "--wireframe", "cage", "--driver", "tess", "--submit", "push",
        "--surface", "pn", "--alpha", "0.3", "--width", "320", "--height", "240",
    ];
    let demo = Demo::start(&x, &args);
    demo.wait_title("meshrefine | tess level 4 (LOD) cage | pn + none |");
    demo.xdotool(&["key", "2"]);
    demo.wait_title("meshrefine | pattern/push level 4 (LOD) cage |");
    let stderr = demo.quit();
    assert!(!stderr.contains("warning"), "{stderr}");
}

/// A window whose attachments the device cannot allocate is refused in the sentence `render`
/// gives, before any of them is made (no validation message): here at 640x480 and 4 samples
/// under a limit lowered to 4,000,000 bytes (`MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE`), at the
/// start and when a window that fits is resized past it.
#[test]
fn a_window_too_large_to_allocate_is_one_sentence() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let child = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args(["--validate", "view", "--frames", "3", "--msaa", "4"])
        .args(["--width", "640", "--height", "480"])
        .env("DISPLAY", &x.display)
        .env("MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE", "4000000")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = common::cli::wait_at_most(child, Duration::from_secs(120))
        .expect("the demo did not end on a window too large to allocate");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(
        stderr.trim_end(),
        "error: cannot show 'the default mesh (spot)': a 640x480 image at 4 sample(s) per pixel needs 4.7 MiB per attachment, over the 3.8 MiB this device allocates at once (maxMemoryAllocationSize): fewer samples per pixel (--msaa) or a smaller image fits"
    );
    // A window that fits, resized past the limit: the same sentence when the swapchain is
    // made again, status 1.
    let limit = [("MESHREFINE_MAX_MEMORY_ALLOCATION_SIZE", "4000000")];
    let args = [
        "--msaa", "4", "--level", "2", "--width", "320", "--height", "240",
    ];
    let demo = Demo::start_with(&x, &args, &limit);
    demo.wait_title("level 2");
    demo.xdotool(&["windowsize", &demo.window, "640", "480"]);
    let (status, stderr) = demo.ended_after("its window grew past the limit");
    assert_eq!(status, Some(1), "{stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");
    assert!(
        stderr.ends_with("a 640x480 image at 4 sample(s) per pixel needs 4.7 MiB per attachment, over the 3.8 MiB this device allocates at once (maxMemoryAllocationSize): fewer samples per pixel (--msaa) or a smaller image fits\n"),
        "{stderr}"
    );
}

/// The X server going away under a running demo ends it at once with status 1 (window.md):
/// Xlib's message, or the window system's sentence where the presentation sees the lost
/// connection first; no panic, no hang.
#[test]
#[allow(unsafe_code)]
fn the_x_server_going_away_ends_the_demo_with_status_1() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let demo = Demo::start(&x, &["--level", "2", "--width", "320", "--height", "240"]);
    demo.wait_title("level 2");
    // SAFETY: sends SIGTERM to the Xvfb child this test started (still running: it is only
    // waited for when `x` drops).
    let killed = unsafe { libc::kill(x.child.id() as libc::pid_t, libc::SIGTERM) };
    assert_eq!(killed, 0);
    let (status, stderr) = demo.ended_after("its X server went away");
    assert_eq!(status, Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    // Whichever sees the lost connection first ends the demo: Xlib's handler, or the
    // swapchain's presentation (the window system's sentence).
    let xlib = format!("X connection to {} broken", x.display);
    let ours = "error: cannot show 'the default mesh (spot)': the window system failed: the window was closed by another program, or its display went away\n";
    assert!(stderr.contains(&xlib) || stderr.ends_with(ours), "{stderr}");
    assert!(!stderr.contains("validation"), "{stderr}");
}

/// The title's refined triangle count (`... -> N triangles`).
fn title_triangles(title: &str) -> u64 {
    let after = title
        .split(" -> ")
        .nth(1)
        .unwrap_or_else(|| panic!("{title}"));
    let n = after.split(' ').next().unwrap();
    n.parse().unwrap_or_else(|_| panic!("{title}"))
}

#[test]
fn the_demo_starts_adaptive_and_keys_change_its_controls() {
    // Without --level the demo draws adaptively (pattern driver, 1 px, culling on); M, [ ], C, G,
    // F and + - change the mode, pixel error, culling, geomorphing, frozen levels and largest
    // level, and the title reports each. Frozen levels stay when the camera zooms in; unfrozen,
    // they follow.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let shot = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window/adaptive-keys.png");
    std::fs::create_dir_all(shot.parent().unwrap()).unwrap();
    let _ = std::fs::remove_file(&shot);
    // The frame budget would lower the largest level on a loaded machine: the keys' effects
    // are checked here, the budget by window_demo_presents_and_screenshots.
    let demo = Demo::start(
        &x,
        &["--screenshot", shot.to_str().unwrap(), "--no-frame-budget"],
    );
    let wait_title = |want: &str, unwanted: &str| {
        let t0 = Instant::now();
        loop {
            let title = demo.xdotool(&["getwindowname", &demo.window]);
            if title.contains(want) && (unwanted.is_empty() || !title.contains(unwanted)) {
                return title;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "title never showed {want:?} without {unwanted:?}: {title}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    };
    let first = wait_title("pattern/instanced adaptive 1 px max level 64 cull on", "");
    assert!(
        first.contains("uniform level") && first.contains("| levels ") && first.contains("culled"),
        "{first}"
    );
    // The level pass's GPU time, from the frame before's timestamps.
    wait_title(" ms GPU, choosing ", "");
    for (key, want, unwanted) in [
        ("bracketright", "adaptive 2 px", ""),
        ("bracketleft", "adaptive 1 px", ""),
        ("bracketleft", "adaptive 0.5 px", ""),
        ("c", "0.5 px max level 64 cull off", ""),
        ("c", "cull on", ""),
        // Geomorphing off and on again (the title says only its absence).
        ("g", "cull on geomorph off", ""),
        ("g", "cull on", "geomorph off"),
        ("minus", "max level 32", ""),
        // The static driver refines adaptively on the CPU (the CPU baseline).
        ("1", "static adaptive 0.5 px max level 32", ""),
        // The static driver chooses its levels on the CPU: no level pass (no key pressed). It
        // never glides: G changes nothing (and says so, below).
        ("", "level pass none", ""),
        (
            "g",
            "static adaptive 0.5 px max level 32 cull on",
            "geomorph off",
        ),
        ("3", "tess adaptive 0.5 px max level 32", ""),
        ("m", "tess level 16", "adaptive"),
        ("m", "tess adaptive", ""),
    ] {
        if !key.is_empty() {
            demo.xdotool(&["key", key]);
        }
        wait_title(want, unwanted);
    }
    // Frozen: zooming out changes nothing the levels chose; unfrozen, fewer triangles (the
    // whole mesh stays in view, so culling does not change: only the levels fall).
    demo.xdotool(&["key", "f"]);
    let frozen = wait_title("cull on frozen", "");
    demo.xdotool(&["mousemove", "--window", &demo.window, "900", "400"]);
    for _ in 0..4 {
        demo.xdotool(&["click", "5"]);
    }
    std::thread::sleep(Duration::from_secs(2));
    let zoomed = wait_title("frozen", "");
    assert_eq!(
        title_triangles(&zoomed),
        title_triangles(&frozen),
        "frozen levels changed with the camera: {frozen} / {zoomed}"
    );
    demo.xdotool(&["key", "f"]);
    let t0 = Instant::now();
    loop {
        let title = wait_title("tess adaptive", "frozen");
        if title_triangles(&title) < title_triangles(&frozen) {
            break;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "unfrozen levels did not follow the zoom: {frozen} / {title}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    // The levels view of the adaptive frame still shows the mesh.
    demo.xdotool(&["key", "n"]);
    demo.xdotool(&["key", "n"]);
    let stderr = demo.quit();
    assert!(
        stderr.contains("'g' changes nothing here: the static driver never glides"),
        "{stderr}"
    );
    let (n, total) = covered(&shot);
    assert!(
        n > total / 5,
        "only {n} of {total} centre pixels show the mesh"
    );
}

/// The camera the demo starts with, from its title (`--eye X,Y,Z --look-at X,Y,Z`, the mesh's
/// coordinates), as (eye, look-at).
fn start_camera(x: &Xvfb, args: &[&str]) -> ([f64; 3], [f64; 3]) {
    let demo = Demo::start(x, args);
    let t0 = Instant::now();
    let title = loop {
        let title = demo.xdotool(&["getwindowname", &demo.window]);
        if title.contains("--eye ") {
            break title;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "no camera in the title: {title}"
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    demo.quit();
    let point = |after: &str| -> [f64; 3] {
        let text = title.split(after).nth(1).unwrap();
        let numbers: Vec<f64> = (text.split_whitespace().next().unwrap().split(','))
            .map(|v| v.parse().unwrap())
            .collect();
        [numbers[0], numbers[1], numbers[2]]
    };
    (point("--eye "), point("--look-at "))
}

#[test]
fn a_lone_eye_or_look_at_is_completed_from_the_fitted_camera() {
    // As render: the one default camera (fitted to the surface drawn), and an --eye or
    // --look-at given alone keeps the other from it; --fov alone fits the eye at it.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() <= 2e-3);
    let (eye, look_at) = start_camera(&x, &["--level", "2"]);
    let (lone_eye, its_look_at) = start_camera(&x, &["--level", "2", "--eye", "2,1,2"]);
    assert!(close(lone_eye, [2.0, 1.0, 2.0]), "{lone_eye:?}");
    assert!(close(its_look_at, look_at), "{its_look_at:?} {look_at:?}");
    let (its_eye, _) = start_camera(&x, &["--level", "2", "--look-at", "0,0.1,0"]);
    assert!(close(its_eye, eye), "{its_eye:?} {eye:?}");
    // A narrower field of view: fitted from farther away.
    let (narrow_eye, narrow_look_at) = start_camera(&x, &["--level", "2", "--fov", "20"]);
    let distance = |e: [f64; 3], t: [f64; 3]| (0..3).map(|i| (e[i] - t[i]).powi(2)).sum::<f64>();
    assert!(
        distance(narrow_eye, narrow_look_at) > 4.0 * distance(eye, look_at),
        "{narrow_eye:?} {eye:?}"
    );
    // Loop's limit surface, not its control cage, as export (render's camera) fits it.
    let (loop_eye, loop_look_at) = start_camera(&x, &["--surface", "loop", "--level", "2"]);
    let obj = std::env::temp_dir().join(format!("window-loop-{}.obj", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
        .args([
            "export",
            "--surface",
            "loop",
            "--pixel-error",
            "4",
            "--width",
            "1280",
        ])
        .args(["--height", "720", "-o"])
        .arg(&obj)
        .env_remove("DISPLAY")
        .env("MESHREFINE_VALIDATE", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && !stderr.contains("validation"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&obj).unwrap();
    let _ = std::fs::remove_file(&obj);
    let header = text
        .lines()
        .find(|l| l.starts_with("# camera eye "))
        .unwrap();
    let v: Vec<f64> = (header.split_whitespace().skip(3).take(7))
        .filter_map(|w| w.parse().ok())
        .collect();
    // The title rounds to two decimals at Spot's scale.
    let rounded = |a: [f64; 3], b: &[f64]| (0..3).all(|i| (a[i] - b[i]).abs() <= 6e-3);
    assert!(rounded(loop_eye, &v[0..3]), "{loop_eye:?} {header}");
    assert!(rounded(loop_look_at, &v[3..6]), "{loop_look_at:?} {header}");
}

/// CPU time (user + system, in clock ticks) the process has used so far.
fn cpu_ticks(pid: u32) -> u64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    // Fields after the command's closing parenthesis: utime and stime are the 12th and 13th.
    let rest = &stat[stat.rfind(')').unwrap() + 2..];
    let f: Vec<u64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .map(|w| w.parse().unwrap())
        .collect();
    f[0] + f[1]
}

/// A minimised window draws nothing (X11 reports no zero size for it: winit's minimised state
/// and occlusion say it), nor does one wholly covered by another window, and each draws again
/// once shown.
#[test]
fn a_minimised_or_covered_window_pauses() {
    // Alone: another demo's frames would slow this one's, and its own CPU rates are measured.
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    // Minimising is the window manager's business.
    let mut wm = Command::new("openbox")
        .env("DISPLAY", &x.display)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("openbox is not installed: run scripts/setup.sh (apt-get install openbox)");
    let model = common::model_path("tetrahedron.obj");
    let demo = Demo::start(
        &x,
        &[model.to_str().unwrap(), "--width", "320", "--height", "240"],
    );
    let title = || demo.xdotool(&["getwindowname", &demo.window]);
    let frames_flow = || {
        let first = title();
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(120) {
            std::thread::sleep(Duration::from_millis(200));
            let now = title();
            if now != first && now.contains(" fps") {
                return true;
            }
        }
        false
    };
    assert!(frames_flow(), "no frames at the start: {}", title());
    let pid = demo.child.id();
    // CPU ticks a second while shown, then while `hide` keeps it out of sight.
    let paused = |what: &str, hide: &dyn Fn()| {
        let (visible0, t0) = (cpu_ticks(pid), Instant::now());
        std::thread::sleep(Duration::from_secs(2));
        let visible = cpu_ticks(pid) - visible0;
        let visible_s = t0.elapsed().as_secs_f64();
        hide();
        std::thread::sleep(Duration::from_secs(1));
        let (hidden0, t0) = (cpu_ticks(pid), Instant::now());
        std::thread::sleep(Duration::from_secs(3));
        let hidden = cpu_ticks(pid) - hidden0;
        let hidden_s = t0.elapsed().as_secs_f64();
        // Drawing keeps a core busy (about 100 ticks a second); paused, the process sleeps.
        assert!(
            (hidden as f64 / hidden_s) < 0.1 * (visible as f64 / visible_s),
            "{what}: {hidden} ticks in {hidden_s:.1} s, shown: {visible} in {visible_s:.1} s"
        );
    };
    paused("minimised", &|| {
        demo.xdotool(&["windowminimize", "--sync", &demo.window]);
    });
    demo.xdotool(&["windowactivate", "--sync", &demo.window]);
    assert!(frames_flow(), "no frames after restoring: {}", title());
    // Another client's window over the whole screen, raised above the demo's.
    let cover = std::cell::RefCell::new(None);
    paused("covered", &|| {
        let child = Command::new("xmessage")
            .args(["-geometry", "2000x2000+0+0", "covering the demo"])
            .env("DISPLAY", &x.display)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("xmessage is not installed: run scripts/setup.sh (apt-get install x11-utils)");
        *cover.borrow_mut() = Some(child);
        // Measured once the cover is mapped (the window manager places it first).
        let t0 = Instant::now();
        while demo
            .xdotool(&["search", "--onlyvisible", "--class", "Xmessage"])
            .is_empty()
        {
            assert!(
                t0.elapsed() < Duration::from_secs(30),
                "xmessage never showed"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    });
    let mut child = cover.borrow_mut().take().unwrap();
    let _ = child.kill();
    let _ = child.wait();
    assert!(frames_flow(), "no frames once uncovered: {}", title());
    demo.quit();
    let _ = wm.kill();
    let _ = wm.wait();
}

/// `--no-frame-budget` draws what is asked even where the slower estimate puts a frame over a
/// second: Spot's cage at uniform level 96 (3.4 M triangles, past the estimate's second) is
/// lowered to 64 without it and drawn at 96 with it, with no word of the budget.
#[test]
fn no_frame_budget_draws_the_level_asked() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    #[rustfmt::skip]
    let args = [
        "--level", "96", "--surface", "flat", "--msaa", "1", "--width", "320", "--height", "240",
    ];
    let said =
        "level 96 would take over a second a frame on this software device: drawing level 64";
    let demo = Demo::start(&x, &args);
    demo.wait_title("level 64 ");
    let stderr = demo.quit();
    assert!(stderr.contains(said), "{stderr}");
    let demo = Demo::start(&x, &[&args[..], &["--no-frame-budget"]].concat());
    demo.wait_title("level 96 ");
    let stderr = demo.quit();
    assert!(!stderr.contains("would take over a second"), "{stderr}");
}

/// The frame budget learns from slow frames in uniform mode too: the tessellator's wireframe
/// pass costs lavapipe far more a triangle than the estimate (about 20 s a frame for
/// spot_tri at level 8), so after a measured slow frame the demo draws a level that fits and
/// says so, instead of every frame taking seconds. With open seams, so that every line is
/// drawn (on a closed surface the lines of faces turned away are culled, and level 24's
/// frames come in under a second).
#[test]
fn slow_wireframe_frames_lower_the_level() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let model = common::model_path("spot_control_tri.obj");
    let demo = Demo::start(
        &x,
        &[
            model.to_str().unwrap(),
            "--driver",
            "tess",
            "--level",
            "24",
            "--wireframe",
            "--pn-seams",
            "open",
            "--width",
            "480",
            "--height",
            "320",
            "--msaa",
            "1",
        ],
    );
    let t0 = Instant::now();
    let title = loop {
        let title = demo.xdotool(&["getwindowname", &demo.window]);
        let level =
            (title.split(" level ").nth(1)).and_then(|t| t.split(' ').next()?.parse::<u32>().ok());
        if level.is_some_and(|l| l < 24) {
            break title;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(150),
            "the level never came down: {title}"
        );
        std::thread::sleep(Duration::from_millis(200));
    };
    assert!(title.contains(" wire"), "{title}");
    let stderr = demo.quit();
    assert!(
        stderr.contains("level 24 would take over a second a frame on this software device"),
        "{stderr}"
    );
}

/// A `--pixel-error` outside the slider's 0.25 to 16 px is drawn at the nearest end, with a
/// warning (docs/window.md); within it, no warning. A `--max-level` that is not a power of two
/// starts the window too (docs/cli.md).
#[test]
fn a_pixel_error_past_the_slider_is_held_at_its_end_with_a_warning() {
    let _guard = common::gpu_lock();
    let x = Xvfb::start();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("window");
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("slider-end.png");
    let size = ["--width", "320", "--height", "240"];
    for (px, said) in [
        ("64", Some("--pixel-error 64 is drawn at 16 px")),
        ("0.1", Some("--pixel-error 0.1 is drawn at 0.25 px")),
        ("3", None),
    ] {
        let mut args = vec!["--pixel-error", px];
        args.extend(size);
        let stderr = run_view_frames(&x.display, "2", &args, &shot);
        let warned = (stderr.lines())
            .filter(|l| l.starts_with("warning: the window's pixel error spans 0.25 to 16 px"))
            .collect::<Vec<_>>();
        match said {
            Some(s) => assert!(
                warned.len() == 1 && warned[0].ends_with(s),
                "{px}: {stderr}"
            ),
            None => assert!(warned.is_empty(), "{px}: {stderr}"),
        }
    }
    // A largest level that is not a power of two: the window takes it (tess draws it, the
    // pattern and static drivers round it down), where render refuses it for them.
    let mut args = vec!["--max-level", "48"];
    args.extend(size);
    let stderr = run_view_frames(&x.display, "2", &args, &shot);
    assert!(
        stderr.contains("warning: --max-level 48 is not a power of two: the pattern and static drivers draw adaptively up to 32, tess up to 48"),
        "{stderr}"
    );
}
