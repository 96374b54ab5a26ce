//! Clean stops on Ctrl-C, SIGTERM and SIGHUP (the `ctrlc` crate with its
//! `termination` feature). The handler sets a flag; a watcher thread then
//! waits for the frame being written (if any) to get its manifest line, and
//! exits. A frame still rendering is abandoned before any of its files exist,
//! so no partial frame is left: nothing is written until a frame is whole in
//! memory, and the write phase runs under [`StopGuard::write_lock`].

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// Exit code after a stop requested by a signal (128 + SIGINT).
pub const EXIT_INTERRUPTED: i32 = 130;

/// A stop flag and the lock held while a frame's files and manifest line are written.
#[derive(Clone, Default)]
pub struct StopGuard {
    flag: Arc<AtomicBool>,
    lock: Arc<Mutex<()>>,
}

impl StopGuard {
    /// A guard with no handler installed (tests, library use).
    pub fn new() -> StopGuard {
        StopGuard::default()
    }

    /// True once a stop was requested.
    pub fn stopped(&self) -> bool {
        self.flag.load(Ordering::SeqCst)
    }

    /// Requests a stop (as the signal handler does).
    pub fn request_stop(&self) {
        self.flag.store(true, Ordering::SeqCst);
    }

    /// The lock to hold while writing a frame; the signal watcher takes it
    /// before exiting, so a frame being written is finished first.
    pub fn write_lock(&self) -> std::sync::MutexGuard<'_, ()> {
        self.lock.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Installs the process-wide handler: on a signal, set the flag, wait for
    /// any write in progress, run `on_stop` (sweep, summary) and exit with
    /// [`EXIT_INTERRUPTED`]. Call at most once per process.
    pub fn install(&self, on_stop: impl Fn() + Send + 'static) -> Result<(), String> {
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        let flag = self.flag.clone();
        ctrlc::set_handler(move || {
            flag.store(true, Ordering::SeqCst);
            let _ = tx.send(());
        })
        .map_err(|e| format!("cannot install the signal handler: {e}"))?;
        let me = self.clone();
        std::thread::spawn(move || {
            if rx.recv().is_ok() {
                eprintln!("parallax: stop requested; finishing the frame being written");
                let _held = me.write_lock();
                on_stop();
                std::process::exit(EXIT_INTERRUPTED);
            }
        });
        Ok(())
    }
}
