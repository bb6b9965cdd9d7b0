//! Ctrl-C (SIGINT) as a request to stop: long runs end at the next check, their sinks flush and
//! close their files (a CSV ends on a whole row, an `.rrd` gets its footer), and `rins` exits 130.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

extern "C" fn on_sigint(_: libc::c_int) {
    // Only an atomic store: async-signal-safe.
    REQUESTED.store(true, Ordering::Relaxed);
}

/// Installs the SIGINT handler. A second Ctrl-C still stops at the next check (not at once):
/// runs check every few milliseconds of wall time.
#[allow(unsafe_code)]
pub fn install() {
    #[cfg(unix)]
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe; the handler has
    // the signature signal(2) expects.
    unsafe {
        libc::signal(libc::SIGINT, on_sigint as *const () as libc::sighandler_t);
    }
}

/// True once SIGINT arrived.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
