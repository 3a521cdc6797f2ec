//! One frame: fixed length, little-endian, a Fletcher-16 checksum over everything before it.
//!
//! | bytes | field |
//! |---|---|
//! | 0–1 | sync `A5 5A` |
//! | 2 | sequence number (wraps) |
//! | 3 | flags: bit 0 tared, bit 1 in contact, bit 2 fault (the torque is the safe 0) |
//! | 4–7 | time stamp, µs (wraps after 71 min) |
//! | 8–19 | pressure of sensors 1–3, Pa (`i32`) |
//! | 20–21 | force, 0.1 gf (`u16`, `FFFF`: none, as while taring) |
//! | 22 | Arrival-of-Time cell `0..9` on the 3 × 3 grid (`FF`: no contact) |
//! | 23 | contact MLP cell `0..24` on the 4 × 6 pad (`FF`: no contact) |
//! | 24–25 | grasp torque limit, MX-28 counts `0..=1023` |
//! | 26–27 | Fletcher-16 of bytes 0–25 |

use core::fmt;

/// Bytes in one frame.
pub const LEN: usize = 28;
/// The UART's rate, 8N1: a frame takes 0.6 ms, well inside the 6.18 ms sensor cycle at
/// OSR 1024.
pub const BAUD: u32 = 460_800;
/// The two bytes every frame starts with.
pub const SYNC: [u8; 2] = [0xA5, 0x5A];
/// Flag: the pad's zero is tared (force and contact are meaningful).
pub const TARED: u8 = 1;
/// Flag: the mean contact pressure is above the contact threshold.
pub const IN_CONTACT: u8 = 1 << 1;
/// Flag: the cycle failed; the torque field holds the safe value 0.
pub const FAULT: u8 = 1 << 2;
/// A cell field's "nothing" value.
pub const NONE_U8: u8 = 0xFF;
/// The force field's "nothing" value.
pub const NONE_U16: u16 = 0xFFFF;

/// Cells of the 3 × 3 Arrival-of-Time grid.
pub const GRID_CELLS: u8 = 9;
/// Cells of the 4 × 6 pad.
pub const PAD_CELLS: u8 = 24;
/// The largest torque limit an MX-28 takes, counts.
const TORQUE_MAX: u16 = 1023;

/// What one fingertip cycle reports.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    /// Sequence number; it wraps, so a gap tells the host frames were lost.
    pub seq: u8,
    /// The cycle's time stamp, µs (the MCU's clock, wrapping at 2³² µs).
    pub t_us: u32,
    /// The three compensated pressures, Pa.
    pub pressure_pa: [i32; 3],
    /// Whether the zero is tared; until then force and contact are not estimated.
    pub tared: bool,
    /// Whether the mean rise is above the contact threshold.
    pub in_contact: bool,
    /// Whether the cycle failed (then the torque is the safe 0 and nothing is estimated).
    pub fault: bool,
    /// The force estimate, gf, sent in steps of 0.1 gf (negative forces as 0; at most
    /// 6553.4 gf).
    pub force_gf: Option<f32>,
    /// Arrival-of-Time's cell on the 3 × 3 grid (`0..9`, row-major), once a contact arrived.
    pub grid_cell: Option<u8>,
    /// The contact MLP's cell on the 4 × 6 pad (`0..24`, row-major), once a contact arrived.
    pub pad_cell: Option<u8>,
    /// The grasp torque limit, MX-28 counts (`0..=1023`).
    pub torque_raw: u16,
}

/// Why 28 bytes are not a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FrameError {
    /// The first two bytes are not [`SYNC`].
    Sync([u8; 2]),
    /// The checksum does not match the bytes before it: damaged on the way.
    Checksum {
        /// The checksum the frame carries.
        carried: u16,
        /// The checksum of its bytes.
        computed: u16,
    },
    /// A field holds a value the MCU never sends (a checksum-valid frame of another format).
    Field {
        /// The field's name.
        field: &'static str,
        /// Its value.
        value: u16,
    },
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrameError::Sync([a, b]) => {
                write!(f, "frame starts {a:02X} {b:02X}, not the sync A5 5A")
            }
            FrameError::Checksum { carried, computed } => write!(
                f,
                "frame damaged: it carries checksum {carried:04X}, its bytes sum to {computed:04X}"
            ),
            FrameError::Field { field, value } => {
                write!(
                    f,
                    "frame's {field} is {value}, which the fingertip never sends"
                )
            }
        }
    }
}

