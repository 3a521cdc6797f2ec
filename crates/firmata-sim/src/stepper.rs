//! A stepper as AccelStepperFirmata drives it: a position that moves toward its target at up
//! to the maximum speed, accelerating and decelerating at the set rate (AccelStepper's
//! trapezoidal profile), integrated in wall-clock time.

/// `MAX_ACCELERATION` of ConfigurableFirmata 2.10.1 `AccelStepperFirmata.h`: the acceleration
/// a stepper has after config, or when set to 0 — full speed on the first step.
pub const MAX_ACCELERATION: f64 = 1_000_000.0;

/// One configured stepper.
#[derive(Debug, Clone, PartialEq)]
pub struct Stepper {
    position: f64,
    target: i64,
    speed: f64,
    max_speed: f64,
    acceleration: f64,
    running: bool,
    enabled: bool,
}

impl Default for Stepper {
    /// As after `ACCELSTEPPER_CONFIG`: at 0, maximum speed 1 step/s, acceleration
    /// [`MAX_ACCELERATION`], not running.
    fn default() -> Stepper {
        Stepper {
            position: 0.0,
            target: 0,
            speed: 0.0,
            max_speed: 1.0,
            acceleration: MAX_ACCELERATION,
            running: false,
            enabled: true,
        }
    }
}

impl Stepper {
    /// The position in whole steps, as AccelStepper's `currentPosition()` counts them.
    pub fn position(&self) -> i32 {
        self.position.round() as i32
    }

    /// Whether a move is under way.
    pub fn running(&self) -> bool {
        self.running
    }

    /// Whether the outputs are enabled.
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    /// `ACCELSTEPPER_ZERO`: the current position becomes 0.
    pub fn zero(&mut self) {
        self.target -= self.position.round() as i64;
        self.position = 0.0;
    }

    /// `ACCELSTEPPER_TO`.
    pub fn move_to(&mut self, target: i32) {
        self.target = i64::from(target);
        self.running = true;
    }

    /// `ACCELSTEPPER_STEP`: relative to the current position.
    pub fn move_by(&mut self, steps: i32) {
        self.target = self.position.round() as i64 + i64::from(steps);
        self.running = true;
    }

    /// `ACCELSTEPPER_SET_SPEED` (the maximum speed; its magnitude).
    pub fn set_max_speed(&mut self, steps_per_s: f32) {
        self.max_speed = f64::from(steps_per_s).abs();
    }

    /// `ACCELSTEPPER_SET_ACCELERATION`; 0 means [`MAX_ACCELERATION`].
    pub fn set_acceleration(&mut self, steps_per_s2: f32) {
        let a = f64::from(steps_per_s2).abs();
        self.acceleration = if a == 0.0 { MAX_ACCELERATION } else { a };
    }

    /// `ACCELSTEPPER_ENABLE`.
    pub fn set_enabled(&mut self, on: bool) {
        self.enabled = on;
    }

    /// `ACCELSTEPPER_STOP` as ConfigurableFirmata 2.10.1 does it: the run flag drops, so the
    /// motor stops where it is.
    pub fn stop(&mut self) {
        self.running = false;
        self.speed = 0.0;
        self.position = self.position.round();
        self.target = self.position as i64;
    }

    /// Advances `dt_s` seconds; `true` when the move completed in it.
    pub fn advance(&mut self, dt_s: f64) -> bool {
        if !self.running {
            return false;
        }
        // Sub-steps of at most 0.5 ms keep the profile's corners within a step.
        let n = (dt_s / 5e-4).ceil().max(1.0);
        let h = dt_s / n;
        for _ in 0..n as u64 {
            let target = self.target as f64;
            let d = target - self.position;
            if d == 0.0 && self.speed == 0.0 {
                self.running = false;
                return true;
            }
            let dir = if d > 0.0 { 1.0 } else { -1.0 };
            let stopping = self.speed * self.speed / (2.0 * self.acceleration);
            if self.speed * dir > 0.0 && d.abs() <= stopping {
                // Decelerate, never past standstill.
                let v = self.speed - dir * self.acceleration * h;
                self.speed = if v * dir < 0.0 { 0.0 } else { v };
            } else {
                let v = self.speed + dir * self.acceleration * h;
                self.speed = v.clamp(-self.max_speed, self.max_speed);
            }
            self.position += self.speed * h;
            let crossed = (target - self.position) * dir <= 0.0;
            // Within half a step at creeping speed counts as arrived (the last step is taken).
            let creeping = self.speed.abs() * h < 1e-3 && (target - self.position).abs() < 0.5;
            if crossed || creeping {
                self.position = target;
                self.speed = 0.0;
                self.running = false;
                return true;
            }
        }
        false
    }
}
