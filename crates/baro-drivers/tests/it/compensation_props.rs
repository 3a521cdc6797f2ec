//! Property tests: the compensation is total over every 24-bit code and every PROM that
//! passes its CRC, pressure never falls as D1 rises, and a code above 24 bits is refused.

use baro_drivers::{CODE_MAX, Calibration, CompensationError, Error, Prom};
use proptest::prelude::*;

fn any_crc_valid_prom() -> impl Strategy<Value = Prom> {
    (any::<u16>(), any::<[u16; 6]>(), 0u16..0x1000)
        .prop_map(|(factory, c, serial)| Prom::with_crc(factory, c, serial))
        .prop_filter("blank images are refused", |p| p.calibration().is_ok())
}

const CODE: core::ops::RangeInclusive<u32> = 0..=0x00FF_FFFF;

proptest! {
    #[test]
    fn never_overflows_or_panics(prom in any_crc_valid_prom(), d1 in CODE, d2 in CODE) {
        let cal = prom.calibration().expect("filtered to valid");
        // Debug-checked arithmetic would panic on overflow; the release profile would wrap,
        // so also check the result against the no-overflow bounds.
        let i = cal.intermediates(d1, d2).expect("24-bit codes");
        prop_assert!(i.temp.abs() < 1 << 18);
        prop_assert!(i.temperature().abs() < 1 << 18);
        match cal.compensate(d1, d2) {
            Ok(m) => {
                prop_assert!(i.sens - i.sens2 > 0);
                prop_assert_eq!(i64::from(m.pressure_pa), i.p);
                prop_assert_eq!(i64::from(m.temperature_centi_celsius), i.temperature());
            }
            Err(CompensationError::NonPositiveSensitivity) => prop_assert!(i.sens - i.sens2 <= 0),
            Err(e) => prop_assert!(false, "unexpected {e:?}"),
        }
    }

    #[test]
    fn pressure_is_monotonic_in_d1(prom in any_crc_valid_prom(), a in CODE, b in CODE, d2 in CODE) {
        let cal = prom.calibration().expect("filtered to valid");
        let (lo, hi) = (a.min(b), a.max(b));
        // Validity depends on D2 only, so both succeed or both fail.
        match (cal.compensate(lo, d2), cal.compensate(hi, d2)) {
            (Ok(p_lo), Ok(p_hi)) => prop_assert!(p_lo.pressure_pa <= p_hi.pressure_pa),
            (Err(_), Err(_)) => {}
            (x, y) => prop_assert!(false, "validity changed with D1: {:?} {:?}", x, y),
        }
    }

    #[test]
    fn every_code_above_24_bits_is_refused(
        prom in any_crc_valid_prom(),
        wide in (CODE_MAX + 1)..=u32::MAX,
        code in CODE,
    ) {
        let cal = prom.calibration().expect("filtered to valid");
        let refused = Err(CompensationError::CodeOutOfRange { code: wide, max: CODE_MAX });
        prop_assert_eq!(cal.compensate(wide, code), refused);
        prop_assert_eq!(cal.compensate(code, wide), refused);
        prop_assert_eq!(cal.intermediates(wide, code).map(|_| ()), refused.map(|_| ()));
    }

    #[test]
    fn crc_rejects_any_other_nibble(prom in any_crc_valid_prom(), wrong in 1u16..16) {
        let mut words = prom.words();
        words[7] ^= wrong;
        prop_assert!(Prom::from_words(words).calibration().is_err());
    }
}

/// The datasheet's example coefficients and D2 (20.07 °C).
const C: [u16; 6] = [40127, 36924, 23317, 23282, 33464, 28312];
const D2: u32 = 8_569_150;

/// A 25-bit D1 is refused, not compensated as if it were 0 (`0x1000000 & 0xFFFFFF`).
#[test]
fn a_25_bit_d1_is_an_error_not_masked_to_zero() {
    let cal = Calibration::new(C);
    let refused = CompensationError::CodeOutOfRange {
        code: 0x100_0000,
        max: 0xFF_FFFF,
    };
    assert_eq!(cal.compensate(0x100_0000, D2), Err(refused));
    assert_eq!(cal.compensate(9_085_466, 0x100_0000), Err(refused));
    assert!(cal.compensate(0, D2) != cal.compensate(0x100_0000, D2));
    assert_eq!(
        refused.to_string(),
        "ADC code 0x1000000 is above the 24-bit maximum 0xffffff"
    );
    // Through the driver's error, as a caller prints it.
    assert_eq!(
        Error::<()>::from(refused).to_string(),
        "ADC code 0x1000000 is above the 24-bit maximum 0xffffff"
    );
}

#[test]
fn the_24_bit_boundary_2_pow_24_minus_1_is_accepted_2_pow_24_refused() {
    let cal = Calibration::new(C);
    assert_eq!(CODE_MAX, (1 << 24) - 1);
    // The top code compensates (to a pressure far above the chip's range, but defined).
    assert!(cal.compensate(CODE_MAX, D2).is_ok());
    assert!(cal.intermediates(D2, CODE_MAX).is_ok());
    for (d1, d2) in [(CODE_MAX + 1, D2), (D2, CODE_MAX + 1)] {
        assert_eq!(
            cal.compensate(d1, d2),
            Err(CompensationError::CodeOutOfRange {
                code: 1 << 24,
                max: CODE_MAX
            })
        );
    }
}
