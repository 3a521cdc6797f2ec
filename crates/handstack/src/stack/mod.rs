//! Composition: the real devices a scene names, opened by the port, bus or host it gives,
//! their buses through the run's [`Platform`].

pub mod arm;
pub mod fingertip;
pub mod fingertip_mcu;
pub mod hand;
pub mod pad;
pub mod platform;
pub mod underactuated;

use crate::error::RunError;
use crate::scene::SceneOf;
use platform::Platform;
use ur_bridge::UrArm;

/// What [`check_real_devices`] leaves open for the run: the arm. Its connection takes seconds
/// and uploads the controller's script, and a controller still closing the check's
/// connection can refuse the next one its input registers; so a run connects it once.
#[derive(Default)]
pub struct Checked {
    arm: Option<(String, UrArm)>,
}

impl Checked {
    /// The arm at `host`: the connection the check made, or a new one.
    pub fn arm(&mut self, host: &str) -> Result<UrArm, RunError> {
        match self.arm.take() {
            Some((checked, arm)) if checked == host => Ok(arm),
            _ => arm::open(host),
        }
    }
}

/// Opens every real device `scene` names (fingertip buses or board, pad bus or board, hand
/// port, arm host) and closes them again (the hand with its torque off), except the arm, which
/// stays connected in the returned [`Checked`]: a wrong path or an absent device is a typed
/// [`RunError::Open`] before any experiment starts. The sensors are opened first, so a hand is
/// never commanded when its fingertip cannot be read.
pub fn check_real_devices<X>(
    scene: &SceneOf<X>,
    platform: &dyn Platform,
) -> Result<Checked, RunError> {
    check_devices(scene, platform, true)
}

/// As [`check_real_devices`]; the arm only `with_arm` (a collect session records the sensors
/// and leaves the arm alone, so it need not be on).
pub fn check_devices<X>(
    scene: &SceneOf<X>,
    platform: &dyn Platform,
    with_arm: bool,
) -> Result<Checked, RunError> {
    let s = &scene.file.sensors;
    if s.real_fingertip() {
        drop(fingertip::open(scene, platform)?);
    }
    if let Some(pad) = s.imu_pad.as_ref().map(|p| p.get_ref()) {
        if let Some(wiring) = pad.wiring() {
            drop(pad::open_wired(platform, wiring, pad.pressure_mode)?);
        }
    }
    // The underactuated hand is opened once, by its experiment: opening resets its board.
    if let Some(h) = scene
        .file
        .hand
        .as_ref()
        .filter(|h| !h.get_ref().model.is_underactuated())
    {
        if let Some(port) = &h.get_ref().serial_port {
            // Opened to check it, then left unpowered until a run commands it.
            hand::open(h.get_ref(), port.get_ref())?
                .set_torque(false)
                .map_err(|e| RunError::Open {
                    device: "hand",
                    path: port.get_ref().clone(),
                    reason: format!("torque off after the check: {e}"),
                })?;
        }
    }
    if let Some(host) = scene
        .file
        .arm
        .as_ref()
        .and_then(|a| a.get_ref().host.as_ref())
        .filter(|_| with_arm)
    {
        let host = host.get_ref();
        return Ok(Checked {
            arm: Some((host.clone(), arm::open(host)?)),
        });
    }
    Ok(Checked::default())
}
