//! Long computations that Ctrl-C stops: the work runs on a worker thread
//! with the GIL released while the calling thread polls Python's signal
//! handlers every [`POLL`]; on an exception (KeyboardInterrupt, or any a
//! signal handler raised) the work's [`Cancel`] flag is set, the worker
//! joined and the exception re-raised.

use pyo3::prelude::*;
use segmentation::Cancel;
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::Duration;

/// How often the calling thread runs Python's signal handlers.
pub const POLL: Duration = Duration::from_millis(50);

/// Runs `work` on a worker thread, the GIL released, and returns its
/// result; a Python exception raised by a signal handler meanwhile stops
/// it (through its [`Cancel`]) and is returned once the worker has ended.
/// A panic of the worker is resumed on the calling thread.
pub fn run_interruptible<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&Cancel) -> T + Send,
{
    let cancel = Cancel::new();
    std::thread::scope(|scope| {
        let (tx, mut rx) = channel();
        let cancel = &cancel;
        let worker = scope.spawn(move || {
            // The receiver outlives the worker unless the caller left.
            let _ = tx.send(work(cancel));
        });
        loop {
            let (received, back) = py.detach(move || (rx.recv_timeout(POLL), rx));
            rx = back;
            match received {
                Ok(result) => {
                    join(py, worker);
                    return Ok(result);
                }
                Err(RecvTimeoutError::Disconnected) => {
                    join(py, worker);
                    unreachable!("the worker sends its result before it ends");
                }
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(interrupt) = py.check_signals() {
                        cancel.cancel();
                        join(py, worker);
                        return Err(interrupt);
                    }
                }
            }
        }
    })
}

/// Joins the worker without the GIL, resuming its panic if it panicked.
fn join(py: Python<'_>, worker: std::thread::ScopedJoinHandle<'_, ()>) {
    if let Err(panic) = py.detach(move || worker.join()) {
        std::panic::resume_unwind(panic);
    }
}
