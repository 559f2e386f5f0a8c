//! An export interrupted while it writes its file (Ctrl-C, `kill`) leaves no temporary file
//! beside its output and what the output held before, and ends as the signal says; a signal
//! the process ignores (`nohup`) stays ignored (src/interrupt.rs).
// `pre_exec` sets the child's signal actions as a shell would (see `spawn`).
#![allow(unsafe_code)]

mod common;

use std::os::unix::process::{CommandExt as _, ExitStatusExt as _};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const OLD: &str = "# what was there before\n";

/// The temporary files `write_output` makes in `dir` that hold data (the empty ones are the
/// writability probe made at startup, before the export writes).
fn written_temporaries(dir: &Path) -> Vec<String> {
    (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap())
        .filter(|e| e.metadata().is_ok_and(|m| m.len() > 0))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".meshrefine-") && n.ends_with(".tmp"))
        .collect()
}

/// Every temporary file in `dir`, empty or not.
fn temporaries(dir: &Path) -> Vec<String> {
    (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".meshrefine-") && n.ends_with(".tmp"))
        .collect()
}

/// Spot exported at level 64 (1.5 M triangles, about 125 MB of OBJ) into `out`, validated, with
/// the three signals at their default action, or `ignored` ignored, whatever the test runner
/// inherited.
fn spawn(out: &Path, ignored: Option<libc::c_int>) -> Child {
    let spot = common::model_path("spot_control_tri.obj");
    let mut command = Command::new(env!("CARGO_BIN_EXE_meshrefine"));
    command
        .args(["export", spot.to_str().unwrap(), "--level", "64", "-o"])
        .arg(out)
        .env("MESHREFINE_VALIDATE", "1")
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    // SAFETY: `signal` is async-signal-safe, as a `pre_exec` closure must be.
    unsafe {
        command.pre_exec(move || {
            for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
                let action = if Some(s) == ignored {
                    libc::SIG_IGN
                } else {
                    libc::SIG_DFL
                };
                libc::signal(s, action);
            }
            Ok(())
        });
    }
    command.spawn().unwrap()
}

/// Waits until the export writes its temporary file in `dir` (true), or ends first (false).
fn wait_for_writing(child: &mut Child, dir: &Path) -> bool {
    let start = Instant::now();
    loop {
        if !written_temporaries(dir).is_empty() {
            return true;
        }
        if child.try_wait().unwrap().is_some() || start.elapsed() > Duration::from_secs(300) {
            return false;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Waits for `child`'s end; its standard error must hold no validation message.
fn finish(child: Child) -> std::process::ExitStatus {
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("validation"), "{stderr}");
    out.status
}

fn send(child: &Child, signal: libc::c_int) {
    let sent = Command::new("kill")
        .args([format!("-{signal}"), child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
}

/// SIGINT, SIGTERM, then SIGHUP reach the export as soon as its temporary file holds data. An export
/// that finished writing before the signal reached it (renamed its file: a fast disk) is run
/// again, up to three times; each signal must once have interrupted it. Then SIGHUP, ignored
/// as under `nohup`, lets the export finish.
#[test]
fn an_interrupted_export_leaves_no_temporary_file() {
    let _guard = common::gpu_lock();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-interrupt");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("spot.obj");
    for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        let mut interrupted = false;
        for _attempt in 0..3 {
            std::fs::write(&out, OLD).unwrap();
            let mut child = spawn(&out, None);
            assert!(
                wait_for_writing(&mut child, &dir),
                "no temporary file was written"
            );
            send(&child, signal);
            let status = finish(child);
            let left = temporaries(&dir);
            assert!(left.is_empty(), "left behind: {left:?} ({status})");
            if std::fs::read_to_string(&out).is_ok_and(|t| t == OLD) {
                assert_eq!(status.signal(), Some(signal), "{status}");
                interrupted = true;
                break;
            }
            // Finished (renamed) before the signal came: the output is the new mesh.
            assert!(std::fs::metadata(&out).unwrap().len() > 1_000_000);
        }
        assert!(interrupted, "every export finished before signal {signal}");
    }
    std::fs::write(&out, OLD).unwrap();
    let mut child = spawn(&out, Some(libc::SIGHUP));
    assert!(
        wait_for_writing(&mut child, &dir),
        "no temporary file was written"
    );
    send(&child, libc::SIGHUP);
    let status = finish(child);
    assert!(status.success(), "{status}");
    assert!(std::fs::metadata(&out).unwrap().len() > 1_000_000);
    assert!(temporaries(&dir).is_empty());
}
