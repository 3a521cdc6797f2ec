//! One simulated MX-28(2.0): the control table in memory (EEPROM / RAM, access rights, ranges →
//! error codes), a DC-motor position servo under the Goal PWM limit, and the overload shutdown.

use std::time::Duration;

use crate::InstructionError;
use crate::control_table::{Access, Area, ControlTable, LimitBy, MX_28, Register, hardware_error};

/// Physical parameters of the simulated servo.
///
/// MX-28AT at 12 V, e-Manual "MX-28(2.0)" specifications: stall torque 2.5 N·m, no-load speed
/// 55 rev/min. The rotor inertia is not published: `inertia_kg_m2` gives the geared motor a
/// mechanical time constant J·ω₀/τ_stall of 20 ms, typical of coreless servos of this size.
/// The overload trip is not documented either; the defaults bracket the paper's evidence
/// (seed 000 §7, Table 5): a torque limit of 400/1023 (39 %) holds an object for more than 2 min,
/// while 1023 (100 %) makes the servo overload and let go. The servo trips when |Present Load|
/// stays above `overload_threshold` for `overload_time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoParams {
    /// Stall torque at the output, N·m.
    pub stall_torque_nm: f64,
    /// No-load speed at the output, rad/s.
    pub no_load_speed_rad_s: f64,
    /// Output-referred inertia, kg·m².
    pub inertia_kg_m2: f64,
    /// |Present Load| fraction above which the overload timer runs.
    pub overload_threshold: f64,
    /// How long the load must stay above the threshold to trip.
    pub overload_time: Duration,
    /// Present Temperature reported, °C.
    pub temperature_c: u8,
    /// Present Input Voltage reported, 0.1 V.
    pub input_voltage_dv: u16,
}

impl Default for ServoParams {
    fn default() -> Self {
        let stall = 2.5;
        let w0 = 55.0 * std::f64::consts::TAU / 60.0;
        Self {
            stall_torque_nm: stall,
            no_load_speed_rad_s: w0,
            inertia_kg_m2: stall / w0 * 0.020,
            overload_threshold: 0.8,
            overload_time: Duration::from_secs(2),
            temperature_c: 36,
            input_voltage_dv: 120,
        }
    }
}

/// An external load on a servo's output: the torque (N·m) it opposes the motor with.
///
/// The grasp loop couples an object here: e.g. a spring that engages once the finger reaches
/// the object's surface. Positive torque opposes positive motion.
pub trait Plant: Send {
    /// Load torque at output angle `position_rad`, speed `velocity_rad_s`, simulated time `t`.
    fn load_torque_nm(&mut self, position_rad: f64, velocity_rad_s: f64, t: Duration) -> f64;
}

impl<F> Plant for F
where
    F: FnMut(f64, f64, Duration) -> f64 + Send,
{
    fn load_torque_nm(&mut self, position_rad: f64, velocity_rad_s: f64, t: Duration) -> f64 {
        self(position_rad, velocity_rad_s, t)
    }
}

/// One simulated servo.
pub struct SimServo {
    table: &'static ControlTable,
    mem: Vec<u8>,
    /// The register starting at each address (the physics reads a dozen per step).
    by_address: Vec<Option<Register>>,
    params: ServoParams,
    /// Output angle, rad (Present Position × unit).
    theta: f64,
    /// Output speed, rad/s.
    omega: f64,
    /// Motor torque as a fraction of stall torque (Present Load).
    load: f64,
    /// Time the load has stayed above the overload threshold.
    over_for: Duration,
    /// Simulated time of the last step.
    now: Duration,
    plant: Option<Box<dyn Plant>>,
    registered: Option<(u16, Vec<u8>)>,
}

impl std::fmt::Debug for SimServo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimServo")
            .field("id", &self.id())
            .field("theta", &self.theta)
            .field("omega", &self.omega)
            .field("load", &self.load)
            .finish_non_exhaustive()
    }
}

