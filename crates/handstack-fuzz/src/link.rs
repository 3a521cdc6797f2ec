//! The fingertip microcontroller's UART line: what the host's frame reader (fingertip-link)
//! makes of a serial port's bytes, in chunks as reads deliver them.
//!
//! Oracles: every frame the reader returns is the 28 bytes the line carried just before it
//! (after a damaged frame the reader rescans bytes it already took, and none may be made up),
//! and encodes back to them; and the bytes it counts as dropped never exceed the line's.

use fingertip_link::{FrameReader, LEN};

/// Runs the reader over `data`.
pub fn frames(data: &[u8]) {
    let data = crate::bounded(data);
    let mut reader = FrameReader::new();
    for (i, &b) in data.iter().enumerate() {
        if let Some(Ok(frame)) = reader.push(b) {
            let start = (i + 1)
                .checked_sub(LEN)
                .unwrap_or_else(|| panic!("a frame after {} bytes", i + 1));
            assert_eq!(
                frame.encode()[..],
                data[start..=i],
                "a frame the line did not carry at {start}"
            );
        }
    }
    assert!(
        reader.dropped_bytes() <= data.len() as u64,
        "{} bytes dropped of {}",
        reader.dropped_bytes(),
        data.len()
    );
}
