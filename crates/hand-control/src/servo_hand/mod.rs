//! A hand of Dynamixel servos on one Protocol 2.0 bus, closed by position control under an
//! effort limit (the grasping paper's §6–7), through `dynamixel2`.

mod actuator;
mod goal_packets;
mod status;

pub use goal_packets::GoalPackets;
pub use status::{DecodedAnswer, decode_replies};

use std::time::Duration;

use dynamixel2::Bus;
use dynamixel2::instructions::SyncWriteData;
use dynamixel2::instructions::{instruction_id, packet_id};
use dynamixel2::serial2::SerialPort;

use crate::control_table::{ControlTable, LimitBy};
use crate::error::{Error, faults_from_hardware_error};
use hand_traits::Faults;

/// Bytes for the bus's read and write buffers: a 4-servo sync read answer is < 100 bytes.
const BUFFER_LEN: usize = 1024;

/// One servo's state from a sync read, in raw control-table units.
///
/// `Default` (all zero) is there to size a buffer for [`ServoHand::read_states_into`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RawServoState {
    /// Servo ID.
    pub id: u8,
    /// Present Position.
    pub position: i32,
    /// Present Velocity.
    pub velocity: i32,
    /// Present Load (MX) or Present Current (X, RH-P12-RN).
    pub load: i32,
    /// The status packet's alert bit: Hardware Error Status is not zero.
    pub alert: bool,
}

/// Protocol 2.0 packets a [`ServoHand`] has exchanged since it was opened: instruction packets
/// written (each sync write is one) and status packets received (a corrupted one included).
/// Instructions sent through [`ServoHand::bus_mut`] are not counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PacketCounts {
    /// Instruction packets written.
    pub sent: u64,
    /// Status packets received.
    pub received: u64,
}

/// Raw goals for every servo of a hand, as one command encodes them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RawGoals {
    /// Goal Position per servo.
    pub position: i32,
    /// Goal PWM or Goal Current per servo.
    pub effort: i32,
}

/// Servos of one model on one bus, driven together as a gripper.
///
/// Positions are the servo's raw Present Position times the model's unit (radians from raw 0);
/// the effort fraction of [`hand_traits::Effort`] maps onto Goal PWM (MX-28: the paper's
/// 0…1023 torque limit becomes 0…885) or Goal Current (XM430, RH-P12-RN).
///
/// # Allocation
///
/// The per-cycle calls allocate nothing once the hand exists: [`ServoHand::write_goals`],
/// [`ServoHand::torque_off_all`], [`ServoHand::read_states_into`] (into the caller's buffer)
/// and the [`hand_traits::GripperActuator`] methods built on them (`command`, `state`,
/// `safe_stop`). The buffers they need — the bus's read and write buffers, the status-packet
/// framing, the SYNC READ parameters, one state per servo — are sized by the constructor.
/// Errors allocate (messages), and so do the convenience [`ServoHand::read_states`] (its
/// returned `Vec`) and [`ServoHand::recover`].
#[derive(Debug)]
pub struct ServoHand {
    link: status::Link,
    ids: Vec<u8>,
    table: &'static ControlTable,
    /// SYNC READ parameters of the state block (start, length, every ID), built once.
    sync_read: Vec<u8>,
    /// One state per servo, for [`hand_traits::GripperActuator::state`].
    states: Vec<RawServoState>,
    /// The last command a fault-free state read confirmed.
    last_safe: Option<RawGoals>,
    /// The last command sent, not yet confirmed.
    pending: Option<RawGoals>,
    /// RAM settings (address, value) written again after every REBOOT.
    ram: Vec<(u16, i32)>,
    /// The goal sync writes, framed in a buffer kept between cycles.
    goal_packets: GoalPackets,
}

/// The reply allowance a real bus needs: the ROBOTIS SDK's flat 34 ms (as `dynamixel2`).
pub const DEFAULT_REPLY_LATENCY: Duration = Duration::from_millis(34);

