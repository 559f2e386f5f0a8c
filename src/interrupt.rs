//! An interrupted command leaves no unfinished output behind: while a regular output file is
//! written beside its path ([`crate::paths::write_output`], [`crate::paths::write_outputs`]),
//! the temporary file is registered here, and `SIGINT`, `SIGTERM` or `SIGHUP` (Ctrl-C, `kill`, a closed terminal) removes it
//! before the process ends as the signal says (its default action, re-raised: the shell still
//! sees the signal). What the path held before stays, unless the interruption comes while a
//! finished file is copied into it in place (another user's file, one with other hard links:
//! [`crate::paths::write_output`]).
//!
//! Handlers are installed only for signals whose action is the default, so a signal the
//! process ignores (`nohup`, a background job) stays ignored. A temporary file is registered
//! before it is made (a name not made removes nothing), in one of [`SLOTS`] slots (several when one command writes several
//! outputs as a set, [`crate::paths::write_outputs`]); with every slot taken, a registration
//! replaces the first slot's.
//!
//! The handler does only what is safe in a signal handler: it swaps each slot's atomic pointer,
//! calls `unlink` on the C strings they pointed to, and restores and re-raises the signal.
//! Registered names are never freed (a few bytes per output written), so the handler never reads freed
//! memory whatever the thread it runs on.

use std::ffi::{c_char, CStr, CString};
use std::path::Path;
use std::sync::atomic::{AtomicPtr, Ordering};
use std::sync::Once;

/// How many temporary files may be pending at once.
pub const SLOTS: usize = 4;

/// The temporary files being written, as C strings; null where none is.
static PENDING: [AtomicPtr<c_char>; SLOTS] =
    [const { AtomicPtr::new(std::ptr::null_mut()) }; SLOTS];

const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

/// Removes the pending temporary files, then ends the process as `signal` would have.
extern "C" fn on_signal(signal: libc::c_int) {
    for slot in &PENDING {
        let pending = slot.swap(std::ptr::null_mut(), Ordering::SeqCst);
        if !pending.is_null() {
            // SAFETY: `unlink` is async-signal-safe; `pending` is a NUL-terminated string
            // that is never freed (`register`).
            unsafe {
                libc::unlink(pending);
            }
        }
    }
    // SAFETY: `signal` and `raise` are async-signal-safe.
    unsafe {
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
    /// Forgets the registration if it is still pending (the file was renamed into place or
    /// removed).
    pub fn clear(&self) {
        if let Some(name) = self.0 {
            release(&PENDING, name.as_ptr().cast_mut());
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
            claim(&PENDING, name.as_ptr().cast_mut());
            Registered(Some(name))
        }
        // A path with a NUL byte cannot have been made.
        Err(_) => Registered(None),
    }
}

/// Runs `f` with SIGINT, SIGTERM and SIGHUP held back (blocked on this thread, delivered when
/// it returns): where this is the thread that would take them (no other thread runs), what `f`
/// puts in place is never cut in the middle.
pub fn deferred<T>(f: impl FnOnce() -> T) -> T {
    /// The mask before; restored when dropped, a panic in `f` included.
    struct Restore(libc::sigset_t);
    impl Drop for Restore {
        fn drop(&mut self) {
            // SAFETY: `pthread_sigmask` reads only the set passed.
            unsafe {
                libc::pthread_sigmask(libc::SIG_SETMASK, &self.0, std::ptr::null_mut());
            }
        }
    }
    // SAFETY: `sigemptyset`, `sigaddset` and `pthread_sigmask` write only the sets passed
    // (zeroed sets are valid to start from).
    let _restore = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for s in SIGNALS {
            libc::sigaddset(&mut set, s);
        }
        let mut old: libc::sigset_t = std::mem::zeroed();
        libc::pthread_sigmask(libc::SIG_BLOCK, &set, &mut old);
        Restore(old)
    };
    f()
}

/// Puts `name` in the first free slot of `slots`, or with none free in the first.
fn claim(slots: &[AtomicPtr<c_char>], name: *mut c_char) {
    let null = std::ptr::null_mut();
    let free = (slots.iter())
        .any(|s| (s.compare_exchange(null, name, Ordering::SeqCst, Ordering::SeqCst)).is_ok());
    if !free {
        slots[0].store(name, Ordering::SeqCst);
    }
}

