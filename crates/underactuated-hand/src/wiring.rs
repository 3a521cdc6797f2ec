//! Which Arduino pin is which part of the hand, and how the stepper's steps pull the tendon.

/// The hand's wiring on the board.
///
/// The default is the build the project's simulated hand board uses (and a real build of the
/// paper's hand would): eight analog inputs, so a Mega 2560 (an Uno has six).
///
/// | Arduino pin | what |
/// |---|---|
/// | A0 … A3 | FSR divider of finger 1 … 4 (FSR from 5 V to the pin, 10 kΩ to ground) |
/// | A4 … A7 | distal potentiometer wiper of finger 1 … 4 (track across 5 V) |
/// | D2, D3 | STEP, DIR of the stepper driver (AccelStepperFirmata device 0) |
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct Wiring {
    /// The analog channels of the FSR dividers, finger 1 … 4.
    pub fsr_channels: [u8; 4],
    /// The analog channels of the distal potentiometers, finger 1 … 4.
    pub pot_channels: [u8; 4],
    /// The AccelStepperFirmata device number of the stepper (0–9).
    pub stepper_device: u8,
    /// The driver's STEP pin.
    pub step_pin: u8,
    /// The driver's DIR pin.
    pub dir_pin: u8,
}

impl Default for Wiring {
    fn default() -> Wiring {
        Wiring::PAPER_BUILD
    }
}

impl Wiring {
    /// The default wiring (the table above).
    pub const PAPER_BUILD: Wiring = Wiring {
        fsr_channels: [0, 1, 2, 3],
        pot_channels: [4, 5, 6, 7],
        stepper_device: 0,
        step_pin: 2,
        dir_pin: 3,
    };

    /// The eight analog channels: FSRs 1–4, then potentiometers 1–4.
    pub fn channels(&self) -> [u8; 8] {
        core::array::from_fn(|k| {
            if k < 4 {
                self.fsr_channels[k]
            } else {
                self.pot_channels[k - 4]
            }
        })
    }

    /// What is wrong with the wiring, if anything: a channel above A15, one used twice, a
    /// stepper device above 9, STEP and DIR on one pin.
    ///
    /// ```
    /// use underactuated_hand::Wiring;
    /// assert!(Wiring::default().check().is_ok());
    /// let twice = Wiring { pot_channels: [3, 5, 6, 7], ..Wiring::default() };
    /// assert_eq!(twice.check().unwrap_err(), "analog channel A3 is wired twice");
    /// ```
    pub fn check(&self) -> Result<(), String> {
        let channels = self.channels();
        for (i, c) in channels.iter().enumerate() {
            if *c > 15 {
                return Err(format!("analog channel A{c} does not exist (A0…A15)"));
            }
            if channels[..i].contains(c) {
                return Err(format!("analog channel A{c} is wired twice"));
            }
        }
        if self.stepper_device > 9 {
            return Err(format!(
                "stepper device {} does not exist (AccelStepperFirmata has 0…9)",
                self.stepper_device
            ));
        }
        if self.step_pin == self.dir_pin {
            return Err(format!("STEP and DIR are both pin {}", self.step_pin));
        }
        Ok(())
    }
}

/// How the stepper's steps pull the tendon: positive steps close the hand.
///
/// The paper gives no motor data; the default is the common build the simulated hand assumes:
/// a 200-step motor at 1/16 microstepping winding the tendon on a spool of 5.09 mm radius,
/// 0.01 mm of tendon a step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct Drive {
    /// Tendon pulled per step, mm.
    pub mm_per_step: f64,
}

impl Default for Drive {
    fn default() -> Drive {
        Drive { mm_per_step: 0.01 }
    }
}

impl Drive {
    /// The step rate of a tendon speed of `mm_s`, steps/s.
    ///
    /// ```
    /// use underactuated_hand::Drive;
    /// assert_eq!(Drive::default().steps_per_s(1.5), 150.0); // the paper-speed close
    /// ```
    pub fn steps_per_s(&self, mm_s: f64) -> f64 {
        mm_s / self.mm_per_step
    }

    /// The tendon pulled after `steps` steps from open, mm.
    pub fn travel_mm(&self, steps: i64) -> f64 {
        steps as f64 * self.mm_per_step
    }

    /// What is wrong with the drive, if anything.
    pub fn check(&self) -> Result<(), &'static str> {
        if self.mm_per_step.is_finite() && self.mm_per_step > 0.0 && self.mm_per_step <= 10.0 {
            Ok(())
        } else {
            Err("mm_per_step must be in (0, 10] mm")
        }
    }
}
