//! The fingertip a paper scene names: three real MS5611 on its `i2c_buses` or behind a switch
//! on its `firmata_port` (`handstack::stack::fingertip`), or hand-sim's pad with three MS5611
//! chip models behind the real driver.

use crate::scene::PaperScene;
use hand_traits::{PressureFrame, TactileSource};
use handstack::RunError;
use handstack::stack::platform::Platform;

/// A fingertip of either kind, its errors as run errors.
pub struct Fingertip(Box<dyn TactileSource<Frame = PressureFrame<3>, Error = RunError>>);

impl Fingertip {
    /// `source` as a fingertip.
    pub fn new(
        source: impl TactileSource<Frame = PressureFrame<3>, Error = RunError> + 'static,
    ) -> Fingertip {
        Fingertip(Box::new(source))
    }
}

impl TactileSource for Fingertip {
    type Frame = PressureFrame<3>;
    type Error = RunError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        self.0.read_frame()
    }
}

/// The scene's fingertip: real when it names `i2c_buses`, `firmata_port` or `serial_port`
/// (opened through `platform`), else hand-sim's, seeded by the scene.
pub fn open(scene: &PaperScene, platform: &dyn Platform) -> Result<Fingertip, crate::Error> {
    if scene.file.sensors.real_fingertip() {
        return Ok(Fingertip::new(handstack::stack::fingertip::open(
            &scene.scene,
            platform,
        )?));
    }
    Ok(Fingertip::new(SimSource(pressable(scene, |seed| seed)?)))
}

/// hand-sim's fingertip with its errors as run errors.
struct SimSource(hand_sim::fingertip::Fingertip);

impl TactileSource for SimSource {
    type Frame = PressureFrame<3>;
    type Error = RunError;
    fn read_frame(&mut self) -> Result<PressureFrame<3>, RunError> {
        self.0.read_frame().map_err(|e| RunError::Device {
            device: "sensors.fingertip",
            reason: e.to_string(),
        })
    }
}

/// The simulated fingertip of `scene` with its environment in reach: a protocol that places
/// loads on the pad itself (the weight series) drives it through hand-sim's `set_contact` and
/// reads it through the real driver. `stream` picks the seeded run (`weight_run_seed`).
pub fn pressable(
    scene: &PaperScene,
    stream: impl FnOnce(u64) -> u64,
) -> Result<hand_sim::fingertip::Fingertip, crate::Error> {
    let config = scene.sim.fingertip.clone().unwrap_or_default();
    Ok(hand_sim::fingertip::Fingertip::new(
        &config,
        stream(scene.seed()),
    )?)
}
