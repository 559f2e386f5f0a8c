//! The command-line tests' helpers (tests/cli*.rs): the binary with the validation layer on and
//! no display, its expected successes and one-sentence failures, temporary paths, and what the
//! outputs say.
#![allow(dead_code, unused_imports)]

pub use super::model_path;
pub use std::path::{Path, PathBuf};
pub use std::process::{Command, Output, Stdio};
pub use std::time::{Duration, Instant};

/// The binary, with the validation layer on for every GPU run (a validation message then fails
/// the command, see `check_messages` in main.rs).
pub fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_meshrefine"));
    c.env("MESHREFINE_VALIDATE", "1");
    c
}

pub fn meshrefine(args: &[&str]) -> Output {
    let _guard = super::gpu_lock();
    bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("run meshrefine")
}

/// An export's text without its `# command:` line (which names its own output path).
pub fn without_command(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("# command: "))
        .collect();
    assert!(
        kept.len() < text.lines().count(),
        "no command line in {}",
        path.display()
    );
    kept.join("\n")
}

pub fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

pub fn write(name: &str, text: &[u8]) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs and expects failure with exactly one `error: ...` line containing every `needles` entry.
pub fn expect_error(args: &[&str], needles: &[&str]) {
    check_error(&meshrefine(args), args, needles);
}

/// [`expect_error`]'s checks on the output of a run with `args`.
pub fn check_error(out: &Output, args: &[&str], needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "{args:?} succeeded; stderr: {stderr}"
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{args:?}: exit status {:?}; stderr: {stderr}",
        out.status
    );
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert!(
        !stderr.contains("validation"),
        "{args:?}: validation message: {stderr}"
    );
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(
        errors.len(),
        1,
        "{args:?}: expected one error line, got: {stderr}"
    );
    for n in needles {
        assert!(
            errors[0].contains(n),
            "{args:?}: error line lacks {n:?}: {}",
            errors[0]
        );
    }
}

