//! The hand a scene names on a real bus: `ServoHand` (dynamixel2 over serial2) on the scene's
//! `serial_port`.

use crate::error::RunError;
use crate::scene::parts::Hand;
use hand_control::{DEFAULT_REPLY_LATENCY, ServoHand};
use std::time::Duration;

/// The default bus speed, 1 Mbps. Kim et al. 2020 (§6, Table 4) drive their hand's MX-28
/// servos over RS-485 but give no speed.
pub const DEFAULT_BAUD: u32 = 1_000_000;

/// Opens `port` and identifies the servos `hand` names; position mode, torque on.
pub fn open(hand: &Hand, port: &str) -> Result<ServoHand, RunError> {
    let baud = hand.baud.as_ref().map_or(DEFAULT_BAUD, |b| *b.get_ref());
    let latency = hand
        .reply_timeout_ms
        .map_or(DEFAULT_REPLY_LATENCY, Duration::from_millis);
    let fail = |reason: String| RunError::Open {
        device: "hand",
        path: port.to_owned(),
        reason,
    };
    let serial = serial2::SerialPort::open(port, baud).map_err(|e| fail(e.to_string()))?;
    let mut servo = ServoHand::with_reply_latency(serial, &hand.ids, latency)
        .map_err(|e| fail(format!("servos {}: {e}", ids(&hand.ids))))?;
    let Some(named) = hand.model.table() else {
        return Err(fail(format!("`{}` is not a servo hand", hand.model.name())));
    };
    let found = servo.table();
    if found.model_number != named.model_number {
        return Err(fail(format!(
            "the servos are {}, the scene names `{}` ({})",
            found.name, named.key, named.name
        )));
    }
    // Operating Mode is in EEPROM, writable only with torque off (a previous run may have
    // left it on).
    servo
        .set_torque(false)
        .and_then(|()| servo.set_position_mode())
        .and_then(|()| servo.set_torque(true))
        .map_err(|e| fail(format!("setting up the servos: {e}")))?;
    Ok(servo)
}

/// Servo IDs as a person writes them: `1, 2`.
fn ids(ids: &[u8]) -> String {
    ids.iter().map(u8::to_string).collect::<Vec<_>>().join(", ")
}

/// What a hand's messages call its bus: `servo bus /dev/ttyUSB0`.
pub fn bus_label(port: &str) -> String {
    format!("servo bus {port}")
}

/// The `[hand]` `scene` names and its `serial_port` (a simulated hand has none: an error).
pub fn scene_hand<X>(scene: &crate::scene::SceneOf<X>) -> Result<(&Hand, &str), RunError> {
    scene
        .file
        .hand
        .as_ref()
        .and_then(|h| {
            Some((
                h.get_ref(),
                h.get_ref().serial_port.as_ref()?.get_ref().as_str(),
            ))
        })
        .ok_or(RunError::Device {
            device: "hand",
            reason: "a hardware hand needs a [hand] on a serial_port".into(),
        })
}

/// Opens the hand `scene` names on its `serial_port`.
pub fn open_scene<X>(scene: &crate::scene::SceneOf<X>) -> Result<ServoHand, RunError> {
    let (hand, port) = scene_hand(scene)?;
    open(hand, port)
}
