//! Live progress of a scene run, reported to whoever shows it ([`Bars`] on a terminal).

/// Receives a run's stages and their advance; every method has a no-op default.
pub trait Progress {
    /// A new stage of `len` units starts (`len` 0: unknown length).
    fn stage(&self, _name: &str, _len: u64) {}
    /// `n` more units of the current stage are done.
    fn advance(&self, _n: u64) {}
    /// Tells the user something they must read or act on (a question, what a step measured):
    /// on stderr by default, always shown.
    fn say(&self, text: &str) {
        eprintln!("{text}");
    }
}

/// Shows nothing (tests, `--json`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {}

/// An indicatif bar per stage on stderr, or nothing when stderr is not a terminal.
#[derive(Debug)]
pub struct Bars(indicatif::ProgressBar);

impl Bars {
    /// A live bar when `live` (and stderr is a terminal), else a hidden one.
    pub fn new(live: bool) -> Bars {
        use std::io::IsTerminal as _;
        if !(live && std::io::stderr().is_terminal()) {
            return Bars(indicatif::ProgressBar::hidden());
        }
        let bar = indicatif::ProgressBar::new(0).with_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {prefix} {msg} [{bar:30}] {pos}/{len} {elapsed}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        Bars(bar)
    }

    /// Names what the bar is working on (the scene file).
    pub fn prefix(&self, prefix: String) {
        self.0.set_prefix(prefix);
    }

    /// Runs `f` with the bar hidden, so printed lines do not tear it.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.0.suspend(f)
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}

impl Progress for Bars {
    fn stage(&self, name: &str, len: u64) {
        self.0.set_length(len);
        self.0.set_position(0);
        self.0.set_message(name.to_owned());
    }
    fn advance(&self, n: u64) {
        self.0.inc(n);
    }
    fn say(&self, text: &str) {
        self.0.suspend(|| eprintln!("{text}"));
    }
}
