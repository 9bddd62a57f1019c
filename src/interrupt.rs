//! Ctrl-C (SIGINT) and SIGTERM: the first signal asks long loops to stop at the end of their
//! current step; they then write what they have, marked as interrupted in `run.toml`, and the
//! process exits with code 130. A second signal kills the process at once.

use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// Installs the handler (once; later calls do nothing). Returns false if it could not be set.
pub fn install() -> bool {
    ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!("\ninterrupt: stopping at the end of the current step (again to kill)");
    })
    .is_ok()
}

/// True once a stop has been requested.
pub fn requested() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// Requests a stop, as a signal would (for tests).
pub fn request() {
    STOP.store(true, Ordering::SeqCst);
}

/// Withdraws a stop request, so that later runs run (the Python package calls it once every
/// run a Ctrl-C stopped has returned; the command line never does: it exits).
pub fn clear() {
    STOP.store(false, Ordering::SeqCst);
}