impl ServoHand {
    /// Opens a hand on `port` (already configured for the bus's baud rate), pings every ID and
    /// identifies the model.
    ///
    /// # Errors
    /// [`Error::NoServos`], a ping failure, [`Error::UnknownModel`] or [`Error::MixedModels`].
    pub fn new(port: SerialPort, ids: &[u8]) -> Result<Self, Error> {
        Self::with_reply_latency(port, ids, DEFAULT_REPLY_LATENCY)
    }

    /// As [`ServoHand::new`], allowing each status packet `latency` beyond its wire time (from
    /// the identifying pings on). A USB adapter, or a simulated bus on a loaded machine, may
    /// want more than a real servo's [`DEFAULT_REPLY_LATENCY`] (`dxl-sim` advises 1 s).
    ///
    /// # Errors
    /// As [`ServoHand::new`].
    pub fn with_reply_latency(
        port: SerialPort,
        ids: &[u8],
        latency: Duration,
    ) -> Result<Self, Error> {
        let bus =
            Bus::with_buffers(port, vec![0; BUFFER_LEN], vec![0; BUFFER_LEN]).map_err(|e| {
                Error::Io(match e {
                    dynamixel2::InitializeError::GetConfiguration(io)
                    | dynamixel2::InitializeError::GetBaudRate(io) => io,
                })
            })?;
        Self::with_bus(bus, ids, latency)
    }

    /// Opens the serial device at `path` with `baud_rate` and builds the hand.
    ///
    /// # Errors
    /// As [`ServoHand::new`], plus opening the port.
    pub fn open(
        path: impl AsRef<std::path::Path>,
        baud_rate: u32,
        ids: &[u8],
    ) -> Result<Self, Error> {
        Self::new(SerialPort::open(path, baud_rate)?, ids)
    }

    fn with_bus(bus: Bus<Vec<u8>, Vec<u8>>, ids: &[u8], latency: Duration) -> Result<Self, Error> {
        let (&first, _) = ids.split_first().ok_or(Error::NoServos)?;
        let mut hand = Self {
            link: status::Link::new(bus, latency)?,
            ids: ids.to_vec(),
            table: &crate::control_table::MX_28,
            sync_read: Vec::new(),
            states: vec![RawServoState::default(); ids.len()],
            last_safe: None,
            pending: None,
            ram: Vec::new(),
            goal_packets: GoalPackets::new(&crate::control_table::MX_28, ids),
        };
        let table = hand.identify(first)?;
        for &id in &ids[1..] {
            let t = hand.identify(id)?;
            if t.model_number != table.model_number {
                return Err(Error::MixedModels {
                    id,
                    expected: table.name,
                    found: t.name,
                });
            }
        }
        hand.table = table;
        hand.goal_packets = GoalPackets::new(table, ids);
        let (start, len) = table.state_block();
        hand.sync_read.reserve_exact(4 + ids.len());
        hand.sync_read.extend_from_slice(&start.to_le_bytes());
        hand.sync_read.extend_from_slice(&len.to_le_bytes());
        hand.sync_read.extend_from_slice(ids);
        // The largest exchange a hand makes: every servo's state block.
        hand.link.reserve(ids.len(), len);
        Ok(hand)
    }

