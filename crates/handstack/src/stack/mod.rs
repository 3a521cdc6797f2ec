//! Composition: the real devices a scene names, opened by the port, bus or host it gives,
//! their buses through the run's [`Platform`].

pub mod arm;
pub mod fingertip;
pub mod hand;
pub mod pad;
pub mod platform;
pub mod underactuated;

use crate::error::RunError;
use crate::scene::SceneOf;
use platform::Platform;

/// Opens every real device `scene` names (fingertip buses or board, pad bus or board, hand
/// port, arm host) and closes them again (the hand with its torque off): a wrong path or an
/// absent device is a typed [`RunError::Open`] before any experiment starts. The sensors are
/// opened first, so a hand is never commanded when its fingertip cannot be read.
pub fn check_real_devices<X>(scene: &SceneOf<X>, platform: &dyn Platform) -> Result<(), RunError> {
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
    {
        drop(arm::open(host.get_ref())?);
    }
    Ok(())
}
