//! The 128-bit factory PROM: six calibration coefficients guarded by a 4-bit CRC.

use crate::compensation::Calibration;

/// Why a PROM image was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum PromError {
    /// The CRC-4 stored in the low nibble of word 7 does not match the words read.
    Crc {
        /// CRC read from the chip.
        stored: u8,
        /// CRC computed over the words read.
        computed: u8,
    },
    /// Every word read as 0x0000 or every word as 0xFFFF: the bus line is stuck, no chip
    /// answered. (An all-zero image even has a matching CRC, so the CRC alone misses it.)
    Blank,
}

/// The eight 16-bit PROM words as read (word 0: factory data, 1 … 6: C1 … C6, 7: serial
/// code and CRC).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Prom {
    words: [u16; 8],
}

impl Prom {
    /// Wraps eight words read from the chip, without checking them.
    pub const fn from_words(words: [u16; 8]) -> Self {
        Self { words }
    }

    /// Builds an image holding `coefficients` (C1 … C6) with word 0 = `factory`, the upper
    /// 12 bits of word 7 = `serial`, and a valid CRC: what a factory-programmed chip holds.
    pub fn with_crc(factory: u16, coefficients: [u16; 6], serial: u16) -> Self {
        let mut words = [0u16; 8];
        words[0] = factory;
        words[1..7].copy_from_slice(&coefficients);
        words[7] = serial << 4;
        words[7] |= u16::from(crc4(&words));
        Self { words }
    }

    /// The raw words.
    pub const fn words(&self) -> [u16; 8] {
        self.words
    }

    /// The CRC stored in the low nibble of word 7.
    pub const fn stored_crc(&self) -> u8 {
        (self.words[7] & 0x000F) as u8
    }

    /// Checks the image and extracts the calibration coefficients.
    pub fn calibration(&self) -> Result<Calibration, PromError> {
        if self.words.iter().all(|&w| w == 0) || self.words.iter().all(|&w| w == 0xFFFF) {
            return Err(PromError::Blank);
        }
        let computed = crc4(&self.words);
        if computed != self.stored_crc() {
            return Err(PromError::Crc {
                stored: self.stored_crc(),
                computed,
            });
        }
        let w = &self.words;
        Ok(Calibration::new([w[1], w[2], w[3], w[4], w[5], w[6]]))
    }
}

/// CRC-4 of a PROM image exactly as Application Note AN520 computes it: each of the 16 bytes
/// (most significant first) is XORed into the *low* byte of a 16-bit remainder, which is then
/// shifted eight times with polynomial 0x3000 applied on carry out of bit 15; the low byte of
/// word 7 (serial tail and the CRC itself) is taken as zero.
pub fn crc4(words: &[u16; 8]) -> u8 {
    let mut remainder: u16 = 0;
    for (i, &word) in words.iter().enumerate() {
        // The CRC's own nibble (low byte of word 7 in AN520) does not take part.
        let word = if i == 7 { word & 0xFF00 } else { word };
        for byte in word.to_be_bytes() {
            remainder ^= u16::from(byte);
            for _ in 0..8 {
                remainder = if remainder & 0x8000 != 0 {
                    (remainder << 1) ^ 0x3000
                } else {
                    remainder << 1
                };
            }
        }
    }
    ((remainder >> 12) & 0x000F) as u8
}
