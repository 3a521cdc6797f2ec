//! The UART frame a fingertip sends each cycle, in `fingertip-link`'s format (the host decodes
//! it with the same crate): 28 bytes, a sync, a sequence number, the estimate, Fletcher-16.

use crate::Estimate;
pub use fingertip_link::{Frame, LEN};

/// The frame for `estimate`, sequence number `seq`.
pub fn encode(estimate: &Estimate, seq: u8) -> [u8; LEN] {
    Frame {
        seq,
        // The wire's stamp wraps after 71 min.
        t_us: estimate.t_us as u32,
        pressure_pa: estimate.pressure_pa,
        tared: estimate.tared,
        in_contact: estimate.in_contact,
        fault: false,
        force_gf: estimate.force_gf,
        grid_cell: estimate.grid_cell,
        pad_cell: estimate.pad_cell,
        torque_raw: estimate.torque_raw,
    }
    .encode()
}

/// The frame a failed cycle sends: the fault flag and the safe torque 0, nothing else.
pub fn fault(t_us: u64, seq: u8) -> [u8; LEN] {
    Frame::fault(t_us as u32, seq).encode()
}
