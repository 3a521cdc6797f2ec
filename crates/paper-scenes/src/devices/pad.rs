//! The ICM-20789 pad a paper scene names, as a frame source: hand-sim's pad with its chip
//! model behind the real driver, its taps the protocol's schedule (who presses where is the
//! environment, not the device). A real pad (`i2c_bus` or `firmata_port`) is opened and
//! identified by `handstack::stack::pad`, but no driver-level frame source for it exists yet,
//! so asking for its frames is an error naming it.

use crate::Error;
use crate::error::device;
use crate::scene::PaperScene;
use hand_sim::imu_pad::{ImuPad, TapSpec};

/// The seed of the scene's pad (its noise, the rows of its taps): its tap experiment's
/// `seed`, else the scene's.
pub fn seed(scene: &PaperScene) -> u64 {
    scene
        .tap()
        .and_then(|t| t.seed)
        .unwrap_or_else(|| scene.seed())
}

/// The scene's taps: `per_region` on each region, on rows drawn from its [`seed`]
/// (`tap_run::schedule`).
pub fn schedule(scene: &PaperScene, per_region: usize) -> Vec<TapSpec> {
    paper_experiments::tap_run::schedule(seed(scene), per_region)
}

/// The scene's pad, with the randomness of its [`seed`], tapped at `taps`.
pub fn open(scene: &PaperScene, taps: Vec<TapSpec>) -> Result<ImuPad, Error> {
    let seed = seed(scene);
    let real = scene
        .file
        .sensors
        .imu_pad
        .as_ref()
        .and_then(|p| p.get_ref().wiring());
    if let Some(wiring) = real {
        return Err(device(
            "sensors.imu_pad",
            format!("{}: a real pad is not yet a frame source", wiring.path()),
        ));
    }
    let mut config = scene.sim.imu_pad.clone().unwrap_or_default();
    config.taps = taps;
    Ok(ImuPad::new(&config, seed)?)
}
