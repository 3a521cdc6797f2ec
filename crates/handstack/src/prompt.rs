//! What a run asks its user ("place 50 gf on the fingertip, then press Enter"): each question
//! answered by a line on stdin, or ended by the run's [`Stop`], so Ctrl-C at a question ends
//! the run as it ends one anywhere else.

use crate::stop::{Stop, StopReason};
use std::io::BufRead;
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Mutex, OnceLock};
use std::time::Duration;

/// How often a wait for an answer looks at the stop.
const STOP_POLL: Duration = Duration::from_millis(50);

/// Why a question got no answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unanswered {
    /// The run was stopped while it waited.
    Stopped(StopReason),
    /// The input ended (stdin closed, a script ran out of lines).
    Closed,
}

type Source = Box<dyn BufRead + Send>;

/// The answers to a run's questions, one line each, read on a thread of their own from the
/// first question on (a run that asks nothing never reads its input).
pub struct Prompter {
    source: Mutex<Option<Source>>,
    lines: OnceLock<Mutex<Receiver<String>>>,
}

impl Default for Prompter {
    fn default() -> Self {
        Prompter::stdin()
    }
}

impl Prompter {
    /// Answers from this process's stdin.
    pub fn stdin() -> Prompter {
        Prompter::from_reader(std::io::BufReader::new(std::io::stdin()))
    }

    /// Answers from `reader`, a line each (a script, a test).
    ///
    /// ```
    /// use handstack::prompt::{Prompter, Unanswered};
    /// use handstack::stop::Stop;
    /// let p = Prompter::from_reader(&b"\n120\n"[..]);
    /// let stop = Stop::new();
    /// assert_eq!(p.answer(&stop), Ok(String::new()));
    /// assert_eq!(p.answer(&stop), Ok("120".to_owned()));
    /// assert_eq!(p.answer(&stop), Err(Unanswered::Closed));
    /// ```
    pub fn from_reader(reader: impl BufRead + Send + 'static) -> Prompter {
        Prompter {
            source: Mutex::new(Some(Box::new(reader))),
            lines: OnceLock::new(),
        }
    }

    /// The next line, without its line ending and surrounding blanks; waits until one comes,
    /// the input ends or `stop` is set.
    pub fn answer(&self, stop: &Stop) -> Result<String, Unanswered> {
        let lines = self.lines.get_or_init(|| {
            let (tx, rx) = channel();
            let source = self
                .source
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .take();
            if let Some(mut source) = source {
                std::thread::spawn(move || {
                    let mut line = String::new();
                    // Ends at the input's end or a read error: the question is then unanswered.
                    while matches!(source.read_line(&mut line), Ok(n) if n > 0) {
                        if tx.send(line.trim().to_owned()).is_err() {
                            break;
                        }
                        line.clear();
                    }
                });
            }
            Mutex::new(rx)
        });
        let lines = lines
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        loop {
            if let Some(reason) = stop.reason() {
                return Err(Unanswered::Stopped(reason));
            }
            match lines.recv_timeout(STOP_POLL) {
                Ok(line) => return Ok(line),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(stop
                        .reason()
                        .map_or(Unanswered::Closed, Unanswered::Stopped));
                }
            }
        }
    }
}
