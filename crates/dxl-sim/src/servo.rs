//! One simulated MX-28(2.0): the control table in memory (EEPROM / RAM, access rights, ranges →
//! error codes), a DC-motor position servo under the Goal PWM limit, and the overload shutdown.

use std::time::Duration;

use hand_control::InstructionError;
use hand_control::control_table::{
    Access, Area, ControlTable, LimitBy, MX_28, Register, hardware_error,
};

/// Physical parameters of the simulated servo: the one MX-28 model of the workspace (hand-sim's
/// grasp physics drives this motor through a [`Plant`]).
///
/// MX-28AT at 12 V, e-Manual "MX-28(2.0)" specifications: stall torque 2.5 N·m at 1.4 A, no-load
/// speed 55 rev/min (67 rev/min is the 14.8 V figure). The rotor inertia is not published:
/// `inertia_kg_m2` gives the geared motor a mechanical time constant J·ω₀/τ_stall of 20 ms,
/// typical of coreless servos of this size; gear friction is assumed too.
///
/// The overload trip (Hardware Error bit 5, "persistent load that exceeds maximum output") is
/// not documented either: the servo trips when |Present Load| stays at or above
/// `overload_threshold` (90 %) for `overload_time` (1 s). Against the evidence of the grasping
/// paper whose hand has these servos (Kim et al., *Artificial Intelligence-Based Optimal
/// Grasping Control*, 2020: §7, Table 5): a limit below 90 % can never trip it, so 400/1023 holds for more than 2 min;
/// 1023 on an object that resists at full output stalls the motor at 100 % load, trips and
/// lets go (§7), while a compliant object the servo reaches unsaturated (cone, paper cup) is
/// held at 1023 (Table 5). `docs/sim-calibration/grasp.md` works this through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoParams {
    /// Stall torque at the output, N·m.
    pub stall_torque_nm: f64,
    /// Stall current, A (Present Load and current are the same fraction of stall).
    pub stall_current_a: f64,
    /// No-load speed at the output, rad/s.
    pub no_load_speed_rad_s: f64,
    /// Output-referred inertia, kg·m² (rotor through the 193:1 gear, plus what it carries).
    pub inertia_kg_m2: f64,
    /// Viscous gear friction at the output, N·m·s/rad.
    pub gear_friction_nm_s: f64,
    /// |Present Load| fraction at or above which the overload timer runs.
    pub overload_threshold: f64,
    /// How long the load must stay there to trip.
    pub overload_time: Duration,
    /// Present Temperature reported, °C.
    pub temperature_c: u8,
    /// Present Input Voltage reported, 0.1 V.
    pub input_voltage_dv: u16,
}

/// MX-28 stall torque at 12 V, N·m (e-Manual).
pub const MX28_STALL_TORQUE_NM: f64 = 2.5;
/// MX-28 stall current at 12 V, A (e-Manual).
pub const MX28_STALL_CURRENT_A: f64 = 1.4;
/// MX-28 no-load speed at 12 V, rad/s (55 rev/min, e-Manual).
pub const MX28_NO_LOAD_SPEED_RAD_S: f64 = 55.0 * std::f64::consts::TAU / 60.0;

impl Default for ServoParams {
    fn default() -> Self {
        Self {
            stall_torque_nm: MX28_STALL_TORQUE_NM,
            stall_current_a: MX28_STALL_CURRENT_A,
            no_load_speed_rad_s: MX28_NO_LOAD_SPEED_RAD_S,
            inertia_kg_m2: MX28_STALL_TORQUE_NM / MX28_NO_LOAD_SPEED_RAD_S * 0.020,
            gear_friction_nm_s: 0.01,
            overload_threshold: 0.9,
            overload_time: Duration::from_secs(1),
            temperature_c: 36,
            input_voltage_dv: 120,
        }
    }
}

