//! The command encode stage of a Dynamixel hand: a gripper command → raw goals (hand-control's
//! [`encode_goals`]) → the two Protocol 2.0 SYNC WRITE packets [`ServoHand`] sends each cycle
//! (goal effort, then goal position), framed by hand-control's [`protocol::encode`]. The
//! buffers are kept between cycles, so encoding allocates nothing once warm.
//!
//! [`ServoHand`]: hand_control::ServoHand

use crate::CycleError;
use hand_control::control_table::{ControlTable, Register};
use hand_control::protocol::{self, instruction_id, packet_id};
use hand_control::{RawGoals, encode_goals};
use hand_traits::GripperCommand;

/// Encodes the goal sync writes for a fixed set of servo IDs.
///
/// ```
/// use hand_control::control_table::MX_28;
/// use hand_control::protocol::Parser;
/// use hand_traits::{Effort, GripperCommand};
/// use handstack_benches::dxl::GoalWriter;
///
/// let mut w = GoalWriter::new(&MX_28, &[1, 2]);
/// let cmd = GripperCommand { position_rad: 3.5, effort: Effort::from_torque_limit_raw(400) };
/// let (goals, wire) = w.encode(&cmd)?;
/// assert_eq!(goals.effort, 346);
/// let mut p = Parser::default();
/// p.push(wire);
/// let pwm = p.next_packet().unwrap().unwrap(); // SYNC WRITE to Goal PWM (address 100, 2 bytes)
/// assert_eq!(pwm.params[..4], [100, 0, 2, 0]);
/// assert_eq!(pwm.params[4..], [1, 0x5A, 0x01, 2, 0x5A, 0x01]); // 346 = 0x015A for IDs 1 and 2
/// # Ok::<(), handstack_benches::CycleError>(())
/// ```
#[derive(Debug, Clone)]
pub struct GoalWriter {
    table: &'static ControlTable,
    ids: Vec<u8>,
    params: Vec<u8>,
    wire: Vec<u8>,
}

impl GoalWriter {
    /// A writer for servos `ids` of model `table`.
    pub fn new(table: &'static ControlTable, ids: &[u8]) -> Self {
        // Room for both packets: header 10 + address/length 4 + (id + 4 bytes) per servo,
        // doubled for worst-case byte stuffing.
        let per_packet = 2 * (14 + 5 * ids.len());
        GoalWriter {
            table,
            ids: ids.to_vec(),
            params: Vec::with_capacity(4 + 5 * ids.len()),
            wire: Vec::with_capacity(2 * per_packet),
        }
    }

    /// The raw goals for `cmd` and the bytes of both sync writes, in sending order.
    pub fn encode(&mut self, cmd: &GripperCommand) -> Result<(RawGoals, &[u8]), CycleError> {
        let goals = encode_goals(self.table, cmd).map_err(|e| CycleError::Config(e.to_string()))?;
        self.wire.clear();
        let (effort, position) = (self.table.goal_effort, self.table.goal_position);
        self.sync_write(effort, goals.effort);
        self.sync_write(position, goals.position);
        Ok((goals, &self.wire))
    }

    /// Appends one broadcast SYNC WRITE of `value` to `reg` of every servo.
    fn sync_write(&mut self, reg: Register, value: i32) {
        let bytes = reg.encode(value);
        let width = usize::from(reg.width);
        self.params.clear();
        self.params.extend_from_slice(&reg.address.to_le_bytes());
        self.params
            .extend_from_slice(&u16::from(reg.width).to_le_bytes());
        for &id in &self.ids {
            self.params.push(id);
            self.params.extend_from_slice(&bytes[..width]);
        }
        protocol::encode(
            &mut self.wire,
            packet_id::BROADCAST,
            instruction_id::SYNC_WRITE,
            &self.params,
        );
    }
}
