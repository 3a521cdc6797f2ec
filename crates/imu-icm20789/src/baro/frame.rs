//! The 9-byte measurement frame: three CRC-protected words, pressure or temperature first.
//!
//! Pressure travels as `P_MMSB P_MSB CRC | P_LSB P_LLSB CRC` where `P_LLSB` is not part of the
//! 24-bit code; temperature as `T_MSB T_LSB CRC` (DS-000169 §10, "sensor data read").

use crate::baro::conversion::RawSample;
use crate::baro::mode::FrameOrder;
use crate::crc8;
use crate::error::Error;

/// Bytes in one measurement frame.
pub const FRAME_LEN: usize = 9;

/// Decodes a frame read after a conversion started with `order`, checking all three CRCs.
pub fn decode_frame<E>(bytes: &[u8; FRAME_LEN], order: FrameOrder) -> Result<RawSample, Error<E>> {
    let word = |i: usize| {
        crc8::decode_word([bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]])
            .map_err(|(received, computed)| Error::Crc { received, computed })
    };
    let (w0, w1, w2) = (word(0)?, word(1)?, word(2)?);
    let pressure = |hi: u16, lo: u16| (u32::from(hi) << 8) | u32::from(lo >> 8);
    Ok(match order {
        FrameOrder::PressureFirst => RawSample {
            p_lsb: pressure(w0, w1),
            t_lsb: w2,
        },
        FrameOrder::TemperatureFirst => RawSample {
            p_lsb: pressure(w1, w2),
            t_lsb: w0,
        },
    })
}

/// Encodes `raw` the way the chip sends it (chip model). `P_LLSB` is sent as zero.
pub fn encode_frame(raw: RawSample, order: FrameOrder) -> [u8; FRAME_LEN] {
    let p = raw.p_lsb & 0x00FF_FFFF;
    let p_hi = (p >> 8) as u16;
    let p_lo = ((p & 0xFF) as u16) << 8;
    let words = match order {
        FrameOrder::PressureFirst => [p_hi, p_lo, raw.t_lsb],
        FrameOrder::TemperatureFirst => [raw.t_lsb, p_hi, p_lo],
    };
    let mut out = [0_u8; FRAME_LEN];
    for (chunk, word) in out.chunks_exact_mut(3).zip(words) {
        chunk.copy_from_slice(&crc8::encode_word(word));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_in_both_orders_and_bytes_sit_where_the_datasheet_puts_them() {
        let raw = RawSample {
            p_lsb: 0x00AB_CDEF,
            t_lsb: 0x6789,
        };
        let pf = encode_frame(raw, FrameOrder::PressureFirst);
        assert_eq!(
            [pf[0], pf[1], pf[3], pf[4], pf[6], pf[7]],
            [0xAB, 0xCD, 0xEF, 0x00, 0x67, 0x89]
        );
        let tf = encode_frame(raw, FrameOrder::TemperatureFirst);
        assert_eq!(
            [tf[0], tf[1], tf[3], tf[4], tf[6], tf[7]],
            [0x67, 0x89, 0xAB, 0xCD, 0xEF, 0x00]
        );
        for (frame, order) in [
            (pf, FrameOrder::PressureFirst),
            (tf, FrameOrder::TemperatureFirst),
        ] {
            assert_eq!(decode_frame::<()>(&frame, order), Ok(raw));
        }
    }

    #[test]
    fn a_corrupt_word_is_a_crc_error() {
        let raw = RawSample {
            p_lsb: 0x12_3456,
            t_lsb: 0x8000,
        };
        for byte in 0..FRAME_LEN {
            let mut frame = encode_frame(raw, FrameOrder::PressureFirst);
            frame[byte] ^= 0x10;
            assert!(matches!(
                decode_frame::<()>(&frame, FrameOrder::PressureFirst),
                Err(Error::Crc { .. })
            ));
        }
    }
}
