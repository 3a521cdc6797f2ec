//! The minibatch Adam loop: it learns a line, and refuses non-finite rows and an empty set.

use dfdx::prelude::*;
use tactile_nets::NetError;
use tactile_nets::train::{Loss, Samples, TrainConfig, fit};

fn config(seed: u64) -> TrainConfig {
    TrainConfig {
        epochs: 60,
        batch_size: 4,
        learning_rate: 1e-2,
        l2: 0.0,
        seed,
        progress: false,
        label: String::new(),
    }
}

#[test]
fn learns_a_line_and_rejects_bad_rows() -> Result<(), NetError> {
    let mut s = Samples::default();
    for i in 0..16 {
        let x = i as f32 / 8.0 - 1.0;
        s.push(&[x], &[2.0 * x + 0.5]);
    }
    let dev = Cpu::seed_from_u64(1);
    let mut m = dev.build_module::<Linear<1, 1>, f32>();
    let log = fit::<_, 1, 1>(&dev, &mut m, &s, Loss::Mse, &config(3))?;
    let (first, last) = (log.epoch_loss[0], log.epoch_loss[log.epoch_loss.len() - 1]);
    assert!(last < first * 0.05, "loss {first} -> {last}");
    let mut bad = s.clone();
    bad.inputs[3] = f32::NAN;
    assert!(matches!(
        fit::<_, 1, 1>(&dev, &mut m, &bad, Loss::Mse, &config(3)),
        Err(NetError::NonFinite { index: 3 })
    ));
    assert!(matches!(
        fit::<_, 1, 1>(&dev, &mut m, &Samples::default(), Loss::Mse, &config(3)),
        Err(NetError::Training(_))
    ));
    Ok(())
}
