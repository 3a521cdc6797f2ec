//! The bytes of one goal command: the two broadcast SYNC WRITEs (goal effort, then goal
//! position) that [`ServoHand::write_goals`](super::ServoHand::write_goals) puts on the wire.

use super::RawGoals;
use crate::control_table::{ControlTable, Register};
use crate::protocol::{self, instruction_id, packet_id};

/// Frames a hand's goal sync writes into a buffer kept between calls, so encoding allocates
/// nothing once made. [`ServoHand`](super::ServoHand) sends exactly these bytes; a benchmark
/// or another transport can encode them without a port.
///
/// ```
/// use hand_control::control_table::MX_28;
/// use hand_control::protocol::Parser;
/// use hand_control::{GoalPackets, RawGoals};
///
/// let mut packets = GoalPackets::new(&MX_28, &[1, 2]);
/// let wire = packets.encode(&RawGoals { position: 2048, effort: 346 });
/// let mut p = Parser::default();
/// p.push(wire);
/// let pwm = p.next_packet().unwrap()?; // SYNC WRITE to Goal PWM (address 100, 2 bytes)
/// assert_eq!(pwm.params[..4], [100, 0, 2, 0]);
/// assert_eq!(pwm.params[4..], [1, 0x5A, 0x01, 2, 0x5A, 0x01]); // 346 = 0x015A for IDs 1 and 2
/// let position = p.next_packet().unwrap()?; // then Goal Position (116, 4 bytes)
/// assert_eq!(position.params[..4], [116, 0, 4, 0]);
/// # Ok::<(), hand_control::protocol::FrameError>(())
/// ```
#[derive(Debug, Clone)]
pub struct GoalPackets {
    table: &'static ControlTable,
    ids: Vec<u8>,
    params: Vec<u8>,
    wire: Vec<u8>,
}

impl GoalPackets {
    /// An encoder for servos `ids` of model `table`.
    pub fn new(table: &'static ControlTable, ids: &[u8]) -> GoalPackets {
        // Room for both packets: header 10 + address / length 4 + (ID + 4 bytes) per servo,
        // doubled for worst-case byte stuffing.
        let per_packet = 2 * (14 + 5 * ids.len());
        GoalPackets {
            table,
            ids: ids.to_vec(),
            params: Vec::with_capacity(4 + 5 * ids.len()),
            wire: Vec::with_capacity(2 * per_packet),
        }
    }

    /// Both sync writes of `goals`, in sending order.
    pub fn encode(&mut self, goals: &RawGoals) -> &[u8] {
        self.wire.clear();
        let (effort, position) = (self.table.goal_effort, self.table.goal_position);
        self.sync_write(effort, goals.effort);
        self.sync_write(position, goals.position);
        &self.wire
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
