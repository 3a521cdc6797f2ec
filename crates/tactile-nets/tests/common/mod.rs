//! Helpers the integration tests share.

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
