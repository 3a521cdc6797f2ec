//! Helpers the integration tests share.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use tactile_nets::train::TrainConfig;

/// The seeded generator of a test's synthetic data.
pub(crate) fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
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

/// A fresh temporary directory for this test process's model files (`tag`: one per test).
pub(crate) fn temp_dir(tag: &str) -> std::io::Result<PathBuf> {
    let dir = std::env::temp_dir().join(format!("tactile-nets-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}
