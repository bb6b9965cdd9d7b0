//! SIGINT/SIGTERM, latched. iceoryx2's handler (installed by a node created with
//! `SignalHandlingMode::HandleTerminationRequests`) records the last signal and hands it out
//! once; the latch keeps it for every later check, so that the waits of the plant loop, the
//! send retries and the pacing sleep all see the same request.

use std::sync::atomic::{AtomicBool, Ordering};

use iceoryx2_bb_posix::signal::SignalHandler;

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Whether SIGINT or SIGTERM arrived in this process.
pub fn termination_requested() -> bool {
    if REQUESTED.load(Ordering::Relaxed) {
        return true;
    }
    if SignalHandler::termination_requested() {
        REQUESTED.store(true, Ordering::Relaxed);
        return true;
    }
    false
}
