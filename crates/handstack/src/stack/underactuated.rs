//! The underactuated hand a scene names: an Arduino running ConfigurableFirmata with
//! AccelStepperFirmata on the `[hand]`'s `serial_port`, its sensors calibrated as
//! `[sensors.underactuated]` says (underactuated-hand).

use crate::error::RunError;
use crate::scene::SceneOf;
use crate::scene::parts::Hand;
use underactuated_hand::{HandConfig, HandError, UnderactuatedHand};

/// The board's baud rate when the scene names none: StandardFirmata's and
/// ConfigurableFirmata's `Firmata.begin(57600)`.
pub const DEFAULT_BAUD: u32 = 57_600;

/// The hand's configuration from `scene`: its `[hand]` wiring, drive and baud rate, its
/// `[sensors.underactuated]` calibration (defaults where the scene names none).
pub fn config<X>(scene: &SceneOf<X>, hand: &Hand) -> HandConfig {
    let mut config = HandConfig::default();
    if let Some(w) = &hand.wiring {
        config.wiring = *w.get_ref();
    }
    if let Some(d) = &hand.drive {
        config.drive = *d.get_ref();
    }
    config.board.baud = hand.baud.as_ref().map_or(DEFAULT_BAUD, |b| *b.get_ref());
    if let Some(u) = &scene.file.sensors.underactuated {
        config.calibration = u.get_ref().calibration();
    }
    config
}

/// Opens the underactuated hand `scene` names on its `serial_port`.
pub fn open<X>(scene: &SceneOf<X>) -> Result<UnderactuatedHand, RunError> {
    let (hand, port) = super::hand::scene_hand(scene)?;
    UnderactuatedHand::open(port, &config(scene, hand)).map_err(|e| RunError::Open {
        device: "hand",
        path: port.to_owned(),
        reason: without_port(&e),
    })
}

/// A hand error in words, without the board's port when the message already names it.
pub fn without_port(e: &HandError) -> String {
    match e {
        HandError::Board(b) => b.kind.to_string(),
        other => other.to_string(),
    }
}
