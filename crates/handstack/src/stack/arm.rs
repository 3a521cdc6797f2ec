//! The arm a scene names: the Universal Robots controller at `host`, through ur_rtde.

use crate::error::RunError;
use std::time::Duration;
use ur_bridge::{UrArm, UrConfig};

/// How long one move may take before the client gives up (a tap-to-move grid move takes about
/// 2 s at the default speed; a loaded machine's simulator needs more).
pub const MOVE_TIMEOUT: Duration = Duration::from_secs(20);

/// Connects to the controller at `host` (ur_rtde's control and receive interfaces).
pub fn open(host: &str) -> Result<UrArm, RunError> {
    let mut config = UrConfig::new(host);
    config.move_timeout = MOVE_TIMEOUT;
    UrArm::connect(config).map_err(|e| RunError::Open {
        device: "arm",
        path: host.to_owned(),
        reason: e.to_string(),
    })
}
