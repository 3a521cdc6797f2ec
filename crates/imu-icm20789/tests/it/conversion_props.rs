//! proptest: every 24-bit p_LSB, 16-bit T_LSB and OTP set that passes its CRC converts to a
//! finite pressure or to a typed error — never a panic or a non-finite value — and every code
//! above 24 bits is refused.

use imu_icm20789::{Calibration, ConversionError, P_LSB_MAX, RawSample, crc8};
use proptest::prelude::*;

/// OTP reads as the bus delivers them: any data bytes with their correct CRC.
fn otp_reads() -> impl Strategy<Value = [[u8; 3]; 4]> {
    any::<[[u8; 2]; 4]>().prop_map(|words| words.map(|[m, l]| [m, l, crc8(&[m, l])]))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4_000, ..ProptestConfig::default() })]

    #[test]
    fn every_pressure_code_above_24_bits_is_refused(
        reads in otp_reads(),
        p_lsb in (P_LSB_MAX + 1)..=u32::MAX,
        t_lsb in any::<u16>(),
    ) {
        let cal = Calibration::from_otp_reads::<()>(reads).expect("CRCs are valid by construction");
        let raw = RawSample { p_lsb, t_lsb };
        let refused = ConversionError::CodeOutOfRange { code: p_lsb, max: P_LSB_MAX };
        prop_assert_eq!(cal.pressure_pa(raw), Err(refused));
        prop_assert_eq!(cal.pressure_milli_pa(raw), Err(refused));
    }

    #[test]
    fn any_crc_valid_otp_any_codes_give_finite_pressure_or_typed_error(
        reads in otp_reads(),
        p_lsb in 0_u32..(1 << 24),
        t_lsb in any::<u16>(),
    ) {
        let cal = Calibration::from_otp_reads::<()>(reads).expect("CRCs are valid by construction");
        let raw = RawSample { p_lsb, t_lsb };
        let float = cal.pressure_pa(raw);
        let int = cal.pressure_milli_pa(raw);
        match float {
            Ok(p) => prop_assert!(p.is_finite()),
            Err(e) => prop_assert!(matches!(e, ConversionError::DegenerateCalibration | ConversionError::Pole | ConversionError::OutOfRange)),
        }
        // The two paths agree on whether the calibration is degenerate (same integer check).
        prop_assert_eq!(
            float == Err(ConversionError::DegenerateCalibration),
            int == Err(ConversionError::DegenerateCalibration)
        );
        if let (Ok(f), Ok(i)) = (float, int) {
            // Both finite; where the result is physical they agree to the integer's rounding.
            if (1_000.0..1_000_000.0).contains(&f) {
                prop_assert!((f - i as f64 / 1_000.0).abs() <= 0.01, "{} vs {}", f, i);
            }
        }
    }

    #[test]
    fn fractional_codes_near_the_lut_points_never_panic(
        otp in any::<[i16; 4]>(),
        t_lsb in any::<u16>(),
        offset in -(1_i64 << 40)..(1_i64 << 40),
    ) {
        if let Ok(lut) = Calibration::from_otp(otp).lut_points(t_lsb) {
            for x in lut.scaled() {
                let _ = lut.pressure_milli_pa_scaled(x + offset);
                if let Ok(abc) = lut.coefficients() {
                    if let Ok(p) = abc.pressure_pa((x + offset) as f64 / f64::from(1 << 24)) {
                        prop_assert!(p.is_finite());
                    }
                }
            }
        }
    }
}
