//! What asks a run to stop: a signal (SIGINT, SIGTERM, SIGHUP), the end of stdin (a node under
//! `handstack cell`), a part that failed, or a test. Every loop of a run checks its [`Stop`]
//! once a cycle and ends through its one shutdown path (the hand's end action, the arm's stop).

use std::sync::Arc;
use std::sync::atomic::{AtomicI32, Ordering};

/// Why a [`Stop`] was set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// A signal, by number (`SIGINT` 2, `SIGTERM` 15, `SIGHUP` 1).
    Signal(i32),
    /// Asked in the program: stdin closed, another part failed, a test.
    Asked,
}

impl StopReason {
    /// The exit status a process stopped so ends with: 128 + the signal's number, as a shell
    /// reports a process a signal ended (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP); 1
    /// otherwise.
    pub fn exit_code(self) -> u8 {
        match self {
            StopReason::Signal(n) => u8::try_from(128 + n).unwrap_or(1),
            StopReason::Asked => 1,
        }
    }
}

impl core::fmt::Display for StopReason {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            StopReason::Signal(n) => match signal_name(n) {
                Some(name) => f.write_str(name),
                None => write!(f, "signal {n}"),
            },
            StopReason::Asked => f.write_str("a stop request"),
        }
    }
}

/// The name of the signals a run stops on.
fn signal_name(n: i32) -> Option<&'static str> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    match n {
        SIGINT => Some("SIGINT (Ctrl-C)"),
        SIGTERM => Some("SIGTERM"),
        SIGHUP => Some("SIGHUP"),
        _ => None,
    }
}

/// 0: not set; −1: asked; n > 0: signal n.
const ASKED: i32 = -1;

/// A shared stop flag that remembers the first reason it was set for. Clones share it.
///
/// ```
/// use handstack::stop::{Stop, StopReason};
/// let stop = Stop::new();
/// let seen_by_loop = stop.clone();
/// assert_eq!(seen_by_loop.reason(), None);
/// stop.set();
/// stop.signal(2); // a later reason does not replace the first
/// assert_eq!(seen_by_loop.reason(), Some(StopReason::Asked));
/// ```
#[derive(Debug, Clone, Default)]
pub struct Stop(Arc<AtomicI32>);

impl Stop {
    /// A flag not set.
    pub fn new() -> Stop {
        Stop::default()
    }

    /// A flag set by SIGINT, SIGTERM and SIGHUP from now on. The signals no longer end the
    /// process by themselves: a second Ctrl-C while the run shuts down cannot cut its end
    /// action short (SIGKILL still can).
    ///
    /// # Errors
    /// The handlers could not be installed.
    pub fn on_signals() -> std::io::Result<Stop> {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
        let stop = Stop::new();
        let flag = stop.clone();
        // The handler only wakes this thread; the flag is set here, in a normal context.
        std::thread::Builder::new()
            .name("handstack-signals".into())
            .spawn(move || signals.forever().for_each(|sig| flag.signal(sig)))?;
        Ok(stop)
    }

    /// Sets it, asked in the program.
    pub fn set(&self) {
        let _ = self
            .0
            .compare_exchange(0, ASKED, Ordering::SeqCst, Ordering::SeqCst);
    }

    /// Sets it as signal `n` would.
    pub fn signal(&self, n: i32) {
        let _ = self
            .0
            .compare_exchange(0, n.max(1), Ordering::SeqCst, Ordering::SeqCst);
    }

    /// Whether it is set.
    pub fn is_set(&self) -> bool {
        self.0.load(Ordering::SeqCst) != 0
    }

    /// Why it was first set, if it is.
    pub fn reason(&self) -> Option<StopReason> {
        match self.0.load(Ordering::SeqCst) {
            0 => None,
            ASKED => Some(StopReason::Asked),
            n => Some(StopReason::Signal(n)),
        }
    }

    /// Sets it when stdin reaches its end (the cell closes a node's stdin to stop it).
    pub fn on_stdin_eof(&self) {
        let stop = self.clone();
        std::thread::spawn(move || {
            let mut sink = Vec::new();
            let _ = std::io::Read::read_to_end(&mut std::io::stdin(), &mut sink);
            stop.set();
        });
    }
}

/// A stop set by SIGINT, SIGTERM and SIGHUP; one set only by the program when the handlers
/// cannot be installed (said on stderr).
pub fn signal_stop() -> Stop {
    Stop::on_signals().unwrap_or_else(|e| {
        eprintln!("warning: signals will end this process without its shutdown: {e}");
        Stop::new()
    })
}
