//! A hand of Dynamixel servos on one Protocol 2.0 bus, closed by position control under an
//! effort limit (seed 000 §6–7), through `dynamixel2`.

mod actuator;
mod status;

use dynamixel2::Bus;
use dynamixel2::instructions::SyncWriteData;
use dynamixel2::serial2::SerialPort;

use crate::control_table::{ControlTable, LimitBy};
use crate::error::{Error, faults_from_hardware_error};
use hand_traits::Faults;

/// Bytes for the bus's read and write buffers: a 4-servo sync read answer is < 100 bytes.
const BUFFER_LEN: usize = 1024;

/// One servo's state from a sync read, in raw control-table units.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
#[derive(Debug)]
pub struct ServoHand {
    bus: Bus<Vec<u8>, Vec<u8>>,
    ids: Vec<u8>,
    table: &'static ControlTable,
    /// The last command a fault-free state read confirmed.
    last_safe: Option<RawGoals>,
    /// The last command sent, not yet confirmed.
    pending: Option<RawGoals>,
}

impl ServoHand {
    /// Opens a hand on `port` (already configured for the bus's baud rate), pings every ID and
    /// identifies the model.
    ///
    /// # Errors
    /// [`Error::NoServos`], a ping failure, [`Error::UnknownModel`] or [`Error::MixedModels`].
    pub fn new(port: SerialPort, ids: &[u8]) -> Result<Self, Error> {
        let bus =
            Bus::with_buffers(port, vec![0; BUFFER_LEN], vec![0; BUFFER_LEN]).map_err(|e| {
                Error::Io(match e {
                    dynamixel2::InitializeError::GetConfiguration(io)
                    | dynamixel2::InitializeError::GetBaudRate(io) => io,
                })
            })?;
        Self::with_bus(bus, ids)
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

    fn with_bus(mut bus: Bus<Vec<u8>, Vec<u8>>, ids: &[u8]) -> Result<Self, Error> {
        let (&first, _) = ids.split_first().ok_or(Error::NoServos)?;
        let table = identify(&mut bus, first)?;
        for &id in &ids[1..] {
            let t = identify(&mut bus, id)?;
            if t.model_number != table.model_number {
                return Err(Error::MixedModels {
                    id,
                    expected: table.name,
                    found: t.name,
                });
            }
        }
        Ok(Self {
            bus,
            ids: ids.to_vec(),
            table,
            last_safe: None,
            pending: None,
        })
    }

    /// The servo IDs, in the order commands and states use.
    pub fn ids(&self) -> &[u8] {
        &self.ids
    }

    /// The model's control table.
    pub fn table(&self) -> &'static ControlTable {
        self.table
    }

    /// The underlying bus, for instructions this type does not wrap.
    pub fn bus_mut(&mut self) -> &mut Bus<Vec<u8>, Vec<u8>> {
        &mut self.bus
    }

