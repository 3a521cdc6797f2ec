//! The arm a paper scene names: ur-sim's UR controller simulator on loopback by default (at
//! the `[sim.arm]` time scale), or the controller at `host`; either way the real ur_rtde client
//! (`handstack::stack::arm`).

use crate::scene::PaperScene;
use handstack::RunError;
use std::net::Ipv4Addr;
use std::sync::atomic::{AtomicU8, Ordering};
use ur_bridge::UrArm;
use ur_sim::{SimConfig, UrSim};

/// Loopback addresses handed to the simulators this process starts (127.0.0.60 on), so scenes
/// run side by side in one process do not share ports; ur-sim's own tests use lower ones.
static NEXT_OCTET: AtomicU8 = AtomicU8::new(60);

/// Hands out simulator addresses from 127.0.0.`octet` on (never lower than the default 60, nor
/// below an address already handed out): a test binary that must stay off another's loopback
/// range moves this process's range before it opens a scene.
pub fn sim_addresses_from(octet: u8) {
    NEXT_OCTET.fetch_max(octet, Ordering::Relaxed);
}

/// A connected arm, and the simulator behind it when the scene named none.
pub struct ArmStack {
    /// The ur_rtde client.
    pub arm: UrArm,
    /// Where it is connected.
    pub host: String,
    /// The simulator, when the scene named no host (dropped after the arm).
    pub sim: Option<UrSim>,
}

/// Connects to the controller at the host `scene`'s `[arm]` names, or starts a simulator
/// (run as `[sim.arm]` says) on a fresh loopback address and connects to it.
pub fn open(scene: &PaperScene) -> Result<ArmStack, RunError> {
    open_by(scene, handstack::stack::arm::open)
}

/// [`open`] in a run: a named host's arm is the connection the run's device check made.
pub fn open_in(
    scene: &PaperScene,
    cx: &handstack::runs::RunContext<'_>,
) -> Result<ArmStack, RunError> {
    open_by(scene, |host| cx.arm(host))
}

fn open_by(
    scene: &PaperScene,
    connect: impl FnOnce(&str) -> Result<UrArm, RunError>,
) -> Result<ArmStack, RunError> {
    let host = scene
        .file
        .arm
        .as_ref()
        .and_then(|a| a.get_ref().host.as_ref().map(|h| h.get_ref().clone()));
    let (host, sim) = match host {
        Some(h) => (h, None),
        None => {
            let octet = NEXT_OCTET.fetch_add(1, Ordering::Relaxed);
            let address = Ipv4Addr::new(127, 0, 0, octet);
            let sim = UrSim::start(SimConfig {
                address,
                time_scale: scene.arm_sim.time_scale,
                ..SimConfig::default()
            })
            .map_err(|e| RunError::Open {
                device: "arm (simulator)",
                path: address.to_string(),
                reason: e.to_string(),
            })?;
            (address.to_string(), Some(sim))
        }
    };
    let arm = connect(&host)?;
    Ok(ArmStack { arm, host, sim })
}
