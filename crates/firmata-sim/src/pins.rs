//! The pin sets of the simulated boards, as StandardFirmata 2.5.9's `Boards.h` defines them.

use firmata_host::PinMode;

/// Which Arduino the simulator is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BoardKind {
    /// Arduino Uno (ATmega328P): pins 0–19, A0–A5 = pins 14–19, I2C on 18 (SDA) / 19 (SCL).
    #[default]
    Uno,
    /// Arduino Mega 2560: pins 0–69, A0–A15 = pins 54–69, I2C on 20 / 21.
    Mega2560,
}

impl BoardKind {
    /// `TOTAL_PINS`.
    pub fn total_pins(self) -> u8 {
        match self {
            BoardKind::Uno => 20,
            BoardKind::Mega2560 => 70,
        }
    }

    /// `TOTAL_ANALOG_PINS`.
    pub fn analog_channels(self) -> u8 {
        match self {
            BoardKind::Uno => 6,
            BoardKind::Mega2560 => 16,
        }
    }

    /// The pin of analog channel 0 (`PIN_TO_ANALOG(p) = p − first`).
    pub fn first_analog_pin(self) -> u8 {
        match self {
            BoardKind::Uno => 14,
            BoardKind::Mega2560 => 54,
        }
    }

    /// `IS_PIN_DIGITAL`: pins 0 and 1 are the USB serial line on both.
    pub fn is_digital(self, pin: u8) -> bool {
        pin >= 2 && pin < self.total_pins()
    }

    /// `IS_PIN_ANALOG`.
    pub fn is_analog(self, pin: u8) -> bool {
        pin >= self.first_analog_pin() && pin < self.total_pins()
    }

    /// The analog channel of `pin`.
    pub fn analog_channel(self, pin: u8) -> Option<u8> {
        self.is_analog(pin).then(|| pin - self.first_analog_pin())
    }

    /// `IS_PIN_PWM` (`digitalPinHasPWM` of the Arduino core's variant).
    pub fn is_pwm(self, pin: u8) -> bool {
        match self {
            BoardKind::Uno => matches!(pin, 3 | 5 | 6 | 9 | 10 | 11),
            BoardKind::Mega2560 => (2..=13).contains(&pin) || (44..=46).contains(&pin),
        }
    }

    /// `IS_PIN_I2C`.
    pub fn is_i2c(self, pin: u8) -> bool {
        match self {
            BoardKind::Uno => pin == 18 || pin == 19,
            BoardKind::Mega2560 => pin == 20 || pin == 21,
        }
    }

    /// A pin's modes and resolutions in the order the firmware lists them in its capability
    /// response (StandardFirmata 2.5.9 `CAPABILITY_QUERY`; ConfigurableFirmata 2.10.1 lists
    /// its features' in registration order and adds AccelStepperFirmata's `STEPPER 21`).
    pub fn capabilities(self, pin: u8, stepper: bool) -> Vec<(PinMode, u8)> {
        let mut modes = Vec::new();
        if self.is_digital(pin) {
            modes.extend([
                (PinMode::Input, 1),
                (PinMode::InputPullup, 1),
                (PinMode::Output, 1),
            ]);
        }
        if self.is_analog(pin) {
            modes.push((PinMode::Analog, 10));
        }
        if self.is_pwm(pin) {
            modes.push((PinMode::Pwm, 8));
        }
        if self.is_digital(pin) {
            modes.push((PinMode::Servo, 14));
        }
        if self.is_i2c(pin) {
            modes.push((PinMode::I2c, 1));
        }
        if stepper && self.is_digital(pin) {
            modes.push((PinMode::Stepper, 21));
        }
        modes
    }
}
