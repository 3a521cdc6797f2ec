//! The simulator's instruction trace: one line per instruction packet the bus executed, in
//! words, so a test (or a person) can see what a client sent and when.
//!
//! ```text
//! 0.412345 ping 1
//! 0.512000 write 1 Torque Enable=1
//! 1.020000 sync_write Goal PWM 1=254 2=254
//! 1.020150 sync_read Present Load+8 1 2
//! 3.100000 sync_write Torque Enable 1=0 2=0
//! ```
//!
//! Each line starts with the simulated time in seconds (with [`Pace::WallClock`](super::Pace)
//! the time since the bus started), then the instruction, its ID (none for a broadcast sync
//! instruction) and what it names: a register by its e-Manual name and the value written
//! (little-endian, the register's width), or for a read the first register and the bytes
//! after it.

use std::fmt::Write as _;
use std::time::Duration;

use hand_control::control_table::ControlTable;
use hand_control::protocol::{Packet, instruction_id as ins};

/// The register at `address` by name, or `@address` where the table has none.
fn register(table: &ControlTable, address: u16) -> String {
    table
        .register_at(address)
        .map_or_else(|| format!("@{address}"), |r| r.name.to_owned())
}

/// `data` as a little-endian integer (up to 4 bytes; longer data is shown in hex).
fn value(data: &[u8]) -> String {
    match data.len() {
        1 => data[0].to_string(),
        2 => i16::from_le_bytes([data[0], data[1]]).to_string(),
        4 => i32::from_le_bytes([data[0], data[1], data[2], data[3]]).to_string(),
        _ => data.iter().fold(String::from("0x"), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        }),
    }
}

/// A read of `len` bytes from `address`: the register and how far beyond it the read goes.
fn span(table: &ControlTable, address: u16, len: u16) -> String {
    let first = register(table, address);
    let width = table.register_at(address).map_or(0, |r| u16::from(r.width));
    if len > width {
        format!("{first}+{}", len - width)
    } else {
        first
    }
}

/// One trace line for `p` at simulated time `now`, registers named by `table`.
pub(crate) fn line(table: &ControlTable, now: Duration, p: &Packet) -> String {
    let u16_at = |b: &[u8], i: usize| b.get(i..i + 2).map(|s| u16::from_le_bytes([s[0], s[1]]));
    let prm = &p.params;
    let mut out = format!("{:.6} ", now.as_secs_f64());
    let _ = match p.instruction {
        ins::PING => write!(out, "ping {}", p.id),
        ins::READ => match (u16_at(prm, 0), u16_at(prm, 2)) {
            (Some(a), Some(n)) => write!(out, "read {} {}", p.id, span(table, a, n)),
            _ => write!(out, "read {} (malformed)", p.id),
        },
        ins::WRITE | ins::REG_WRITE => {
            let name = if p.instruction == ins::WRITE {
                "write"
            } else {
                "reg_write"
            };
            match u16_at(prm, 0) {
                Some(a) if prm.len() > 2 => {
                    write!(
                        out,
                        "{name} {} {}={}",
                        p.id,
                        register(table, a),
                        value(&prm[2..])
                    )
                }
                _ => write!(out, "{name} {} (malformed)", p.id),
            }
        }
        ins::ACTION => write!(out, "action {}", p.id),
        ins::REBOOT => write!(out, "reboot {}", p.id),
        ins::FACTORY_RESET => write!(out, "factory_reset {}", p.id),
        ins::SYNC_READ => match (u16_at(prm, 0), u16_at(prm, 2)) {
            (Some(a), Some(n)) => {
                let _ = write!(out, "sync_read {}", span(table, a, n));
                prm[4..].iter().try_for_each(|id| write!(out, " {id}"))
            }
            _ => write!(out, "sync_read (malformed)"),
        },
        ins::SYNC_WRITE => match (u16_at(prm, 0), u16_at(prm, 2)) {
            (Some(a), Some(n)) if n > 0 => {
                let _ = write!(out, "sync_write {}", register(table, a));
                prm[4..]
                    .chunks_exact(1 + usize::from(n))
                    .try_for_each(|c| write!(out, " {}={}", c[0], value(&c[1..])))
            }
            _ => write!(out, "sync_write (malformed)"),
        },
        ins::BULK_READ => write!(out, "bulk_read"),
        ins::BULK_WRITE => write!(out, "bulk_write"),
        other => write!(out, "instruction {other:#04x} {}", p.id),
    };
    out
}

#[cfg(test)]
mod tests {
    use super::line;
    use hand_control::control_table::MX_28;
    use hand_control::protocol::{Packet, instruction_id as ins, packet_id};
    use std::time::Duration;

    fn packet(id: u8, instruction: u8, params: &[u8]) -> Packet {
        Packet {
            id,
            instruction,
            params: params.to_vec(),
            wire_len: 10 + params.len(),
        }
    }

    #[test]
    fn lines_name_the_registers_and_values_written() {
        let t = Duration::from_millis(1_500);
        // Torque Enable (64) = 1 on servo 1.
        let p = packet(1, ins::WRITE, &[64, 0, 1]);
        assert_eq!(line(&MX_28, t, &p), "1.500000 write 1 Torque Enable=1");
        // Goal PWM (100, 2 bytes) = 254 on servos 1 and 2.
        let p = packet(
            packet_id::BROADCAST,
            ins::SYNC_WRITE,
            &[100, 0, 2, 0, 1, 254, 0, 2, 254, 0],
        );
        assert_eq!(
            line(&MX_28, t, &p),
            "1.500000 sync_write Goal PWM 1=254 2=254"
        );
        // A sync read of 10 bytes from Present Load (126, 2 bytes wide).
        let p = packet(packet_id::BROADCAST, ins::SYNC_READ, &[126, 0, 10, 0, 1, 2]);
        assert_eq!(line(&MX_28, t, &p), "1.500000 sync_read Present Load+8 1 2");
        let p = packet(1, ins::WRITE, &[1]);
        assert_eq!(line(&MX_28, t, &p), "1.500000 write 1 (malformed)");
    }
}
