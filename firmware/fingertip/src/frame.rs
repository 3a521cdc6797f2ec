//! The UART frame a fingertip sends each cycle: fixed length, little-endian, a Fletcher-16
//! checksum over everything before it, so a host resynchronises on the two sync bytes and
//! drops a damaged frame instead of acting on it.
//!
//! | bytes | field |
//! |---|---|
//! | 0–1 | sync `A5 5A` |
//! | 2 | sequence number (wraps) |
//! | 3 | flags: bit 0 tared, bit 1 in contact, bit 2 fault (the torque is the safe 0) |
//! | 4–7 | time stamp, µs (wraps after 71 min) |
//! | 8–19 | pressure of sensors 1–3, Pa (`i32`) |
//! | 20–21 | force, 0.1 gf (`u16`, `FFFF` while taring) |
//! | 22 | Arrival-of-Time cell `0..9` on the 3 × 3 grid (`FF`: no contact) |
//! | 23 | contact MLP cell `0..24` on the 4 × 6 pad (`FF`: no contact) |
//! | 24–25 | grasp torque limit, MX-28 counts `0..=1023` |
//! | 26–27 | Fletcher-16 of bytes 0–25 |

use crate::Estimate;

/// Bytes in one frame.
pub const LEN: usize = 28;
/// The two bytes every frame starts with.
pub const SYNC: [u8; 2] = [0xA5, 0x5A];
/// Flag: the pad's zero is tared (force and contact are meaningful).
pub const TARED: u8 = 1;
/// Flag: the mean contact pressure is above the contact threshold.
pub const IN_CONTACT: u8 = 1 << 1;
/// Flag: the cycle failed; the torque field holds the safe value 0.
pub const FAULT: u8 = 1 << 2;
/// A field's "nothing" value.
pub const NONE_U8: u8 = 0xFF;
/// The force field's "nothing" value.
pub const NONE_U16: u16 = 0xFFFF;

/// The frame for `estimate`, sequence number `seq`.
pub fn encode(estimate: &Estimate, seq: u8) -> [u8; LEN] {
    let mut f = [0u8; LEN];
    f[..2].copy_from_slice(&SYNC);
    f[2] = seq;
    f[3] = (u8::from(estimate.tared) * TARED) | (u8::from(estimate.in_contact) * IN_CONTACT);
    f[4..8].copy_from_slice(&(estimate.t_us as u32).to_le_bytes());
    for (k, p) in estimate.pressure_pa.iter().enumerate() {
        f[8 + 4 * k..12 + 4 * k].copy_from_slice(&p.to_le_bytes());
    }
    // Rounded half up (no `f32::round` without std); negative and NaN forces send 0.
    let force = estimate.force_gf.map_or(NONE_U16, |g| {
        (g * 10.0 + 0.5).clamp(0.0, f32::from(NONE_U16 - 1)) as u16
    });
    f[20..22].copy_from_slice(&force.to_le_bytes());
    f[22] = estimate.grid_cell.unwrap_or(NONE_U8);
    f[23] = estimate.pad_cell.unwrap_or(NONE_U8);
    f[24..26].copy_from_slice(&estimate.torque_raw.to_le_bytes());
    seal(&mut f);
    f
}

/// The frame a failed cycle sends: the fault flag and the safe torque 0, nothing else.
pub fn fault(t_us: u64, seq: u8) -> [u8; LEN] {
    let mut f = [0u8; LEN];
    f[..2].copy_from_slice(&SYNC);
    f[2] = seq;
    f[3] = FAULT;
    f[4..8].copy_from_slice(&(t_us as u32).to_le_bytes());
    f[20..22].copy_from_slice(&NONE_U16.to_le_bytes());
    f[22] = NONE_U8;
    f[23] = NONE_U8;
    seal(&mut f);
    f
}

/// Whether `f` carries its sync bytes and a matching checksum.
pub fn is_valid(f: &[u8; LEN]) -> bool {
    f[..2] == SYNC && f[LEN - 2..] == fletcher16(&f[..LEN - 2]).to_le_bytes()
}

fn seal(f: &mut [u8; LEN]) {
    let sum = fletcher16(&f[..LEN - 2]);
    f[LEN - 2..].copy_from_slice(&sum.to_le_bytes());
}

/// Fletcher-16 (RFC 1146's modulo-255 sums).
fn fletcher16(bytes: &[u8]) -> u16 {
    let (a, b) = bytes.iter().fold((0u16, 0u16), |(a, b), &x| {
        let a = (a + u16::from(x)) % 255;
        (a, (b + a) % 255)
    });
    (b << 8) | a
}
