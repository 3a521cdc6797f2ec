//! Helpers the integration tests share.

use hand_control::grasp_loop::{FaultKind, Mode, Sample};
use hand_traits::SafeAction;
use std::path::{Path, PathBuf};

/// The workspace root (committed datasets and models live below it).
pub(crate) fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
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