/// Empties the slots of `slots` that hold `name`.
fn release(slots: &[AtomicPtr<c_char>], name: *mut c_char) {
    for s in slots {
        let _ = s.compare_exchange(
            name,
            std::ptr::null_mut(),
            Ordering::SeqCst,
            Ordering::SeqCst,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;

    /// A signal raised while `deferred` runs is held back (pending, its handler not yet run)
    /// and delivered once it returns, also when its body panics; the mask is then as before.
    #[test]
    fn deferred_holds_signals_back_until_it_returns() {
        static RAN: AtomicBool = AtomicBool::new(false);
        extern "C" fn on_hangup(_: libc::c_int) {
            RAN.store(true, Ordering::SeqCst);
        }
        let blocked = |signal| {
            // SAFETY: `pthread_sigmask` with no new set and `sigismember` only read and write
            // the sets passed (a zeroed set is valid to start from).
            unsafe {
                let mut now: libc::sigset_t = std::mem::zeroed();
                libc::pthread_sigmask(libc::SIG_BLOCK, std::ptr::null(), &mut now);
                libc::sigismember(&now, signal) == 1
            }
        };
        let raise = || {
            // SAFETY: sends SIGHUP to this thread, whose handler (below) only stores a flag.
            unsafe { libc::pthread_kill(libc::pthread_self(), libc::SIGHUP) };
        };
        // The module's handlers first (other tests install them through `register`), so that
        // none replaces this test's in the middle; what was there comes back at the end.
        install();
        // SAFETY: `sigaction` reads and writes only the structures passed (zeroed ones are
        // valid: no flags, an empty mask); the handler is async-signal-safe (one atomic store).
        // No other test sends SIGHUP.
        let before = unsafe {
            let mut new: libc::sigaction = std::mem::zeroed();
            new.sa_sigaction = on_hangup as extern "C" fn(libc::c_int) as libc::sighandler_t;
            libc::sigemptyset(&mut new.sa_mask);
            let mut before: libc::sigaction = std::mem::zeroed();
            assert_eq!(libc::sigaction(libc::SIGHUP, &new, &mut before), 0);
            before
        };
        let mask = || {
            // SAFETY: as in `blocked`.
            unsafe {
                let mut now: libc::sigset_t = std::mem::zeroed();
                libc::pthread_sigmask(libc::SIG_BLOCK, std::ptr::null(), &mut now);
                SIGNALS.map(|s| libc::sigismember(&now, s))
            }
        };
        let mask_before = mask();
        assert!(!blocked(libc::SIGHUP));
        for panics in [false, true] {
            RAN.store(false, Ordering::SeqCst);
            let result = std::panic::catch_unwind(|| {
                deferred(|| {
                    assert!(SIGNALS.iter().all(|&s| blocked(s)));
                    raise();
                    std::thread::sleep(std::time::Duration::from_millis(20));
                    assert!(!RAN.load(Ordering::SeqCst), "delivered while held back");
                    if panics {
                        // The body's panic, without a panic message.
                        std::panic::resume_unwind(Box::new("the body's panic"));
                    }
                })
            });
            assert_eq!(result.is_err(), panics);
            assert!(RAN.load(Ordering::SeqCst), "not delivered on return");
            assert_eq!(mask(), mask_before);
        }
        // SAFETY: as above; the action saved is put back.
        unsafe { libc::sigaction(libc::SIGHUP, &before, std::ptr::null_mut()) };
    }

    /// Temporaries written as a set are all pending at once, each forgotten alone; past the
    /// slots, the first slot's is replaced.
    #[test]
    fn several_temporaries_are_pending_at_once() {
        let slots: [AtomicPtr<c_char>; 3] = Default::default();
        let names = [c"a.tmp", c"b.tmp", c"c.tmp", c"d.tmp"].map(|n| n.as_ptr().cast_mut());
        let held = |slots: &[AtomicPtr<c_char>]| -> Vec<*mut c_char> {
            slots.iter().map(|s| s.load(Ordering::SeqCst)).collect()
        };
        for &n in &names[..3] {
            claim(&slots, n);
        }
        assert_eq!(held(&slots), names[..3]);
        release(&slots, names[1]);
        assert_eq!(held(&slots), [names[0], std::ptr::null_mut(), names[2]]);
        claim(&slots, names[3]);
        assert_eq!(held(&slots), [names[0], names[3], names[2]]);
        claim(&slots, names[1]);
        assert_eq!(held(&slots), [names[1], names[3], names[2]]);
        for &n in &names {
            release(&slots, n);
        }
        assert!(held(&slots).iter().all(|p| p.is_null()));
    }
}
