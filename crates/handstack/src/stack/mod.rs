//! Composition: the devices a scene names, opened — simulated ones speaking their real
//! interfaces, real ones by the port, bus or host the scene gives, their buses opened through
//! the run's [`Platform`].

pub mod arm;
pub mod fingertip;
pub mod hand;
pub mod pad;
pub mod platform;

use crate::error::RunError;
use crate::scene::Scene;
use platform::Platform;

/// Opens every real device `scene` names (fingertip buses, pad bus, hand port, arm host) and
/// closes them again: a wrong path or an absent device is a typed [`RunError::Open`] before
/// any experiment starts. Simulated devices are built by the experiments that use them.
pub fn check_real_devices(scene: &Scene, platform: &dyn Platform) -> Result<(), RunError> {
    let s = &scene.file.sensors;
    if s.fingertip
        .as_ref()
        .is_some_and(|t| t.get_ref().i2c_buses.is_some())
    {
        drop(fingertip::open(scene, platform)?);
    }
    if let Some(bus) = s
        .imu_pad
        .as_ref()
        .and_then(|p| p.get_ref().i2c_bus.as_ref())
    {
        drop(pad::open(platform, bus.get_ref())?);
    }
    if let Some(h) = &scene.file.hand {
        if let Some(port) = &h.get_ref().serial_port {
            // Real servos grasp by real sensors only: a grasp on hardware without the
            // fingertip's buses is refused here, before the servos hear anything.
            if scene.file.experiment.get_ref().grasp.is_some() {
                drop(fingertip::open_hardware(scene, platform)?);
            }
            drop(hand::open(h.get_ref(), port.get_ref())?);
        }
    }
    if let Some(host) = scene
        .file
        .arm
        .as_ref()
        .and_then(|a| a.get_ref().host.as_ref())
    {
        drop(arm::open(Some(host.get_ref()))?);
    }
    Ok(())
}