/// Registers the simulator uses by address (MX-28(2.0)).
mod addr {
    pub(super) const ID: u16 = 7;
    pub(super) const RETURN_DELAY: u16 = 9;
    pub(super) const OPERATING_MODE: u16 = 11;
    pub(super) const PWM_LIMIT: u16 = 36;
    pub(super) const SHUTDOWN: u16 = 63;
    pub(super) const TORQUE_ENABLE: u16 = 64;
    pub(super) const STATUS_RETURN_LEVEL: u16 = 68;
    pub(super) const REGISTERED: u16 = 69;
    pub(super) const HW_ERROR: u16 = 70;
    pub(super) const POSITION_D_GAIN: u16 = 80;
    pub(super) const POSITION_P_GAIN: u16 = 84;
    pub(super) const VELOCITY_P_GAIN: u16 = 78;
    pub(super) const GOAL_PWM: u16 = 100;
    pub(super) const GOAL_VELOCITY: u16 = 104;
    pub(super) const GOAL_POSITION: u16 = 116;
    pub(super) const REALTIME_TICK: u16 = 120;
    pub(super) const MOVING: u16 = 122;
    pub(super) const MOVING_THRESHOLD: u16 = 24;
    pub(super) const PRESENT_PWM: u16 = 124;
    pub(super) const PRESENT_LOAD: u16 = 126;
    pub(super) const PRESENT_VELOCITY: u16 = 128;
    pub(super) const PRESENT_POSITION: u16 = 132;
    pub(super) const VELOCITY_TRAJECTORY: u16 = 136;
    pub(super) const POSITION_TRAJECTORY: u16 = 140;
    pub(super) const PRESENT_INPUT_VOLTAGE: u16 = 144;
    pub(super) const PRESENT_TEMPERATURE: u16 = 146;
}

impl SimServo {
    /// A factory-fresh MX-28(2.0) with ID `id` at output angle `theta_rad`.
    pub fn new(id: u8, theta_rad: f64, params: ServoParams) -> Self {
        let mut by_address = vec![None; usize::from(MX_28.size)];
        for r in MX_28.registers {
            by_address[usize::from(r.address)] = Some(*r);
        }
        let mut s = Self {
            table: &MX_28,
            mem: vec![0; usize::from(MX_28.size)],
            by_address,
            params,
            theta: theta_rad,
            omega: 0.0,
            load: 0.0,
            over_for: Duration::ZERO,
            now: Duration::ZERO,
            plant: None,
            registered: None,
        };
        s.reset(Area::Eeprom);
        s.set(addr::ID, i32::from(id));
        s.reset(Area::Ram);
        s
    }

    /// Restores every register of `area` (and, for EEPROM, RAM too) to its default.
    fn reset(&mut self, area: Area) {
        for r in self.table.registers {
            if area == Area::Eeprom || r.area == Area::Ram {
                self.mem[usize::from(r.address)..usize::from(r.end())]
                    .copy_from_slice(&r.encode(r.default)[..usize::from(r.width)]);
            }
        }
        if area == Area::Ram || area == Area::Eeprom {
            // Power-on values the e-Manual leaves as "-": hold still, full PWM available.
            let pwm_limit = self.get(addr::PWM_LIMIT);
            self.set(addr::GOAL_PWM, pwm_limit);
            let here = self.position_raw();
            self.set(addr::GOAL_POSITION, here);
            self.over_for = Duration::ZERO;
            self.registered = None;
            self.sync_present(self.now);
        }
    }

    /// The register starting at `address`.
    fn reg(&self, address: u16) -> Option<Register> {
        self.by_address.get(usize::from(address)).copied().flatten()
    }

    /// A register's value (0 where no register starts). The Present registers are refreshed
    /// when a read instruction arrives; [`SimServo::position_rad`] and friends are live.
    pub fn get(&self, address: u16) -> i32 {
        self.reg(address)
            .and_then(|r| r.decode(&self.mem[usize::from(r.address)..]))
            .unwrap_or(0)
    }

    fn set(&mut self, address: u16, value: i32) {
        let Some(r) = self.reg(address) else { return };
        let bytes = r.encode(value);
        self.mem[usize::from(r.address)..usize::from(r.end())]
            .copy_from_slice(&bytes[..usize::from(r.width)]);
    }

    /// The servo's ID (register 7).
    pub fn id(&self) -> u8 {
        self.mem[usize::from(addr::ID)]
    }

    /// Status Return Level (register 68).
    pub fn status_return_level(&self) -> u8 {
        self.mem[usize::from(addr::STATUS_RETURN_LEVEL)]
    }

    /// Return Delay Time in simulated time (register 9, 2 µs units).
    pub fn return_delay(&self) -> Duration {
        Duration::from_micros(2 * u64::from(self.mem[usize::from(addr::RETURN_DELAY)]))
    }

    /// Hardware Error Status (register 70).
    pub fn hardware_error(&self) -> u8 {
        self.mem[usize::from(addr::HW_ERROR)]
    }