    /// Pings `id` and finds its control table.
    fn identify(&mut self, id: u8) -> Result<&'static ControlTable, Error> {
        let (model_number, _) = self.ping(id)?;
        ControlTable::by_model_number(model_number).ok_or(Error::UnknownModel { id, model_number })
    }

    /// Sets how long each status packet may take beyond its wire time.
    pub fn set_reply_latency(&mut self, latency: Duration) {
        self.link.latency = latency;
    }

    /// One instruction to `id` and its status packet (`count` data bytes).
    fn transfer(
        &mut self,
        id: u8,
        instruction: u8,
        params: &[u8],
        count: u16,
    ) -> Result<status::Answer<'_>, Error> {
        self.link.exchange(id, instruction, params, &[id], count)?;
        self.link.answer(0).ok_or(Error::Timeout { id: Some(id) })
    }

    /// The servo IDs, in the order commands and states use.
    pub fn ids(&self) -> &[u8] {
        &self.ids
    }

    /// The model's control table.
    pub fn table(&self) -> &'static ControlTable {
        self.table
    }

    /// The Protocol 2.0 packets sent and received so far.
    pub fn packet_counts(&self) -> PacketCounts {
        self.link.packets
    }

    /// The underlying bus, for instructions this type does not wrap.
    pub fn bus_mut(&mut self) -> &mut Bus<Vec<u8>, Vec<u8>> {
        &mut self.link.bus
    }

    /// Pings one servo: its model number and firmware version.
    ///
    /// # Errors
    /// [`Error::Timeout`], [`Error::Crc`], [`Error::Status`]…
    pub fn ping(&mut self, id: u8) -> Result<(u16, u8), Error> {
        let a = self.transfer(id, instruction_id::PING, &[], 3)?;
        Ok((u16::from_le_bytes([a.data[0], a.data[1]]), a.data[2]))
    }

    /// The register at `address`, or [`Error::OutOfRange`] if the model has none there.
    fn register(&self, address: u16) -> Result<&'static crate::control_table::Register, Error> {
        self.table.register_at(address).ok_or(Error::OutOfRange {
            what: "register address",
            value: f64::from(address),
            min: 0.0,
            max: f64::from(self.table.size),
        })
    }

    /// Writes `value` to register `address` of servo `id` (width from the control table).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an address the table lacks; the servo's own errors otherwise;
    /// [`Error::Hardware`] when the status packet raises the alert bit (the write was executed,
    /// but the servo has a hardware error latched).
    pub fn write_register(&mut self, id: u8, address: u16, value: i32) -> Result<(), Error> {
        let reg = self.register(address)?;
        let (p, n) = address_and_value(reg, value);
        let alert = self.transfer(id, instruction_id::WRITE, &p[..n], 0)?.alert;
        if alert {
            return Err(self.hardware_error_of(id));
        }
        Ok(())
    }

    /// Reads register `address` of servo `id`.
    ///
    /// # Errors
    /// As [`ServoHand::write_register`].
    pub fn read_register(&mut self, id: u8, address: u16) -> Result<i32, Error> {
        let reg = self.register(address)?;
        let [a0, a1] = address.to_le_bytes();
        let [w0, w1] = u16::from(reg.width).to_le_bytes();
        let r = self.transfer(
            id,
            instruction_id::READ,
            &[a0, a1, w0, w1],
            u16::from(reg.width),
        )?;
        reg.decode(r.data).ok_or_else(|| Error::Protocol {
            id: Some(id),
            detail: "short read".into(),
        })
    }

    /// The Hardware Error Status of servo `id`.
    ///
    /// # Errors
    /// The exchange's errors.
    pub fn hardware_error_bits(&mut self, id: u8) -> Result<u8, Error> {
        let addr = self.table.hardware_error_status.address;
        let v = self.read_register(id, addr)?;
        Ok(v as u8)
    }

    /// [`Error::Hardware`] for servo `id` (or the read's own error).
    fn hardware_error_of(&mut self, id: u8) -> Error {
        match self.hardware_error_bits(id) {
            Ok(bits) => Error::Hardware {
                id,
                bits,
                faults: faults_from_hardware_error(bits),
            },
            Err(e) => e,
        }
    }

    /// Enables or disables torque on every servo, one acknowledged write each.
    ///
    /// # Errors
    /// [`Error::Hardware`] when a servo in shutdown refuses to enable; the exchange's errors.
    pub fn set_torque(&mut self, enable: bool) -> Result<(), Error> {
        let addr = self.table.torque_enable.address;
        for i in 0..self.ids.len() {
            let id = self.ids[i];
            match self.write_register(id, addr, i32::from(enable)) {
                // Disabling torque succeeds even while the alert bit is up.
                Err(Error::Hardware { .. }) if !enable => {}
                Err(Error::Status {
                    error: crate::InstructionError::ResultFail,
                    ..
                }) if enable => {
                    return Err(self.hardware_error_of(id));
                }
                other => other?,
            }
        }
        Ok(())
    }

    /// Puts every servo in the model's position-under-effort-limit mode (torque must be off).
    ///
    /// # Errors
    /// The exchange's errors ([`Error::Status`] with `Access` while torque is on).
    pub fn set_position_mode(&mut self) -> Result<(), Error> {
        let (addr, mode) = (self.table.operating_mode.address, self.table.position_mode);
        for i in 0..self.ids.len() {
            self.write_register(self.ids[i], addr, mode)?;
        }
        Ok(())
    }

    /// Sends REBOOT to servo `id`: clears its hardware error; torque comes back disabled.
    ///
    /// # Errors
    /// The exchange's errors.
    pub fn reboot(&mut self, id: u8) -> Result<(), Error> {
        self.transfer(id, instruction_id::REBOOT, &[], 0)?;
        Ok(())
    }

    /// REG_WRITE: servo `id` stores `value` for register `address` until ACTION.
    ///
    /// # Errors
    /// As [`ServoHand::write_register`].
    pub fn reg_write(&mut self, id: u8, address: u16, value: i32) -> Result<(), Error> {
        let reg = self.register(address)?;
        let (p, n) = address_and_value(reg, value);
        self.transfer(id, instruction_id::REG_WRITE, &p[..n], 0)?;
        Ok(())
    }

    /// ACTION to servo `id` (its registered write happens), or to every servo at once with
    /// `packet_id::BROADCAST` (no answer).
    ///
    /// # Errors
    /// [`Error::Status`] with `Instruction` when nothing was registered; the exchange's errors.
    pub fn action(&mut self, id: u8) -> Result<(), Error> {
        let expect: &[u8] = if id == packet_id::BROADCAST {
            &[]
        } else {
            &[id]
        };
        self.link
            .exchange(id, instruction_id::ACTION, &[], expect, 0)?;
        Ok(())
    }

    /// FACTORY RESET of servo `id`: `0xFF` everything, `0x01` all but the ID, `0x02` all but
    /// ID and baud rate.
    ///
    /// # Errors
    /// The exchange's errors.
    pub fn factory_reset(&mut self, id: u8, kind: u8) -> Result<(), Error> {
        self.transfer(id, instruction_id::FACTORY_RESET, &[kind], 0)?;
        Ok(())
    }

    /// Raw goals for `cmd`, validated against the model's position limits
    /// ([`encode_goals`] with this hand's control table).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a non-finite position or one outside Min / Max Position Limit.
    pub fn encode_command(&self, cmd: &hand_traits::GripperCommand) -> Result<RawGoals, Error> {
        encode_goals(self.table, cmd)
    }

    /// Sync-writes raw goals to every servo (two broadcast packets: effort, then position).
    ///
    /// Allocates nothing: [`GoalPackets`] frames both packets in a buffer the hand keeps, and
    /// they go out in one write.
    ///
    /// # Errors
    /// A serial-port error (sync write has no status packets).
    pub fn write_goals(&mut self, goals: &RawGoals) -> Result<(), Error> {
        let wire = self.goal_packets.encode(goals);
        self.link.send(wire)?;
        // Two instruction packets, sent in one write.
        self.link.packets.sent += 2;
        Ok(())
    }

    /// Sync-reads Present Load / Velocity / Position of every servo in one packet into `out`:
    /// `out[k]` is servo [`ServoHand::ids`]`()[k]`; returns how many entries were filled (the
    /// number of servos). Entries past that are left alone.
    ///
    /// Allocates nothing: the SYNC READ parameters were built by the constructor and the status
    /// packets are framed in buffers the hand keeps. Size `out` once (an array, or a `Vec`
    /// kept between calls) and reuse it every cycle.
    ///
    /// ```no_run
    /// use hand_control::{RawServoState, ServoHand};
    ///
    /// let mut hand = ServoHand::open("/dev/ttyUSB0", 1_000_000, &[1, 2])?;
    /// let mut states = [RawServoState::default(); 2]; // on the stack, reused every cycle
    /// let n = hand.read_states_into(&mut states)?;
    /// assert_eq!(n, 2);
    /// assert_eq!(states.map(|s| s.id), [1, 2]);
    /// // A buffer shorter than the hand is a typed error, and nothing is sent.
    /// assert!(matches!(
    ///     hand.read_states_into(&mut states[..1]),
    ///     Err(hand_control::Error::OutOfRange { what: "state buffer length", .. })
    /// ));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`what: "state buffer length"`) when `out` is shorter than the
    /// number of servos, before anything is sent; otherwise the first servo's error
    /// ([`Error::Timeout`], [`Error::Crc`]…), after all answers are consumed. On an exchange
    /// error `out` is left unchanged.
    pub fn read_states_into(&mut self, out: &mut [RawServoState]) -> Result<usize, Error> {
        let n = self.ids.len();
        let Some(out) = out.get_mut(..n) else {
            return Err(Error::OutOfRange {
                what: "state buffer length",
                value: out.len() as f64,
                min: n as f64,
                max: f64::INFINITY,
            });
        };
        let t = self.table;
        let (start, len) = t.state_block();
        self.link.exchange(
            packet_id::BROADCAST,
            instruction_id::SYNC_READ,
            &self.sync_read,
            &self.ids,
            len,
        )?;
        let field = |reg: crate::control_table::Register, data: &[u8]| {
            reg.decode(data.get(usize::from(reg.address - start)..)?)
        };
        for (k, state) in out.iter_mut().enumerate() {
            let a = self.link.answer(k).ok_or(Error::Timeout {
                id: self.ids.get(k).copied(),
            })?;
            match (
                field(t.present_position, a.data),
                field(t.present_velocity, a.data),
                field(t.present_load, a.data),
            ) {
                (Some(position), Some(velocity), Some(load)) => {
                    *state = RawServoState {
                        id: a.id,
                        position,
                        velocity,
                        load,
                        alert: a.alert,
                    }
                }
                _ => {
                    return Err(Error::Protocol {
                        id: Some(a.id),
                        detail: "short sync read".into(),
                    });
                }
            }
        }
        Ok(n)
    }

    /// [`ServoHand::read_states_into`] a new `Vec` (one per call: a loop should keep its own
    /// buffer and call `read_states_into`).
    ///
    /// # Errors
    /// As [`ServoHand::read_states_into`].
    pub fn read_states(&mut self) -> Result<Vec<RawServoState>, Error> {
        let mut states = vec![RawServoState::default(); self.ids.len()];
        let n = self.read_states_into(&mut states)?;
        states.truncate(n);
        Ok(states)
    }

    /// Sync-writes Torque Enable = 0 to every servo: one broadcast packet, no answer needed, so
    /// it reaches every servo even when one has stopped answering. Allocates nothing.
    ///
    /// # Errors
    /// A serial-port error.
    pub fn torque_off_all(&mut self) -> Result<(), Error> {
        let reg = self.table.torque_enable;
        let per_servo = self.ids.iter().map(|&motor_id| SyncWriteData {
            motor_id,
            data: [0u8],
        });
        self.link
            .bus
            .sync_write(reg.address, 1, per_servo)
            .map_err(Error::from_write)?;
        self.link.packets.sent += 1;
        Ok(())
    }

    /// Writes RAM registers (address, value) to every servo and keeps them: REBOOT puts RAM back
    /// to factory values, so [`ServoHand::recover`] writes them again. Gains and profiles a
    /// scene tunes belong here; EEPROM settings persist on their own.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an address where no register starts, before anything is sent;
    /// the writes' errors ([`Error::Status`] for a refused value).
    pub fn keep_ram_settings(&mut self, settings: &[(u16, i32)]) -> Result<(), Error> {
        for &(address, _) in settings {
            self.register(address)?;
        }
        self.ram = settings.to_vec();
        for i in 0..self.ids.len() {
            self.write_ram_settings(self.ids[i])?;
        }
        Ok(())
    }

    fn write_ram_settings(&mut self, id: u8) -> Result<(), Error> {
        for i in 0..self.ram.len() {
            let (address, value) = self.ram[i];
            self.write_register(id, address, value)?;
        }
        Ok(())
    }

    /// Reboots every servo whose Hardware Error Status is set, and writes its kept RAM settings
    /// ([`ServoHand::keep_ram_settings`]) again; returns the IDs rebooted.
    ///
    /// # Errors
    /// The exchanges' errors.
    pub fn recover(&mut self) -> Result<Vec<u8>, Error> {
        let mut rebooted = Vec::new();
        for i in 0..self.ids.len() {
            let id = self.ids[i];
            if self.hardware_error_bits(id)? != 0 {
                self.reboot(id)?;
                self.write_ram_settings(id)?;
                rebooted.push(id);
            }
        }
        Ok(rebooted)
    }

    /// The union of faults of the servos whose status packets raised the alert bit.
    fn faults_of(&mut self, states: &[RawServoState]) -> Result<Faults, Error> {
        let mut faults = Faults::NONE;
        for s in states.iter().filter(|s| s.alert) {
            faults = faults.union(faults_from_hardware_error(self.hardware_error_bits(s.id)?));
        }
        Ok(faults)
    }
}

