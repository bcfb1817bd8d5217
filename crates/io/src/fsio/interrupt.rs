//! Temporary files of [`super::AtomicFile`] removed when the command line is
//! interrupted (Ctrl-C, `kill`): without this, `run -o big.csv` stopped
//! half-way left a hidden `.big.csv.tmp-PID-N` of up to the whole output's
//! size beside the target.
//!
//! The open temporaries' paths are kept in a fixed table of atomic pointers
//! that a SIGINT/SIGTERM handler reads without locking or allocating (only
//! `unlink`, `signal` and `raise`, which are async-signal-safe), then the
//! signal is raised again with its default action (the exit status stays
//! "killed by SIGINT"). A path is leaked when unregistered (a few bytes per
//! output file): the handler may be reading it at that moment.

#[cfg(unix)]
mod imp {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    use std::path::Path;
    use std::sync::atomic::{AtomicPtr, Ordering};

    const SLOTS: usize = 64;
    static TEMPS: [AtomicPtr<libc::c_char>; SLOTS] =
        [const { AtomicPtr::new(std::ptr::null_mut()) }; SLOTS];

    pub fn register(path: &Path) -> Option<usize> {
        let c = CString::new(path.as_os_str().as_bytes()).ok()?;
        let p = c.into_raw();
        for (i, slot) in TEMPS.iter().enumerate() {
            if slot
                .compare_exchange(std::ptr::null_mut(), p, Ordering::AcqRel, Ordering::Acquire)
                .is_ok()
            {
                return Some(i);
            }
        }
        // table full: not removed on a signal, as before
        // SAFETY: `p` came from `CString::into_raw` just above and was not shared.
        drop(unsafe { CString::from_raw(p) });
        None
    }

    pub fn unregister(slot: usize) {
        if let Some(s) = TEMPS.get(slot) {
            // leaked, not freed: a signal handler may be reading it
            s.store(std::ptr::null_mut(), Ordering::Release);
        }
    }

    extern "C" fn on_signal(sig: libc::c_int) {
        for slot in &TEMPS {
            let p = slot.load(Ordering::Acquire);
            if !p.is_null() {
                // SAFETY: `p` is a NUL-terminated path that is never freed.
                unsafe {
                    libc::unlink(p);
                }
            }
        }
        // SAFETY: restoring the default action and raising the signal again
        // are async-signal-safe; the process then ends as it would have.
        unsafe {
            libc::signal(sig, libc::SIG_DFL);
            libc::raise(sig);
        }
    }

    pub fn install() {
        let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
        // SIGPIPE too: output piped into `head` ends the command quietly,
        // as other Unix tools do, not with a panic on the closed pipe
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGPIPE] {
            // SAFETY: `on_signal` only calls async-signal-safe functions and
            // reads atomics.
            unsafe {
                libc::signal(sig, handler);
            }
        }
    }
}

#[cfg(not(unix))]
mod imp {
    use std::path::Path;
    pub fn register(_path: &Path) -> Option<usize> {
        None
    }
    pub fn unregister(_slot: usize) {}
    pub fn install() {}
}

/// Removes the open temporaries of atomic writes on SIGINT, SIGTERM and
/// SIGPIPE (stdout piped into a command that stopped reading),
/// then ends the process by the signal. For the command line (the window
/// has its own handling); a no-op off Unix.
pub fn remove_temporaries_on_signal() {
    imp::install();
}

/// Records the temporary `path` for removal on a signal; the slot for
/// [`forget`].
pub(crate) fn register(path: &std::path::Path) -> Option<usize> {
    imp::register(path)
}

/// The temporary of `slot` was renamed or removed.
pub(crate) fn forget(slot: Option<usize>) {
    if let Some(s) = slot {
        imp::unregister(s);
    }
}