impl core::error::Error for FrameError {}

impl Frame {
    /// The frame a failed cycle sends: the fault flag and the safe torque 0, nothing else.
    pub fn fault(t_us: u32, seq: u8) -> Frame {
        Frame {
            seq,
            t_us,
            fault: true,
            ..Frame::default()
        }
    }

    /// The frame's 28 bytes. Force is rounded to 0.1 gf, half up; a negative or NaN force
    /// is sent as 0.
    pub fn encode(&self) -> [u8; LEN] {
        let mut f = [0u8; LEN];
        f[..2].copy_from_slice(&SYNC);
        f[2] = self.seq;
        f[3] = (u8::from(self.tared) * TARED)
            | (u8::from(self.in_contact) * IN_CONTACT)
            | (u8::from(self.fault) * FAULT);
        f[4..8].copy_from_slice(&self.t_us.to_le_bytes());
        for (k, p) in self.pressure_pa.iter().enumerate() {
            f[8 + 4 * k..12 + 4 * k].copy_from_slice(&p.to_le_bytes());
        }
        // No `f32::round` without std; `as` saturates and sends NaN as 0.
        let force = self.force_gf.map_or(NONE_U16, |g| {
            (g * 10.0 + 0.5).clamp(0.0, f32::from(NONE_U16 - 1)) as u16
        });
        f[20..22].copy_from_slice(&force.to_le_bytes());
        f[22] = self.grid_cell.unwrap_or(NONE_U8);
        f[23] = self.pad_cell.unwrap_or(NONE_U8);
        f[24..26].copy_from_slice(&self.torque_raw.to_le_bytes());
        let sum = fletcher16(&f[..LEN - 2]);
        f[LEN - 2..].copy_from_slice(&sum.to_le_bytes());
        f
    }

    /// The frame in `bytes`: sync, checksum and every field checked.
    pub fn decode(bytes: &[u8; LEN]) -> Result<Frame, FrameError> {
        if bytes[..2] != SYNC {
            return Err(FrameError::Sync([bytes[0], bytes[1]]));
        }
        let carried = u16::from_le_bytes([bytes[LEN - 2], bytes[LEN - 1]]);
        let computed = fletcher16(&bytes[..LEN - 2]);
        if carried != computed {
            return Err(FrameError::Checksum { carried, computed });
        }
        let flags = bytes[3];
        if flags & !(TARED | IN_CONTACT | FAULT) != 0 {
            return Err(FrameError::Field {
                field: "flags",
                value: u16::from(flags),
            });
        }
        let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]);
        let cell = |field, value: u8, cells| match value {
            NONE_U8 => Ok(None),
            v if v < cells => Ok(Some(v)),
            v => Err(FrameError::Field {
                field,
                value: u16::from(v),
            }),
        };
        let torque_raw = u16_at(24);
        if torque_raw > TORQUE_MAX {
            return Err(FrameError::Field {
                field: "torque",
                value: torque_raw,
            });
        }
        let force = u16_at(20);
        Ok(Frame {
            seq: bytes[2],
            t_us: u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]),
            pressure_pa: core::array::from_fn(|k| {
                let i = 8 + 4 * k;
                i32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]])
            }),
            tared: flags & TARED != 0,
            in_contact: flags & IN_CONTACT != 0,
            fault: flags & FAULT != 0,
            force_gf: (force != NONE_U16).then(|| f32::from(force) / 10.0),
            grid_cell: cell("Arrival-of-Time cell", bytes[22], GRID_CELLS)?,
            pad_cell: cell("contact MLP cell", bytes[23], PAD_CELLS)?,
            torque_raw,
        })
    }
}

/// Fletcher-16 (RFC 1146's modulo-255 sums): the first sum in the low byte, the second in the
/// high byte.
pub fn fletcher16(bytes: &[u8]) -> u16 {
    let (a, b) = bytes.iter().fold((0u16, 0u16), |(a, b), &x| {
        let a = (a + u16::from(x)) % 255;
        (a, (b + a) % 255)
    });
    (b << 8) | a
}