    /// Whether torque is enabled.
    pub fn torque_enabled(&self) -> bool {
        self.mem[usize::from(addr::TORQUE_ENABLE)] == 1
    }

    /// Output angle, rad.
    pub fn position_rad(&self) -> f64 {
        self.theta
    }

    /// Output speed, rad/s.
    pub fn velocity_rad_s(&self) -> f64 {
        self.omega
    }

    /// Motor torque as a signed fraction of stall torque.
    pub fn load_fraction(&self) -> f64 {
        self.load
    }

    /// Places the output at `theta_rad` moving at `omega_rad_s` (e.g. a finger's start pose).
    pub fn set_state(&mut self, theta_rad: f64, omega_rad_s: f64) {
        self.theta = theta_rad;
        self.omega = omega_rad_s;
    }

    /// Couples an external load (replacing any previous one).
    pub fn set_plant(&mut self, plant: Option<Box<dyn Plant>>) {
        self.plant = plant;
    }

    /// Raises hardware-error bits, as the firmware would (shutdown per register 63).
    pub fn raise_hardware_error(&mut self, bits: u8) {
        let now = self.hardware_error() | bits;
        self.mem[usize::from(addr::HW_ERROR)] = now;
        if bits & self.mem[usize::from(addr::SHUTDOWN)] != 0 {
            self.mem[usize::from(addr::TORQUE_ENABLE)] = 0;
        }
    }

    fn position_raw(&self) -> i32 {
        (self.theta / f64::from(self.table.position_unit_rad)).round() as i32
    }

    /// Copies the physical state into the Present registers.
    fn sync_present(&mut self, now: Duration) {
        let t = self.table;
        let pos = self.position_raw();
        let vel = (self.omega / f64::from(t.velocity_unit_rad_per_s)).round() as i32;
        let load = (self.load * 1000.0).round().clamp(-1000.0, 1000.0) as i32;
        let pwm = (self.load * f64::from(self.get(addr::PWM_LIMIT))).round() as i32;
        self.set(addr::PRESENT_POSITION, pos);
        self.set(addr::POSITION_TRAJECTORY, self.get(addr::GOAL_POSITION));
        self.set(addr::PRESENT_VELOCITY, vel);
        self.set(addr::VELOCITY_TRAJECTORY, vel);
        self.set(addr::PRESENT_LOAD, load);
        self.set(addr::PRESENT_PWM, pwm);
        let moving = vel.abs() > self.get(addr::MOVING_THRESHOLD);
        self.set(addr::MOVING, i32::from(moving));
        self.set(addr::REALTIME_TICK, (now.as_millis() % 32768) as i32);
        self.set(
            addr::PRESENT_INPUT_VOLTAGE,
            i32::from(self.params.input_voltage_dv),
        );
        self.set(
            addr::PRESENT_TEMPERATURE,
            i32::from(self.params.temperature_c),
        );
    }

    /// Advances the motor by `dt` ending at simulated time `now`.
    ///
    /// Position modes (3, 4): the e-Manual's P(D) position law, PWM = K_PP·e − K_PD·ė with
    /// K_PP = Position P Gain / 128 and K_PD = Position D Gain / 16, clamped to ±Goal PWM.
    /// Velocity mode (1): PWM = K_VP·(goal − ω) with K_VP = Velocity P Gain / 128. PWM mode
    /// (16): PWM = Goal PWM. The PWM duty drives a DC motor: τ = τ_stall·(duty − ω/ω₀).
    pub fn step(&mut self, dt: Duration, now: Duration) {
        let h = dt.as_secs_f64();
        let p = self.params;
        let unit = f64::from(self.table.position_unit_rad);
        let vunit = f64::from(self.table.velocity_unit_rad_per_s);
        let pwm_full = f64::from(self.get(addr::PWM_LIMIT).max(1));
        let duty = if self.torque_enabled() {
            let cap = f64::from(self.get(addr::GOAL_PWM).abs()) / pwm_full;
            let pwm_units = match self.get(addr::OPERATING_MODE) {
                16 => f64::from(self.get(addr::GOAL_PWM)),
                1 => {
                    let kvp = f64::from(self.get(addr::VELOCITY_P_GAIN)) / 128.0;
                    kvp * (f64::from(self.get(addr::GOAL_VELOCITY)) - self.omega / vunit)
                }
                _ => {
                    let kpp = f64::from(self.get(addr::POSITION_P_GAIN)) / 128.0;
                    let kpd = f64::from(self.get(addr::POSITION_D_GAIN)) / 16.0;
                    let err = f64::from(self.get(addr::GOAL_POSITION)) - self.theta / unit;
                    kpp * err - kpd * self.omega / vunit
                }
            };
            (pwm_units / pwm_full).clamp(-cap, cap)
        } else {
            0.0
        };
        let motor = if self.torque_enabled() {
            p.stall_torque_nm * (duty - self.omega / p.no_load_speed_rad_s)
        } else {
            0.0
        };
        let external = match self.plant.as_mut() {
            Some(pl) => pl.load_torque_nm(self.theta, self.omega, now),
            None => 0.0,
        };
        // Semi-implicit Euler: the back-EMF term is stiff, so treat it implicitly.
        let damping = if self.torque_enabled() {
            p.stall_torque_nm / p.no_load_speed_rad_s
        } else {
            0.0
        };
        let drive = if self.torque_enabled() {
            p.stall_torque_nm * duty
        } else {
            0.0
        };
        self.omega = (self.omega * p.inertia_kg_m2 + h * (drive - external))
            / (p.inertia_kg_m2 + h * damping);
        if !self.omega.is_finite() {
            self.omega = 0.0;
        }
        self.theta += self.omega * h;
        self.load = (motor / p.stall_torque_nm).clamp(-1.0, 1.0);
        self.now = now;
        if self.torque_enabled() && self.load.abs() >= p.overload_threshold {
            self.over_for += dt;
            if self.over_for >= p.overload_time {
                self.raise_hardware_error(hardware_error::OVERLOAD);
                self.over_for = Duration::ZERO;
            }
        } else {
            self.over_for = Duration::ZERO;
        }
    }

