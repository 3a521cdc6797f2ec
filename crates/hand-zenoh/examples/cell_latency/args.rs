//! `--name value` and `--flag` arguments, and the stdin that stops a role when it closes.

use crate::Error;
use std::io::Read;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The command line after the program's name.
pub(crate) struct Args<'a>(&'a [String]);

impl<'a> Args<'a> {
    pub(crate) fn new(argv: &'a [String]) -> Args<'a> {
        Args(argv)
    }

    /// The value after `--name`.
    pub(crate) fn value(&self, name: &str) -> Option<&'a str> {
        let i = self.0.iter().position(|a| a == name)?;
        self.0.get(i + 1).map(String::as_str)
    }

    /// The value after `--name`, parsed; `default` when absent.
    pub(crate) fn parse<T: std::str::FromStr>(&self, name: &str, default: T) -> Result<T, Error> {
        match self.value(name) {
            None => Ok(default),
            Some(v) => v
                .parse()
                .map_err(|_| format!("{name} {v}: not a valid value").into()),
        }
    }

    /// The value after `--name`, which must be there.
    pub(crate) fn required(&self, name: &str) -> Result<&'a str, Error> {
        self.value(name)
            .ok_or_else(|| format!("{name} is required").into())
    }

    /// Whether `--name` is there.
    pub(crate) fn flag(&self, name: &str) -> bool {
        self.0.iter().any(|a| a == name)
    }
}

/// Set when stdin closes (the orchestrator's stop) — or never, when the cap passes first.
#[derive(Clone)]
pub(crate) struct Stop {
    flag: Arc<AtomicBool>,
    cap: Instant,
}

impl Stop {
    /// Watches stdin in a thread; `cap` bounds the role's life whatever stdin does.
    pub(crate) fn watch_stdin(cap: Duration) -> (Stop, mpsc::Receiver<()>) {
        let flag = Arc::new(AtomicBool::new(false));
        let (tx, rx) = mpsc::channel();
        let set = Arc::clone(&flag);
        std::thread::spawn(move || {
            let mut sink = [0u8; 256];
            let mut stdin = std::io::stdin();
            while matches!(stdin.read(&mut sink), Ok(n) if n > 0) {}
            set.store(true, Ordering::SeqCst);
            let _ = tx.send(());
        });
        (
            Stop {
                flag,
                cap: Instant::now() + cap,
            },
            rx,
        )
    }

    /// Stdin closed or the cap passed.
    pub(crate) fn stopped(&self) -> bool {
        self.flag.load(Ordering::Relaxed) || Instant::now() >= self.cap
    }

    /// Blocks until stdin closes or the cap passes.
    pub(crate) fn wait(&self, closed: &mpsc::Receiver<()>) {
        let left = self.cap.saturating_duration_since(Instant::now());
        let _ = closed.recv_timeout(left);
    }
}