/// An external load on the output, linearised at the present state so a stiff contact stays
/// stable at any step: torque `torque_nm + stiffness·Δθ + damping·ω` opposes positive motion.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Load {
    /// Load torque at the present angle (spring part), N·m; positive opposes positive motion.
    pub torque_nm: f64,
    /// d τ / d θ, N·m/rad (≥ 0).
    pub stiffness_nm_per_rad: f64,
    /// d τ / d ω, N·m·s/rad (≥ 0).
    pub damping_nm_s_per_rad: f64,
}

impl Load {
    /// A plain torque with no stiffness or damping.
    pub fn torque(torque_nm: f64) -> Self {
        Self {
            torque_nm,
            ..Self::default()
        }
    }
}

/// What a servo drives against: an object in a gripper, a finger's spring, a wall.
///
/// Positive torque opposes positive motion. The servo asks for the [`Load`] at the start of each
/// physics step and reports where the step ended ([`Plant::stepped`]), so a plant with state of
/// its own (friction, damage, a contact patch) advances in the same steps as the motor.
pub trait Plant: Send {
    /// The load at output angle `position_rad`, speed `velocity_rad_s`, simulated time `t`.
    fn load(&mut self, position_rad: f64, velocity_rad_s: f64, t: Duration) -> Load;

    /// The step of `dt` ending at `t` left the output at `position_rad`, `velocity_rad_s`.
    fn stepped(&mut self, position_rad: f64, velocity_rad_s: f64, dt: Duration, t: Duration) {
        let _ = (position_rad, velocity_rad_s, dt, t);
    }
}

