//! Live progress of a scene run, reported to whoever shows it (the binary's indicatif bars).

/// Receives a run's stages and their advance; every method has a no-op default.
pub trait Progress {
    /// A new stage of `len` units starts (`len` 0: unknown length).
    fn stage(&self, _name: &str, _len: u64) {}
    /// `n` more units of the current stage are done.
    fn advance(&self, _n: u64) {}
}

/// Shows nothing (tests, `--json`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {}
