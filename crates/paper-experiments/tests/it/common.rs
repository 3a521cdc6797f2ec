//! Helpers the integration tests share.

// Each test module uses a different subset of it.
#![allow(dead_code)]

use hand_control::grasp_loop::{FaultKind, Mode, Sample};
use hand_traits::SafeAction;
use std::path::{Path, PathBuf};
use tactile_nets::train::TrainConfig;

/// The workspace root (committed datasets and models live below it).
pub(crate) fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A short, silent training configuration.
pub(crate) fn quick(
    seed: u64,
    epochs: usize,
    batch_size: usize,
    learning_rate: f64,
    l2: f64,
) -> TrainConfig {
    TrainConfig {
        epochs,
        batch_size,
        learning_rate,
        l2,
        seed,
        progress: false,
        label: String::new(),
    }
}

/// The bit patterns of `v`, to compare floats exactly.
pub(crate) fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The seeded-training contract on three runs' weight files: two runs with one seed give the
/// same bytes, a run with another seed gives other bytes.
pub(crate) fn assert_seeded(same_a: &[u8], same_b: &[u8], other: &[u8]) {
    assert_eq!(same_a, same_b, "same seed, same weights");
    assert_ne!(same_a, other, "another seed, other weights");
}

/// A fresh temporary directory for this test process's model files.
pub(crate) fn temp_dir(tag: &str) -> std::io::Result<PathBuf> {
    let dir = std::env::temp_dir().join(format!("tactile-nets-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}

/// Asserts the log's first fault is `kind` and that its own cycle sent `action` and ended in
/// the safe state; returns the cycle's index.
pub(crate) fn safe_on_first_fault<const N: usize>(
    log: &[Sample<N>],
    kind: FaultKind,
    action: SafeAction,
) -> usize {
    let i = first_fault(log);
    let s = &log[i];
    assert_eq!(s.fault, Some(kind), "{s:?}");
    assert_eq!((s.safe_action, s.mode), (Some(action), Mode::Safe), "{s:?}");
    i
}

/// The index of the first faulted cycle.
pub(crate) fn first_fault<const N: usize>(log: &[Sample<N>]) -> usize {
    log.iter().position(|s| s.fault.is_some()).expect("a fault")
}

/// Every cycle is logged: numbered from 0, one 10 ms tick apart.
pub(crate) fn ticks_in_order<const N: usize>(log: &[Sample<N>]) {
    let t0 = log[0].t_us;
    for (i, s) in log.iter().enumerate() {
        assert_eq!((s.cycle, s.t_us), (i as u64, t0 + i as u64 * 10_000));
    }
}