pub fn ok(args: &[&str]) -> String {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Every exported face winds counter-clockwise around its vertex normals (outward on a sphere).
pub fn assert_faces_agree_with_normals(mesh: &meshrefine::mesh::Mesh) {
    for t in &mesh.triangles {
        let [a, b, c] = t.p.map(|i| mesh.positions[i as usize]);
        let n: glam::Vec3 = t.n.iter().map(|&i| mesh.normals[i as usize]).sum();
        assert!(
            (b - a).cross(c - a).dot(n) > 0.0,
            "face {t:?} winds against its normals"
        );
    }
}

pub fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The header and rows of `bench`'s summary table: the line above the rule of dashes, split
/// at runs of two or more spaces, and the lines below it up to the first blank one.
pub fn summary_table(s: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let lines: Vec<&str> = s.lines().collect();
    let rule = lines
        .iter()
        .position(|l| l.starts_with("---") && l.chars().all(|c| c == '-' || c == ' '))
        .unwrap_or_else(|| panic!("no summary table in\n{s}"));
    let header = lines[rule - 1]
        .split("  ")
        .map(str::trim)
        .filter(|h| !h.is_empty())
        .map(str::to_owned)
        .collect();
    let rows = lines[rule + 1..]
        .iter()
        .take_while(|l| !l.is_empty())
        .map(|l| l.split_whitespace().map(str::to_owned).collect())
        .collect();
    (header, rows)
}

/// Runs meshrefine with the given stdout and stderr.
pub fn meshrefine_with(args: &[&str], stdout: Stdio, stderr: Stdio) -> std::process::ExitStatus {
    let _guard = super::gpu_lock();
    bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stdout(stdout)
        .stderr(stderr)
        .status()
        .expect("run meshrefine")
}

/// Runs with stdout on a pipe whose reading end is closed before meshrefine writes anything.
pub fn with_closed_stdout(args: &[&str]) -> Output {
    let _guard = super::gpu_lock();
    let mut child = bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("RUST_BACKTRACE", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run meshrefine");
    drop(child.stdout.take());
    child.wait_with_output().expect("wait for meshrefine")
}

/// Waits at most `limit` for a child, killing it if it is still running then.
pub fn wait_at_most(mut child: std::process::Child, limit: Duration) -> Option<Output> {
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().expect("poll meshrefine").is_some() {
            return Some(child.wait_with_output().expect("collect meshrefine"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().ok();
    child.wait().ok();
    None
}

pub fn stdout_commands() -> Vec<Vec<String>> {
    let cube = model_path("cube_tri.obj").display().to_string();
    let tet = model_path("tetrahedron.obj").display().to_string();
    let png = tmp("stdout.png").display().to_string();
    let obj = tmp("stdout.obj").display().to_string();
    let small = ["--width", "32", "--height", "32"];
    let mut render = vec!["render", &cube, "-o", &png, "--level", "2"];
    render.extend(small);
    let mut bench = vec!["bench", &tet, "--levels", "2", "--frames", "1"];
    bench.extend(small);
    [
        vec!["info", &cube, "--level", "4"],
        render,
        vec!["export", &cube, "-o", &obj, "--level", "2"],
        bench,
        vec!["--help"],
    ]
    .iter()
    .map(|a| a.iter().map(|s| s.to_string()).collect())
    .collect()
}

/// A regular tetrahedron's vertices scaled by `scale` and moved by `offset`, as OBJ text.
pub fn tetrahedron(scale: f64, offset: f64) -> String {
    let mut s = String::new();
    for v in [
        [1.0, 1.0, 1.0],
        [-1.0, -1.0, 1.0],
        [-1.0, 1.0, -1.0],
        [1.0, -1.0, -1.0],
    ] {
        let c = v.map(|c: f64| (c * scale + offset) as f32);
        s += &format!("v {:e} {:e} {:e}\n", c[0], c[1], c[2]);
    }
    s + "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n"
}

/// Pixels of a PNG written by meshrefine that are not the clear colour.
pub fn covered(png_path: &Path) -> usize {
    let decoder = png::Decoder::new(std::fs::File::open(png_path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgba).unwrap();
    rgba.truncate(info.buffer_size());
    meshrefine::render::covered_pixels(&meshrefine::gpu::Readback {
        width: info.width,
        height: info.height,
        rgba,
    })
}

/// Runs and expects success (the error output in the message otherwise).
pub fn expect_success(args: &[&str]) {
    let out = meshrefine(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Writes an 8-bit grayscale PNG of `w` x `h` pixels into the tests' directory.
pub fn gray_png(name: &str, w: u32, h: u32, pixels: &[u8]) -> PathBuf {
    let path = tmp(name);
    let mut e = png::Encoder::new(std::fs::File::create(&path).unwrap(), w, h);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::Eight);
    e.write_header().unwrap().write_image_data(pixels).unwrap();
    path
}

/// Runs `export` with `args` (after `export`), expects success, and reloads what it wrote.
pub fn export_and_reload(obj: &Path, args: &[&str]) -> meshrefine::mesh::Mesh {
    let mut all = vec!["export", "-o", p(obj)];
    all.extend_from_slice(args);
    expect_success(&all);
    meshrefine::mesh::Mesh::load_obj(obj).unwrap().0
}

/// Runs and expects success; returns standard error's `warning:` lines.
pub fn warnings_of(args: &[&str]) -> Vec<String> {
    let out = meshrefine(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    assert!(!stderr.contains("validation"), "{args:?}: {stderr}");
    stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .map(str::to_string)
        .collect()
}

/// `(adaptive triangles, uniform triangles, uniform level, culled, elements in the histogram)`
/// from `info --pixel-error`'s report.
pub fn adaptive_report(stdout: &str) -> (u64, u64, u32, u64, u64) {
    let line = |start: &str| {
        stdout
            .lines()
            .find(|l| l.trim_start().starts_with(start))
            .unwrap_or_else(|| panic!("no '{start}' line in:\n{stdout}"))
            .to_string()
    };
    let words = |l: String| -> Vec<String> { l.split_whitespace().map(String::from).collect() };
    let t = words(line("refined triangles:"));
    let culled = words(line("culled")).last().unwrap().parse().unwrap();
    let histogram: u64 = words(line("levels ("))[3..]
        .iter()
        .map(|pair| pair.split(':').nth(1).unwrap().parse::<u64>().unwrap())
        .sum();
    (
        t[2].parse().unwrap(),
        t[5].parse().unwrap(),
        t[9].parse().unwrap(),
        culled,
        histogram,
    )
}

/// The two header lines of an adaptive export: the camera's numbers and `L:n` pairs.
pub fn adaptive_header(text: &str) -> (Vec<f32>, Vec<(u32, u64)>) {
    let camera = text
        .lines()
        .find(|l| l.starts_with("# camera "))
        .unwrap_or_else(|| panic!("no camera line"));
    let words: Vec<&str> = camera.split_whitespace().collect();
    let names = [
        "#",
        "camera",
        "eye",
        "",
        "",
        "",
        "target",
        "",
        "",
        "",
        "up",
        "",
        "",
        "",
        "fov-y",
        "",
        "size",
        "",
        "",
        "pixel-error",
        "",
    ];
    assert_eq!(words.len(), names.len(), "{camera}");
    let mut numbers = Vec::new();
    for (w, n) in words.iter().zip(names) {
        if n.is_empty() {
            numbers.push(
                w.parse::<f32>()
                    .unwrap_or_else(|_| panic!("{w} in {camera}")),
            );
        } else {
            assert_eq!(*w, n, "{camera}");
        }
    }
    let levels = text
        .lines()
        .find(|l| l.starts_with("# levels "))
        .unwrap_or_else(|| panic!("no levels line"));
    let pairs = levels["# levels ".len()..]
        .split_whitespace()
        .map(|pair| {
            let (l, n) = pair.split_once(':').unwrap();
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    (numbers, pairs)
}

/// `bench` of Spot's `pn` at 4 px, one frame of 160x90, with `extra` options.
pub fn small_adaptive_bench<'a>(spot: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["bench", spot, "--surfaces", "pn", "--pixel-error", "4"];
    args.extend(["--frames", "1", "--width", "160", "--height", "90"]);
    args.extend(extra);
    args
}

/// Reads the RGBA pixels of a PNG meshrefine wrote.
pub fn rgba_of(png_path: &Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::fs::File::open(png_path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut rgba = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgba).unwrap();
    rgba.truncate(info.buffer_size());
    rgba
}

/// `meshrefine` with `args` and the environment variables `env` (set last: a test may name a
/// display, or turn validation off with `MESHREFINE_VALIDATE=0`).
pub fn meshrefine_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let _guard = super::gpu_lock();
    bin()
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .envs(env.iter().copied())
        .output()
        .expect("run meshrefine")
}

/// The path of the test mesh `name` as an argument.
pub fn model_arg(name: &str) -> String {
    model_path(name).to_str().unwrap().to_string()
}

/// Runs meshrefine with `args` and `env`, expecting success; returns its standard error.
pub fn succeeds(args: &[&str], env: &[(&str, &str)]) -> String {
    let out = meshrefine_env(args, env);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{args:?}: {stderr}");
    stderr
}

/// The closed, consistently oriented triangles of an exported OBJ's text (each undirected edge
/// in exactly two faces, each directed edge in one), with its `# levels` histogram
/// (level, elements) and its vertex and face counts.
pub fn closed_adaptive_export(text: &str) -> (Vec<(u64, u64)>, usize, usize) {
    let levels: Vec<(u64, u64)> = (text.lines())
        .find_map(|l| l.strip_prefix("# levels "))
        .expect("a # levels line")
        .split_whitespace()
        .map(|b| {
            let (l, n) = b.split_once(':').expect("level:count");
            (l.parse().unwrap(), n.parse().unwrap())
        })
        .collect();
    let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
    let faces: Vec<[usize; 3]> = (text.lines())
        .filter_map(|l| l.strip_prefix("f "))
        .map(|f| {
            let c: Vec<usize> = f
                .split_whitespace()
                .map(|c| c.split('/').next().unwrap().parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let mut undirected = std::collections::HashMap::new();
    let mut directed = std::collections::HashSet::new();
    for f in &faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            assert!(
                directed.insert((a, b)),
                "edge {a}-{b} twice in one direction"
            );
        }
    }
    let open = undirected.values().filter(|&&n| n != 2).count();
    assert_eq!(open, 0, "{open} edges not shared by exactly two faces");
    (levels, vertices, faces.len())
}

/// What `info` says on standard error of a file `name` holding `text`, which loads.
pub fn info_stderr(name: &str, text: &[u8]) -> String {
    let path = write(name, text);
    let out = meshrefine(&["info", p(&path)]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{name}: {stderr}");
    stderr
}
