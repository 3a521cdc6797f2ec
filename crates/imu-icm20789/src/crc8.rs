//! CRC-8 that protects every 16-bit word the barometer sends (ID, OTP, measurement data).
//!
//! Polynomial x⁸ + x⁵ + x⁴ + 1 (0x31), initial value 0xFF, no reflection, no final XOR
//! (ICM-20789 datasheet DS-000169 §10, "checksum calculation"; the same CRC as the ICP-101xx).

/// CRC-8 (poly 0x31, init 0xFF) over `bytes`.
///
/// ```
/// // The known vector of the Sensirion/TDK CRC-8: [0xBE, 0xEF] → 0x92.
/// assert_eq!(imu_icm20789::crc8(&[0xBE, 0xEF]), 0x92);
/// ```
pub fn crc8(bytes: &[u8]) -> u8 {
    let mut crc = 0xFF_u8;
    for &byte in bytes {
        crc ^= byte;
        for _ in 0..8 {
            crc = if crc & 0x80 != 0 {
                (crc << 1) ^ 0x31
            } else {
                crc << 1
            };
        }
    }
    crc
}

/// A 16-bit word with its CRC byte as it travels on the bus: MSB, LSB, CRC.
pub(crate) fn encode_word(word: u16) -> [u8; 3] {
    let [msb, lsb] = word.to_be_bytes();
    [msb, lsb, crc8(&[msb, lsb])]
}

/// Checks one MSB, LSB, CRC triple; `Err((received, computed))` on a mismatch.
pub(crate) fn decode_word(bytes: [u8; 3]) -> Result<u16, (u8, u8)> {
    let computed = crc8(&bytes[..2]);
    if computed == bytes[2] {
        Ok(u16::from_be_bytes([bytes[0], bytes[1]]))
    } else {
        Err((bytes[2], computed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_vectors() {
        // Sensirion/TDK CRC-8 check value: CRC(0xBEEF) = 0x92.
        assert_eq!(crc8(&[0xBE, 0xEF]), 0x92);
        // The OTP-read setup command carries CRC(0x00, 0x66) = 0x9C (DS-000169 §10.4; TDK
        // reference code sends C5 95 00 66 9C).
        assert_eq!(crc8(&[0x00, 0x66]), 0x9C);
        assert_eq!(crc8(&[]), 0xFF);
    }

    #[test]
    fn words_round_trip_and_every_single_bit_flip_is_caught() {
        for word in [0x0000_u16, 0x0008, 0x1234, 0xBEEF, 0xFFFF] {
            let good = encode_word(word);
            assert_eq!(decode_word(good), Ok(word));
            for bit in 0..24 {
                let mut bad = good;
                bad[bit / 8] ^= 1 << (bit % 8);
                assert!(
                    decode_word(bad).is_err(),
                    "flip {bit} of {word:#06x} passed"
                );
            }
        }
    }
}
