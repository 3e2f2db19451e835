//! Running a render with the GIL released while staying interruptible by Ctrl-C.
//!
//! Python runs its signal handlers (Ctrl-C's raises `KeyboardInterrupt`) only in the main thread
//! and only when that thread runs Python code or calls `PyErr_CheckSignals`. So the render runs
//! on a thread of its own (which hands the work to Rayon's pool), while the calling thread waits
//! for it with the GIL released, attaching every [`POLL`] to check for signals. A signal's
//! exception raises the render's [`StopSignal`]: the driver stops at its next pass boundary
//! (the package plans passes of at most [`PASS_SECONDS`], a quarter of the command line's
//! [`render::budget::MAX_PASS_SECONDS`]), the thread ends, and the exception is raised in
//! Python: once the first pass (1 sample per pixel) is done, within about a quarter second of
//! the signal. No render work outlives the call.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use render::stop::StopSignal;

/// How often the waiting thread checks for signals.
pub const POLL: Duration = Duration::from_millis(50);

/// Longest a pass of the package's renders is planned to take, in seconds: a stop waits for the
/// pass under way, so this (with [`POLL`]) bounds how long Ctrl-C takes. Passes never change a
/// render's image, only how often the driver looks up from its work.
pub const PASS_SECONDS: f64 = 0.25;

/// What [`run`] did: the work's result, and the exception a signal raised while it ran (the
/// work was then asked to stop through the [`StopSignal`]).
pub struct Outcome<T> {
    /// What `work` returned.
    pub result: T,
    /// The exception raised by a signal handler (`KeyboardInterrupt` for Ctrl-C), if any.
    pub interrupt: Option<PyErr>,
}

/// Runs `work` on a thread of its own with the GIL released; raises `stop` when a signal
/// handler raises an exception meanwhile. A panic in `work` becomes a `RuntimeError`.
pub fn run<T, F>(py: Python<'_>, stop: &StopSignal, work: F) -> PyResult<Outcome<T>>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    std::thread::scope(|scope| {
        let (done, finished) = mpsc::channel::<()>();
        let handle = scope.spawn(move || {
            let result = work();
            // The receiver outlives the thread's work; a failed send means nothing is waiting.
            let _ = done.send(());
            result
        });
        let mut finished = finished;
        let mut interrupt = None;
        loop {
            let (back, over) = py.detach(move || {
                let over = !matches!(finished.recv_timeout(POLL), Err(RecvTimeoutError::Timeout));
                (finished, over)
            });
            finished = back;
            if over {
                break;
            }
            if interrupt.is_none()
                && let Err(e) = py.check_signals()
            {
                stop.raise();
                interrupt = Some(e);
            }
        }
        let joined = py.detach(move || handle.join());
        match joined {
            Ok(result) => Ok(Outcome { result, interrupt }),
            Err(panic) => {
                let what = panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("no message");
                Err(PyRuntimeError::new_err(format!(
                    "the render failed (a bug in strata, please report it): {what}"
                )))
            }
        }
    })
}