    /// READ: `len` bytes from `address`.
    ///
    /// # Errors
    /// `Access` past the end of the table; `DataLength` for a zero length.
    pub fn read(&self, address: u16, len: u16) -> Result<Vec<u8>, InstructionError> {
        let (a, n) = (usize::from(address), usize::from(len));
        if n == 0 {
            return Err(InstructionError::DataLength);
        }
        self.mem
            .get(a..a + n)
            .map(<[u8]>::to_vec)
            .ok_or(InstructionError::Access)
    }

    /// Checks a WRITE of `data` at `address` without applying it.
    ///
    /// # Errors
    /// `Access` (gap, read-only, EEPROM under torque, past the end), `DataLength` (a register
    /// partly covered), `DataRange` (outside the register's range), `DataLimit` (outside a limit
    /// another register sets), `ResultFail` (torque on while a shutdown error is latched).
    pub fn check_write(&self, address: u16, data: &[u8]) -> Result<(), InstructionError> {
        let start = usize::from(address);
        let end = start + data.len();
        if data.is_empty() {
            return Err(InstructionError::DataLength);
        }
        if end > self.mem.len() {
            return Err(InstructionError::Access);
        }
        let mut at = start;
        while at < end {
            let r = self
                .table
                .registers
                .iter()
                .find(|r| usize::from(r.address) <= at && at < usize::from(r.end()))
                .ok_or(InstructionError::Access)?;
            if usize::from(r.address) != at || usize::from(r.end()) > end {
                return Err(InstructionError::DataLength);
            }
            if r.access != Access::Rw || (r.area == Area::Eeprom && self.torque_enabled()) {
                return Err(InstructionError::Access);
            }
            let value = r
                .decode(&data[at - start..])
                .ok_or(InstructionError::DataLength)?;
            if !r.in_range(value) {
                return Err(InstructionError::DataRange);
            }
            let within = match r.limit {
                LimitBy::None => true,
                LimitBy::Symmetric(l) => value.abs() <= self.get(l),
                // Position limits bind in Position Control Mode (3) only (e-Manual, Goal Position).
                LimitBy::Between { min, max } => {
                    self.get(addr::OPERATING_MODE) != 3
                        || (self.get(min)..=self.get(max)).contains(&value)
                }
            };
            if !within {
                return Err(InstructionError::DataLimit);
            }
            if r.address == addr::TORQUE_ENABLE
                && value == 1
                && self.hardware_error() & self.get(addr::SHUTDOWN) as u8 != 0
            {
                return Err(InstructionError::ResultFail);
            }
            at = usize::from(r.end());
        }
        Ok(())
    }

    /// WRITE: checks, then applies `data` at `address`.
    ///
    /// # Errors
    /// As [`SimServo::check_write`]; nothing is written on error.
    pub fn write(&mut self, address: u16, data: &[u8]) -> Result<(), InstructionError> {
        self.check_write(address, data)?;
        let a = usize::from(address);
        self.mem[a..a + data.len()].copy_from_slice(data);
        Ok(())
    }

