//! What the analog pins see: the extension point for a physics model.
//!
//! The board samples [`AnalogInputs::volts`] at each report (on enable, then every sampling
//! interval) and turns it into the AVR's 10-bit code against its 5 V reference. A constant per
//! pin ([`ConstantVolts`], which the binary's `--analog A0=1.25` sets) is what tests need now;
//! a simulation of the hand (finger potentiometers, FSR dividers) implements the trait — or
//! passes a closure `FnMut(channel, time since start) -> volts` — and drives the pins from its
//! state. A model whose state the board's own outputs move (a stepper pulling a tendon that
//! closes the fingers the sensors sit on) also hears each stepper's steps
//! ([`AnalogInputs::stepper_moved`]), before the pins are sampled in the same pass.
//!
//! The time a model is given restarts at 0 when the sketch restarts (each open of the port
//! resets the board); the motors and the world they move do not restart with it.

use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A source of analog pin voltages over time.
pub trait AnalogInputs: Send {
    /// The voltage at analog `channel` (A0 = 0) at `now` since the board started, in volts.
    fn volts(&mut self, channel: u8, now: Duration) -> f32;

    /// Stepper `device`'s motor turned `steps` whole steps (negative: backwards) in the board's
    /// pass that ended at `now`. Motion only: zeroing the position counter, a reset of the
    /// board or a new configuration does not turn the shaft, so it is not heard here. Nothing
    /// by default.
    fn stepper_moved(&mut self, device: u8, steps: i32, now: Duration) {
        let _ = (device, steps, now);
    }
}

impl<F: FnMut(u8, Duration) -> f32 + Send> AnalogInputs for F {
    fn volts(&mut self, channel: u8, now: Duration) -> f32 {
        self(channel, now)
    }
}

/// One constant voltage per channel, changeable while the board runs (clones share them).
///
/// ```
/// use firmata_sim::{AnalogInputs, ConstantVolts};
/// let pins = ConstantVolts::new(&[(0, 2.5)]);
/// let mut board_side = pins.clone();
/// pins.set(1, 1.0);
/// assert_eq!(board_side.volts(0, Default::default()), 2.5);
/// assert_eq!(board_side.volts(1, Default::default()), 1.0);
/// assert_eq!(board_side.volts(2, Default::default()), 0.0);
/// ```
#[derive(Debug, Clone, Default)]
pub struct ConstantVolts(Arc<Mutex<[f32; 16]>>);

impl ConstantVolts {
    /// These channels at these voltages, the rest at 0 V.
    pub fn new(channels: &[(u8, f32)]) -> ConstantVolts {
        let pins = ConstantVolts::default();
        for &(channel, volts) in channels {
            pins.set(channel, volts);
        }
        pins
    }

    /// Sets `channel` (0–15) to `volts`.
    pub fn set(&self, channel: u8, volts: f32) {
        if let Ok(mut v) = self.0.lock() {
            if let Some(slot) = v.get_mut(usize::from(channel)) {
                *slot = volts;
            }
        }
    }
}

impl AnalogInputs for ConstantVolts {
    fn volts(&mut self, channel: u8, _now: Duration) -> f32 {
        self.0
            .lock()
            .ok()
            .and_then(|v| v.get(usize::from(channel)).copied())
            .unwrap_or(0.0)
    }
}