/// Min / Max Position Limit defaults of the model (the Goal Position's run-time limit).
/// Raw goals of `table`'s model for `cmd`: the effort on the Goal PWM / Goal Current scale,
/// the position in Goal Position units, validated against the model's position limits. No
/// bus needed, so an in-process loop can encode exactly what [`ServoHand`] would send.
///
/// ```
/// use hand_control::{control_table::MX_28, encode_goals};
/// use hand_traits::{Effort, GripperCommand};
/// let cmd = GripperCommand { position_rad: 3.5, effort: Effort::from_torque_limit_raw(400) };
/// let goals = encode_goals(&MX_28, &cmd)?;
/// assert_eq!(goals.effort, 346); // the paper's 400 of 1023 → Goal PWM 346 of 885
/// assert!(encode_goals(&MX_28, &GripperCommand { position_rad: f32::NAN, ..cmd }).is_err());
/// # Ok::<(), hand_control::Error>(())
/// ```
///
/// # Errors
/// [`Error::OutOfRange`] for a non-finite position or one outside Min / Max Position Limit.
pub fn encode_goals(
    table: &ControlTable,
    cmd: &hand_traits::GripperCommand,
) -> Result<RawGoals, Error> {
    let t = table;
    let (min, max) = position_limits(t);
    let unit = f64::from(t.position_unit_rad);
    let (lo, hi) = (f64::from(min) * unit, f64::from(max) * unit);
    let p = f64::from(cmd.position_rad);
    if !p.is_finite() || p < lo - unit / 2.0 || p > hi + unit / 2.0 {
        return Err(Error::OutOfRange {
            what: "goal position (rad)",
            value: p,
            min: lo,
            max: hi,
        });
    }
    let position = ((p / unit).round() as i32).clamp(min, max);
    Ok(RawGoals {
        position,
        effort: t.effort_raw(cmd.effort.fraction()),
    })
}

fn position_limits(t: &ControlTable) -> (i32, i32) {
    match t.goal_position.limit {
        LimitBy::Between { min, max } => (
            t.register_at(min)
                .map_or(t.goal_position.min, |r| r.default),
            t.register_at(max)
                .map_or(t.goal_position.max, |r| r.default),
        ),
        _ => (t.goal_position.min, t.goal_position.max),
    }
}

/// WRITE / REG_WRITE parameters — the address, then the value in the register's width — and
/// how many of the six bytes they take.
fn address_and_value(reg: &crate::control_table::Register, value: i32) -> ([u8; 6], usize) {
    let [a0, a1] = reg.address.to_le_bytes();
    let [v0, v1, v2, v3] = reg.encode(value);
    ([a0, a1, v0, v1, v2, v3], 2 + usize::from(reg.width).min(4))
}