    /// REG_WRITE: checks and stores a write for the next ACTION.
    ///
    /// # Errors
    /// As [`SimServo::check_write`].
    pub fn reg_write(&mut self, address: u16, data: &[u8]) -> Result<(), InstructionError> {
        self.check_write(address, data)?;
        self.registered = Some((address, data.to_vec()));
        self.set(addr::REGISTERED, 1);
        Ok(())
    }

    /// ACTION: applies the registered write.
    ///
    /// # Errors
    /// `Instruction` when nothing is registered (e-Manual, Protocol 2.0 error 0x02).
    pub fn action(&mut self) -> Result<(), InstructionError> {
        let (a, data) = self
            .registered
            .take()
            .ok_or(InstructionError::Instruction)?;
        self.set(addr::REGISTERED, 0);
        self.write(a, &data)
    }

    /// REBOOT: RAM back to defaults (torque off, hardware error cleared); EEPROM kept.
    pub fn reboot(&mut self) {
        self.reset(Area::Ram);
    }

    /// FACTORY RESET: `0xFF` everything, `0x01` all but the ID, `0x02` all but ID and baud rate.
    pub fn factory_reset(&mut self, kind: u8) {
        let (id, baud) = (self.mem[usize::from(addr::ID)], self.mem[8]);
        self.reset(Area::Eeprom);
        if kind == 0x01 || kind == 0x02 {
            self.mem[usize::from(addr::ID)] = id;
        }
        if kind == 0x02 {
            self.mem[8] = baud;
        }
    }

    /// Copies the physical state into the Present registers (before a read).
    pub(crate) fn refresh(&mut self) {
        self.sync_present(self.now);
    }

    /// The model number register (what PING reports).
    pub fn model_number(&self) -> u16 {
        self.table.model_number
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn servo() -> SimServo {
        SimServo::new(1, 1.0, ServoParams::default())
    }

    #[test]
    fn write_errors_follow_the_emanual_codes() {
        let mut s = servo();
        assert_eq!(s.write(70, &[0]), Err(InstructionError::Access)); // read-only
        assert_eq!(s.write(14, &[0]), Err(InstructionError::Access)); // gap
        assert_eq!(s.write(116, &[0, 0]), Err(InstructionError::DataLength)); // half a register
        assert_eq!(s.write(64, &[2]), Err(InstructionError::DataRange));
        assert_eq!(
            s.write(100, &900i16.to_le_bytes()),
            Err(InstructionError::DataRange)
        );
        s.write(36, &500u16.to_le_bytes()).unwrap();
        assert_eq!(
            s.write(100, &600i16.to_le_bytes()),
            Err(InstructionError::DataLimit)
        );
        assert_eq!(
            s.write(116, &5000i32.to_le_bytes()),
            Err(InstructionError::DataLimit)
        );
        s.write(64, &[1]).unwrap();
        assert_eq!(
            s.write(36, &100u16.to_le_bytes()),
            Err(InstructionError::Access)
        ); // EEPROM locked
    }

    #[test]
    fn free_servo_reaches_its_goal_and_stall_trips_overload() {
        let mut s = servo();
        let dt = Duration::from_micros(500);
        let mut now = Duration::ZERO;
        s.write(64, &[1]).unwrap();
        s.write(116, &2048i32.to_le_bytes()).unwrap();
        for _ in 0..4000 {
            now += dt;
            s.step(dt, now);
        }
        s.refresh();
        assert!((s.get(132) - 2048).abs() <= 2, "position {}", s.get(132));
        // A wall just ahead: the motor stalls at full PWM and trips after overload_time.
        let wall = s.position_rad() + 0.05;
        s.set_plant(Some(Box::new(move |th: f64, _w: f64, _t: Duration| {
            if th > wall { 500.0 * (th - wall) } else { 0.0 }
        })));
        s.write(116, &3000i32.to_le_bytes()).unwrap();
        for _ in 0..10_000 {
            now += dt;
            s.step(dt, now);
        }
        assert_eq!(s.hardware_error(), hardware_error::OVERLOAD);
        assert!(!s.torque_enabled());
        assert_eq!(s.write(64, &[1]), Err(InstructionError::ResultFail));
        s.reboot();
        assert_eq!(s.hardware_error(), 0);
        s.write(64, &[1]).unwrap();
    }
}
