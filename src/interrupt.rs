//! An interrupted command leaves no unfinished output behind: while a regular output file is
//! written beside its path ([`crate::paths::write_output`]), the temporary file is registered
//! here, and `SIGINT`, `SIGTERM` or `SIGHUP` (Ctrl-C, `kill`, a closed terminal) removes it
//! before the process ends as the signal says (its default action, re-raised: the shell still
//! sees the signal). What the path held before stays, unless the interruption comes while a
//! finished file is copied into it in place (another user's file, one with other hard links:
//! [`crate::paths::write_output`]).
//!
//! Handlers are installed only for signals whose action is the default, so a signal the
//! process ignores (`nohup`, a background job) stays ignored. One temporary file is registered
//! at a time (the commands write their outputs one after the other), as soon as it is made; a
//! second registration replaces the first.
//!
//! The handler does only what is safe in a signal handler: it swaps one atomic pointer, calls
//! `unlink` on the C string it pointed to, and restores and re-raises the signal. Registered
//! names are never freed (a few bytes per output written), so the handler never reads freed
//! memory whatever the thread it runs on.

use std::ffi::{c_char, CStr, CString};
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

/// Installs the handler for each of the signals whose action is the default (module notes),
/// once.
pub fn install() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        for s in SIGNALS {
            // SAFETY: `sigaction` reads and writes only the structures passed; `on_signal` is
            // async-signal-safe (module notes). Zeroed `sigaction` structures are valid (no
            // flags, an empty mask).
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                if libc::sigaction(s, std::ptr::null(), &mut old) != 0
                    || old.sa_sigaction != libc::SIG_DFL
                {
                    continue;
                }
                let mut new: libc::sigaction = std::mem::zeroed();
                new.sa_sigaction = on_signal as *const () as libc::sighandler_t;
                libc::sigemptyset(&mut new.sa_mask);
                libc::sigaction(s, &new, std::ptr::null_mut());
            }
        }
    });
}

/// A registered temporary file ([`register`]); [`Registered::clear`] forgets it.
#[derive(Debug)]
pub struct Registered(Option<&'static CStr>);

impl Registered {
    /// Forgets the registration if it is still the pending one (the file was renamed into
    /// place or removed).
    pub fn clear(&self) {
        if let Some(name) = self.0 {
            let _ = PENDING.compare_exchange(
                name.as_ptr().cast_mut(),
                std::ptr::null_mut(),
                Ordering::SeqCst,
                Ordering::SeqCst,
            );
        }
    }
}

/// Registers `tmp`, just made, as the temporary file to remove if the process is interrupted
/// (the handlers installed first, [`install`]), until [`Registered::clear`].
#[must_use]
pub fn register(tmp: &Path) -> Registered {
    install();
    use std::os::unix::ffi::OsStrExt as _;
    match CString::new(tmp.as_os_str().as_bytes()) {
        Ok(name) => {
            // Never freed (module notes).
            let name: &'static CStr = Box::leak(name.into_boxed_c_str());
            PENDING.store(name.as_ptr().cast_mut(), Ordering::SeqCst);
            Registered(Some(name))
        }
        // A path with a NUL byte cannot have been made.
        Err(_) => Registered(None),
    }
}