    /// Pings one servo: its model number and firmware version.
    ///
    /// # Errors
    /// [`Error::Timeout`], [`Error::Crc`], [`Error::Status`]…
    pub fn ping(&mut self, id: u8) -> Result<(u16, u8), Error> {
        let p = self
            .bus
            .ping(id)
            .map_err(|e| Error::from_transfer(Some(id), e))?;
        Ok((p.data.model, p.data.firmware))
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
        let bytes = reg.encode(value);
        let r = self
            .bus
            .write(id, address, &bytes[..usize::from(reg.width)])
            .map_err(|e| Error::from_transfer(Some(id), e))?;
        if r.alert {
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
        let r = self
            .bus
            .read(id, address, u16::from(reg.width))
            .map_err(|e| Error::from_transfer(Some(id), e))?;
        reg.decode(&r.data).ok_or(Error::Protocol {
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
        let r = self
            .bus
            .read_u8(id, addr)
            .map_err(|e| Error::from_transfer(Some(id), e))?;
        Ok(r.data)
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
        self.bus
            .reboot(id)
            .map_err(|e| Error::from_transfer(Some(id), e))?;
        Ok(())
    }

    /// Raw goals for `cmd`, validated against the model's position limits.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a non-finite position or one outside Min / Max Position Limit.
    pub fn encode_command(&self, cmd: &hand_traits::GripperCommand) -> Result<RawGoals, Error> {
        let t = self.table;
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

    /// Sync-writes raw goals to every servo (two broadcast packets: effort, then position).
    ///
    /// # Errors
    /// A serial-port error (sync write has no status packets).
    pub fn write_goals(&mut self, goals: &RawGoals) -> Result<(), Error> {
        let t = self.table;
        for (reg, value) in [
            (t.goal_effort, goals.effort),
            (t.goal_position, goals.position),
        ] {
            let bytes = reg.encode(value);
            let data: Vec<_> = self
                .ids
                .iter()
                .map(|&motor_id| SyncWriteData {
                    motor_id,
                    data: &bytes[..usize::from(reg.width)],
                })
                .collect();
            self.bus
                .sync_write(reg.address, u16::from(reg.width), &data)
                .map_err(Error::from_write)?;
        }
        Ok(())
    }

    /// Sync-reads Present Load / Velocity / Position of every servo in one packet.
    ///
    /// # Errors
    /// The first servo's error ([`Error::Timeout`], [`Error::Crc`]…); all answers are consumed.
    pub fn read_states(&mut self) -> Result<Vec<RawServoState>, Error> {
        let t = self.table;
        let (start, len) = t.state_block();
        let ids = self.ids.clone();
        let answers = status::sync_read(&mut self.bus, &ids, start, len)?;
        let field = |reg: crate::control_table::Register, data: &[u8]| {
            reg.decode(data.get(usize::from(reg.address - start)..)?)
        };
        answers
            .into_iter()
            .map(|a| {
                match (
                    field(t.present_position, &a.data),
                    field(t.present_velocity, &a.data),
                    field(t.present_load, &a.data),
                ) {
                    (Some(position), Some(velocity), Some(load)) => Ok(RawServoState {
                        id: a.id,
                        position,
                        velocity,
                        load,
                        alert: a.alert,
                    }),
                    _ => Err(Error::Protocol {
                        id: Some(a.id),
                        detail: "short sync read".into(),
                    }),
                }
            })
            .collect()
    }

    /// Sync-writes Torque Enable = 0 to every servo: one broadcast packet, no answer needed, so
    /// it reaches every servo even when one has stopped answering.
    ///
    /// # Errors
    /// A serial-port error.
    pub fn torque_off_all(&mut self) -> Result<(), Error> {
        let reg = self.table.torque_enable;
        let data: Vec<_> = self
            .ids
            .iter()
            .map(|&motor_id| SyncWriteData {
                motor_id,
                data: [0u8],
            })
            .collect();
        self.bus
            .sync_write(reg.address, 1, &data)
            .map_err(Error::from_write)
    }

    /// Reboots every servo whose Hardware Error Status is set; returns the IDs rebooted.
    ///
    /// # Errors
    /// The exchanges' errors.
    pub fn recover(&mut self) -> Result<Vec<u8>, Error> {
        let mut rebooted = Vec::new();
        for i in 0..self.ids.len() {
            let id = self.ids[i];
            if self.hardware_error_bits(id)? != 0 {
                self.reboot(id)?;
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

/// Pings `id` and finds its control table.
fn identify(bus: &mut Bus<Vec<u8>, Vec<u8>>, id: u8) -> Result<&'static ControlTable, Error> {
    let p = bus
        .ping(id)
        .map_err(|e| Error::from_transfer(Some(id), e))?;
    ControlTable::by_model_number(p.data.model).ok_or(Error::UnknownModel {
        id,
        model_number: p.data.model,
    })
}
