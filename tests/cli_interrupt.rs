//! An export interrupted while it writes its file (Ctrl-C, `kill`) leaves no temporary file
//! beside its output and what the output held before, and ends as the signal says
//! (src/interrupt.rs).

mod common;

use std::os::unix::process::ExitStatusExt as _;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The temporary files `write_output` makes in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".meshrefine-") && n.ends_with(".tmp"))
        .collect()
}

/// Spot exported at level 64 (1.5 M triangles, about 125 MB of OBJ, half a second or more of
/// writing) is sent SIGINT, then SIGTERM, as soon as its temporary file appears. An export that
/// finished before the signal reached it (a fast disk) is run again, up to three times; one of
/// the signals must have interrupted it.
#[test]
fn an_interrupted_export_leaves_no_temporary_file() {
    let _guard = common::gpu_lock();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-interrupt");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("spot.obj");
    let spot = common::model_path("spot_control_tri.obj");
    let mut interrupted = 0;
    for signal in [libc::SIGINT, libc::SIGTERM] {
        for _attempt in 0..3 {
            std::fs::write(&out, "# what was there before\n").unwrap();
            let mut child = Command::new(env!("CARGO_BIN_EXE_meshrefine"))
                .args(["export", spot.to_str().unwrap(), "--level", "64", "-o"])
                .arg(&out)
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            let start = Instant::now();
            let seen = loop {
                if !temporaries(&dir).is_empty() {
                    break true;
                }
                if child.try_wait().unwrap().is_some() || start.elapsed() > Duration::from_secs(300)
                {
                    break false;
                }
                std::thread::sleep(Duration::from_millis(2));
            };
            assert!(seen, "no temporary file appeared in {}", dir.display());
            let sent = Command::new("kill")
                .args([format!("-{signal}"), child.id().to_string()])
                .status()
                .unwrap();
            assert!(sent.success());
            let status = child.wait().unwrap();
            let left = temporaries(&dir);
            assert!(left.is_empty(), "left behind: {left:?} ({status})");
            if status.success() {
                // Finished before the signal came: the output is the new mesh.
                assert!(std::fs::metadata(&out).unwrap().len() > 1_000_000);
                continue;
            }
            assert_eq!(status.signal(), Some(signal), "{status}");
            assert_eq!(
                std::fs::read_to_string(&out).unwrap(),
                "# what was there before\n"
            );
            interrupted += 1;
            break;
        }
    }
    assert_eq!(interrupted, 2, "every export finished before its signal");
}