/// A closure is a plant of torque only: `|θ, ω, t| torque_nm`.
impl<F> Plant for F
where
    F: FnMut(f64, f64, Duration) -> f64 + Send,
{
    fn load(&mut self, position_rad: f64, velocity_rad_s: f64, t: Duration) -> Load {
        Load::torque(self(position_rad, velocity_rad_s, t))
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
    /// The profile's set-point in position units, moving toward Goal Position at Profile
    /// Velocity; `None` while torque is off (torque on starts it where the output is).
    setpoint: Option<f64>,
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
    pub(super) const PROFILE_VELOCITY: u16 = 112;
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
            setpoint: None,
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
        let trajectory = self
            .setpoint
            .map_or_else(|| self.get(addr::GOAL_POSITION), |sp| sp.round() as i32);
        self.set(addr::POSITION_TRAJECTORY, trajectory);
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
    /// K_PP = Position P Gain / 128 and K_PD = Position D Gain / 16, clamped to ±Goal PWM, where
    /// `e` is measured from the profile's set-point: it moves toward Goal Position at Profile
    /// Velocity (0 = at once). Velocity mode (1): PWM = K_VP·(goal − ω) with K_VP = Velocity P
    /// Gain / 128. PWM mode (16): PWM = Goal PWM. The PWM duty drives a DC motor,
    /// τ = τ_stall·(duty − ω/ω₀), against gear friction and the plant's [`Load`].
    ///
    /// The step is linearly implicit: the controller's spring and damping (while unsaturated),
    /// back-EMF, friction and the load's stiffness and damping are all taken at the end of the
    /// step, so any stiffness and any step size stay bounded.
    pub fn step(&mut self, dt: Duration, now: Duration) {
        let h = dt.as_secs_f64();
        if h <= 0.0 {
            return;
        }
        let p = self.params;
        let unit = f64::from(self.table.position_unit_rad);
        let vunit = f64::from(self.table.velocity_unit_rad_per_s);
        let pwm_full = f64::from(self.get(addr::PWM_LIMIT).max(1));
        let on = self.torque_enabled();
        let mode = self.get(addr::OPERATING_MODE);
        if !on {
            self.setpoint = None;
        } else if mode == 3 || mode == 4 {
            let goal = f64::from(self.get(addr::GOAL_POSITION));
            let here = self.setpoint.unwrap_or(self.theta / unit);
            let v = f64::from(self.get(addr::PROFILE_VELOCITY)) * vunit / unit;
            let next = if v > 0.0 {
                here + (goal - here).clamp(-v * h, v * h)
            } else {
                goal
            };
            self.setpoint = Some(next);
        }
        // duty = raw − a_θ·Δθ − a_ω·ω near the present state (per rad, per rad/s).
        let (raw, a_theta, a_omega) = match mode {
            16 => (f64::from(self.get(addr::GOAL_PWM)) / pwm_full, 0.0, 0.0),
            1 => {
                let kvp = f64::from(self.get(addr::VELOCITY_P_GAIN)) / 128.0 / pwm_full;
                let goal = f64::from(self.get(addr::GOAL_VELOCITY));
                (kvp * (goal - self.omega / vunit), 0.0, kvp / vunit)
            }
            _ => {
                let kpp = f64::from(self.get(addr::POSITION_P_GAIN)) / 128.0 / pwm_full;
                let kpd = f64::from(self.get(addr::POSITION_D_GAIN)) / 16.0 / pwm_full;
                let err = self.setpoint.unwrap_or(self.theta / unit) - self.theta / unit;
                (
                    kpp * err - kpd * self.omega / vunit,
                    kpp / unit,
                    kpd / vunit,
                )
            }
        };
        let cap = f64::from(self.get(addr::GOAL_PWM).abs()) / pwm_full;
        let duty_at = |raw: f64| if on { raw.clamp(-cap, cap) } else { 0.0 };
        let duty0 = duty_at(raw);
        let (spring, ctrl_damping) = if on && raw.abs() <= cap {
            (a_theta * p.stall_torque_nm, a_omega * p.stall_torque_nm)
        } else {
            (0.0, 0.0)
        };
        let emf = if on {
            p.stall_torque_nm / p.no_load_speed_rad_s
        } else {
            0.0
        };
        let load = match self.plant.as_mut() {
            Some(pl) => pl.load(self.theta, self.omega, now),
            None => Load::default(),
        };
        let lhs = p.inertia_kg_m2 / h
            + (spring + load.stiffness_nm_per_rad) * h
            + ctrl_damping
            + emf
            + load.damping_nm_s_per_rad
            + p.gear_friction_nm_s;
        let rhs = p.inertia_kg_m2 / h * self.omega + p.stall_torque_nm * duty0 - load.torque_nm;
        let omega_before = self.omega;
        let omega = rhs / lhs;
        self.omega = if omega.is_finite() { omega } else { 0.0 };
        let moved = self.omega * h;
        self.theta += moved;
        // The duty at the end of the step: the Present Load the servo reports.
        let duty = duty_at(raw - a_theta * moved - a_omega * (self.omega - omega_before));
        self.load = if on {
            (duty - self.omega / p.no_load_speed_rad_s).clamp(-1.0, 1.0)
        } else {
            0.0
        };
        self.now = now;
        if let Some(pl) = self.plant.as_mut() {
            pl.stepped(self.theta, self.omega, dt, now);
        }
        if on && self.load.abs() >= p.overload_threshold {
            self.over_for += dt;
            if self.over_for >= p.overload_time {
                self.raise_hardware_error(hardware_error::OVERLOAD);
                self.over_for = Duration::ZERO;
                self.setpoint = None;
                self.load = 0.0;
            }
        } else {
            self.over_for = Duration::ZERO;
        }
    }

    /// Motor current, A (signed like the load).
    pub fn current_a(&self) -> f64 {
        self.load * self.params.stall_current_a
    }

    /// Simulated time of the last step.
    pub fn now(&self) -> Duration {
        self.now
    }

    /// The motor's physical parameters.
    pub fn params(&self) -> &ServoParams {
        &self.params
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

    /// Writes `value` into the register called `name`.
    fn set(s: &mut SimServo, name: &str, value: i32) {
        let r = MX_28.register(name).unwrap();
        s.write(r.address, &r.encode(value)[..usize::from(r.width)])
            .unwrap();
    }

    /// `steps` steps of `dt` from where the servo's clock stands.
    fn run(s: &mut SimServo, dt: Duration, steps: u32) {
        for _ in 0..steps {
            let now = s.now() + dt;
            s.step(dt, now);
        }
    }

    #[test]
    fn set_point_follows_profile_velocity() {
        let mut s = servo();
        set(&mut s, "Position P Gain", 1772);
        set(&mut s, "Profile Velocity", 8);
        set(&mut s, "Torque Enable", 1);
        let start = s.get(132);
        set(&mut s, "Goal Position", start + 400);
        let dt = Duration::from_millis(1);
        run(&mut s, dt, 1000);
        // 8 × 0.229 rev/min = 0.192 rad/s: the output trails the set-point slightly.
        let v = 8.0 * f64::from(MX_28.velocity_unit_rad_per_s);
        assert!(
            (s.velocity_rad_s() - v).abs() < 0.02 * v,
            "{}",
            s.velocity_rad_s()
        );
        run(&mut s, dt, 5000);
        s.refresh();
        assert!((s.get(132) - (start + 400)).abs() <= 1, "{}", s.get(132));
        assert!(s.load_fraction().abs() < 0.05);
    }

    #[test]
    fn stalled_load_equals_goal_pwm_and_overload_needs_ninety_percent() {
        /// A wall that does not move: all damping.
        struct Wall;
        impl Plant for Wall {
            fn load(&mut self, _: f64, _: f64, _: Duration) -> Load {
                Load {
                    torque_nm: 100.0,
                    stiffness_nm_per_rad: 0.0,
                    damping_nm_s_per_rad: 1e6,
                }
            }
        }
        for (pwm, trips) in [(346, false), (778, false), (805, true), (885, true)] {
            let mut s = servo();
            s.set_plant(Some(Box::new(Wall)));
            set(&mut s, "Torque Enable", 1);
            set(&mut s, "Goal PWM", pwm);
            set(&mut s, "Goal Position", 4000);
            run(&mut s, Duration::from_millis(1), 3000);
            assert_eq!(
                s.hardware_error() == hardware_error::OVERLOAD,
                trips,
                "{pwm}"
            );
            if !trips {
                let want = f64::from(pwm) / 885.0;
                assert!(
                    (s.load_fraction() - want).abs() < 1e-3,
                    "{}",
                    s.load_fraction()
                );
                assert!((s.current_a() - want * 1.4).abs() < 2e-3);
            }
        }
    }

    #[test]
    fn stiff_load_stays_bounded_at_any_step() {
        // 1e7 N·m/rad is far stiffer than any grasp object; a linearly implicit step stays put.
        let mut s = servo();
        let wall = s.position_rad() + 0.01;
        struct Spring(f64);
        impl Plant for Spring {
            fn load(&mut self, th: f64, _: f64, _: Duration) -> Load {
                let k = 1e7;
                if th > self.0 {
                    Load {
                        torque_nm: k * (th - self.0),
                        stiffness_nm_per_rad: k,
                        damping_nm_s_per_rad: 0.0,
                    }
                } else {
                    Load::default()
                }
            }
        }
        s.set_plant(Some(Box::new(Spring(wall))));
        set(&mut s, "Torque Enable", 1);
        set(&mut s, "Goal Position", 3000);
        let dt = Duration::from_millis(5);
        let mut now = Duration::ZERO;
        for _ in 0..400 {
            now += dt;
            s.step(dt, now);
            // Contact is found at the start of a step, so the output may enter the wall by one
            // step's travel at most; an explicit step would then ring with growing amplitude.
            let (th, w) = (s.position_rad(), s.velocity_rad_s());
            assert!(
                th.is_finite() && w.is_finite() && th < wall + 0.05,
                "{th} {w}"
            );
        }
        // Pressed against the wall at the stall torque: 2.5 N·m / 1e7 N·m/rad.
        assert!(
            (s.position_rad() - wall).abs() < 1e-6,
            "{}",
            s.position_rad()
        );
        assert!(s.velocity_rad_s().abs() < 1e-6);
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
