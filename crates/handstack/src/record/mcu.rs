//! A fingertip microcontroller's frames as `/hand0/tactile/mcu` (`handstack_msgs/FingertipFrame`):
//! every field the board sent, its sequence number and clock included, so that `handstack train
//! contact-mlp` can rebuild the board's contact inputs from the recording.

use super::{HAND_FRAME, HAND_NS, Recorder, TopicId};
use fingertip_link::Frame;
use hand_zenoh::convert::header;
use hand_zenoh::msg::handstack_msgs::FingertipFrame;

/// What `FingertipFrame` carries for a cell or a force the board did not report.
const NONE_CELL: u8 = fingertip_link::NONE_U8;

/// The topic of a fingertip microcontroller's frames, `/hand0/tactile/mcu`.
pub fn mcu_topic() -> String {
    format!("{HAND_NS}/tactile/mcu")
}

/// `frame` as the message a recording holds, stamped `t_ns`.
pub fn to_message(frame: &Frame, t_ns: u64) -> FingertipFrame {
    FingertipFrame {
        header: header(t_ns as i64, HAND_FRAME),
        seq: frame.seq,
        t_us: frame.t_us,
        pressure_pa: frame.pressure_pa,
        tared: frame.tared,
        in_contact: frame.in_contact,
        fault: frame.fault,
        force_gf: frame.force_gf.unwrap_or(f32::NAN),
        grid_cell: frame.grid_cell.unwrap_or(NONE_CELL),
        pad_cell: frame.pad_cell.unwrap_or(NONE_CELL),
        torque_raw: frame.torque_raw,
    }
}

/// The frame a recorded message holds (a cell out of range reads as none).
pub fn from_message(m: &FingertipFrame) -> Frame {
    let cell = |c: u8, n: u8| (c < n).then_some(c);
    Frame {
        seq: m.seq,
        t_us: m.t_us,
        pressure_pa: m.pressure_pa,
        tared: m.tared,
        in_contact: m.in_contact,
        fault: m.fault,
        force_gf: m.force_gf.is_finite().then_some(m.force_gf),
        grid_cell: cell(m.grid_cell, fingertip_link::GRID_CELLS),
        pad_cell: cell(m.pad_cell, fingertip_link::PAD_CELLS),
        torque_raw: m.torque_raw,
    }
}

/// The board's clock unwrapped: its 32-bit µs stamps (wrapping after 71 min) as one count
/// from the first frame seen.
#[derive(Debug, Clone, Copy, Default)]
pub struct McuClock {
    last: Option<(u32, i64)>,
}

impl McuClock {
    /// `t_us` on the unwrapped clock (each frame's stamp is later than the one before).
    pub fn unwrap(&mut self, t_us: u32) -> i64 {
        let t = match self.last {
            Some((raw, t)) => t + i64::from(t_us.wrapping_sub(raw)),
            None => i64::from(t_us),
        };
        self.last = Some((t_us, t));
        t
    }
}

/// The frames of a fingertip's microcontroller as `/hand0/tactile/mcu`, one reused message.
pub struct McuTopic<'r> {
    recorder: &'r Recorder,
    topic: Option<TopicId>,
}

impl<'r> McuTopic<'r> {
    /// Declares the topic on `recorder`.
    pub fn new(recorder: &'r Recorder) -> Self {
        McuTopic {
            recorder,
            topic: recorder.topic::<FingertipFrame>(&mcu_topic()),
        }
    }

    /// Records `frame`, read at `t_ns`.
    pub fn record(&mut self, t_ns: u64, frame: &Frame) {
        self.recorder
            .write(self.topic, t_ns, &to_message(frame, t_ns));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_reads_back_from_its_message() {
        let frame = Frame {
            seq: 7,
            t_us: 123_456,
            pressure_pa: [101_300, 101_420, 101_010],
            tared: true,
            in_contact: true,
            fault: false,
            force_gf: Some(42.5),
            grid_cell: Some(4),
            pad_cell: None,
            torque_raw: 300,
        };
        assert_eq!(from_message(&to_message(&frame, 9)), frame);
    }

    #[test]
    fn the_boards_clock_counts_on_through_its_wrap() {
        let mut clock = McuClock::default();
        assert_eq!(clock.unwrap(u32::MAX - 5), i64::from(u32::MAX - 5));
        assert_eq!(clock.unwrap(10), i64::from(u32::MAX) + 11);
    }
}
