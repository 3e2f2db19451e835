//! A request to stop rendering early, shared between whoever asks (the Ctrl-C handler, a test)
//! and the driver, which honours it at the next pass boundary.
//!
//! The handler comes from the `ctrlc` crate: a signal handler may only do async-signal-safe
//! work, so it hands the signal to an ordinary thread (through a pipe) where raising the flag,
//! printing and exiting are safe.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A shared flag asking a render to stop at its next pass boundary. Clones share the flag.
#[derive(Clone, Debug, Default)]
pub struct StopSignal(Arc<AtomicBool>);

impl StopSignal {
    /// A signal that has not been raised.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the render to stop; returns whether it had already been asked.
    pub fn raise(&self) -> bool {
        self.0.swap(true, Ordering::SeqCst)
    }

    /// Whether a stop has been asked for.
    pub fn is_raised(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

impl PartialEq for StopSignal {
    /// Two signals are equal when they share one flag.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Eq for StopSignal {}

/// Exit status of a process ended by Ctrl-C (128 + SIGINT), with or without writing its image.
pub const INTERRUPTED_EXIT_STATUS: u8 = 130;

/// Makes Ctrl-C (SIGINT), SIGTERM and SIGHUP raise `stop`, so the render ends at its next pass
/// boundary and writes what it has; a second signal exits the process at once with status
/// [`INTERRUPTED_EXIT_STATUS`], writing nothing. Can be called once per process.
pub fn raise_on_ctrl_c(stop: StopSignal) -> Result<(), ctrlc::Error> {
    ctrlc::set_handler(move || {
        if stop.raise() {
            std::process::exit(i32::from(INTERRUPTED_EXIT_STATUS));
        }
        eprintln!(
            "\nstrata: stopping after this pass and writing the image \
             (interrupt again to quit without writing)"
        );
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_the_flag_and_raise_reports_repeats() {
        let signal = StopSignal::new();
        let clone = signal.clone();
        assert!(!clone.is_raised());
        assert!(!signal.raise(), "first request");
        assert!(clone.is_raised());
        assert!(clone.raise(), "second request");
        assert_eq!(signal, clone);
        assert_ne!(signal, StopSignal::new());
    }
}
