//! Command bytes of the MS5611 (datasheet p. 9, "Commands"): the chip has no registers,
//! every transfer starts with one of these.

use crate::osr::Osr;

/// Reset: reloads the PROM into the internal register (takes [`RESET_TIME_NS`]).
pub(crate) const RESET: u8 = 0x1E;
/// Convert D1 (uncompensated pressure); OR the OSR offset in.
pub(crate) const CONVERT_D1: u8 = 0x40;
/// Convert D2 (uncompensated temperature); OR the OSR offset in.
pub(crate) const CONVERT_D2: u8 = 0x50;
/// Read the 24-bit ADC result of the last conversion.
pub(crate) const ADC_READ: u8 = 0x00;
/// Read PROM word 0 … 7 at `PROM_READ | (index << 1)`.
pub(crate) const PROM_READ: u8 = 0xA0;

/// Time the chip needs after the reset command (0x1E) before it answers again (datasheet: 2.8 ms).
pub const RESET_TIME_NS: u32 = 2_800_000;

/// The command starting a D1 conversion at `osr`.
pub(crate) const fn convert_d1(osr: Osr) -> u8 {
    CONVERT_D1 | osr.command_offset()
}

/// The command starting a D2 conversion at `osr`.
pub(crate) const fn convert_d2(osr: Osr) -> u8 {
    CONVERT_D2 | osr.command_offset()
}

/// The command reading PROM word `index` (0 … 7).
pub(crate) const fn prom_read(index: u8) -> u8 {
    PROM_READ | ((index & 0x07) << 1)
}

/// What a command byte asks the chip to do; the chip model decodes with this too, so the
/// driver and the model cannot disagree on the encoding.
#[cfg(feature = "sim")]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decoded {
    Reset,
    ConvertD1(Osr),
    ConvertD2(Osr),
    AdcRead,
    PromRead(u8),
}

#[cfg(feature = "sim")]
pub(crate) fn decode(byte: u8) -> Option<Decoded> {
    let osr_of = |b: u8| {
        Osr::ALL
            .into_iter()
            .find(|o| o.command_offset() == b & 0x0F)
    };
    match byte {
        RESET => Some(Decoded::Reset),
        ADC_READ => Some(Decoded::AdcRead),
        b if b & 0xF0 == CONVERT_D1 => osr_of(b).map(Decoded::ConvertD1),
        b if b & 0xF0 == CONVERT_D2 => osr_of(b).map(Decoded::ConvertD2),
        b if b & 0xF1 == PROM_READ => Some(Decoded::PromRead((b >> 1) & 0x07)),
        _ => None,
    }
}
