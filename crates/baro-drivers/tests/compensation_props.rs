//! Property tests: the compensation is total over every 24-bit code and every PROM that
//! passes its CRC, and pressure never falls as D1 rises.

use baro_drivers::{CompensationError, Prom};
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
        let i = cal.intermediates(d1, d2);
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
    fn crc_rejects_any_other_nibble(prom in any_crc_valid_prom(), wrong in 1u16..16) {
        let mut words = prom.words();
        words[7] ^= wrong;
        prop_assert!(Prom::from_words(words).calibration().is_err());
    }
}
