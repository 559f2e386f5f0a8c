//! An interrupted command leaves no unfinished output behind: while a regular output file is
//! written beside its path ([`crate::paths::write_output`]), the temporary file is registered
//! here, and `SIGINT`, `SIGTERM` or `SIGHUP` (Ctrl-C, `kill`, a closed terminal) removes it
//! before the process ends as the signal says (its default action, re-raised: the shell still
//! sees the signal). What the path held before stays, as after any other failure.
//!
//! The handler does only what is safe in a signal handler: it reads one atomic pointer, calls
//! `unlink` on the C string it points to, and restores and re-raises the signal. Registered
//! names are never freed (a few bytes per output written), so the handler never reads freed
//! memory whatever the thread it runs on.

use std::ffi::{c_char, CString};
use std::path::Path;
use std::sync::atomic::{AtomicPtr, Ordering};
use std::sync::Once;

/// The temporary file being written, as a C string; null when none is.
static PENDING: AtomicPtr<c_char> = AtomicPtr::new(std::ptr::null_mut());

const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

/// Removes the pending temporary file, then ends the process as `signal` would have.
extern "C" fn on_signal(signal: libc::c_int) {
    let pending = PENDING.swap(std::ptr::null_mut(), Ordering::SeqCst);
    // SAFETY: `unlink`, `signal` and `raise` are async-signal-safe; `pending` is null or a
    // NUL-terminated string that is never freed (`register`).
    unsafe {
        if !pending.is_null() {
            libc::unlink(pending);
        }
        libc::signal(signal, libc::SIG_DFL);
        libc::raise(signal);
    }
}

/// Registers `tmp` as the temporary file to remove if the process is interrupted, installing
/// the handlers on first use (not over a signal the process ignores, as `nohup` asks).
pub fn register(tmp: &Path) {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        for s in SIGNALS {
            // SAFETY: `on_signal` is async-signal-safe (module notes); installing a handler
            // has no other effect on the program.
            unsafe {
                let previous = libc::signal(s, on_signal as *const () as libc::sighandler_t);
                if previous == libc::SIG_IGN {
                    libc::signal(s, libc::SIG_IGN);
                }
            }
        }
    });
    use std::os::unix::ffi::OsStrExt as _;
    if let Ok(name) = CString::new(tmp.as_os_str().as_bytes()) {
        PENDING.store(name.into_raw(), Ordering::SeqCst);
    }
}

/// Forgets the registered temporary file (renamed into place or removed).
pub fn clear() {
    PENDING.store(std::ptr::null_mut(), Ordering::SeqCst);
}
