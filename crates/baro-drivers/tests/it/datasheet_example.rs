//! The worked example of the MS5611-01BA03 datasheet, and the PROM CRC-4 cases.

use baro_drivers::{Calibration, Measurement, Prom, PromError, crc4};

// MS5611-01BA03 datasheet (DA5611-01BA03), p. 7, "Pressure and temperature calculation",
// column "Example / Typical": C1 … C6, D1, D2 and every intermediate below.
const C: [u16; 6] = [40127, 36924, 23317, 23282, 33464, 28312];
const D1: u32 = 9_085_466;
const D2: u32 = 8_569_150;

#[test]
fn first_order_intermediates_match_the_datasheet_example() {
    let i = Calibration::new(C)
        .intermediates(D1, D2)
        .expect("24-bit codes");
    assert_eq!(i.dt, 2366);
    assert_eq!(i.temp, 2007);
    assert_eq!(i.off, 2_420_281_617);
    assert_eq!(i.sens, 1_315_097_036);
    assert_eq!(i.p, 100_009);
    // 20.07 °C is above 20 °C: the second-order terms are zero.
    assert_eq!((i.t2, i.off2, i.sens2), (0, 0, 0));
}

#[test]
fn example_compensates_to_20_07_celsius_and_1000_09_mbar() {
    let m = Calibration::new(C)
        .compensate(D1, D2)
        .expect("example is in range");
    assert_eq!(
        m,
        Measurement {
            temperature_centi_celsius: 2007,
            pressure_pa: 100_009
        }
    );
    assert!((m.temperature_celsius() - 20.07).abs() < 1e-4);
    assert!((m.pressure_mbar() - 1000.09).abs() < 1e-3);
}

/// D2 for a first-order TEMP of `temp` with the example coefficients (dT = (TEMP−2000)·2^23/C6).
fn d2_for_first_order(temp: i64) -> u32 {
    let dt = ((temp - 2000) << 23) / i64::from(C[5]);
    u32::try_from(i64::from(C[4]) * 256 + dt).expect("in 24 bits")
}

#[test]
fn below_20_celsius_uses_the_ms5611_second_order_terms() {
    // Datasheet p. 8: T2 = dT²/2^31, OFF2 = 5(TEMP−2000)²/2, SENS2 = 5(TEMP−2000)²/4.
    let i = Calibration::new(C)
        .intermediates(D1, d2_for_first_order(500))
        .expect("24-bit codes");
    let below = (i.temp - 2000).pow(2);
    assert!(i.temp < 2000 && i.temp >= -1500);
    assert_eq!(i.t2, i.dt * i.dt / (1 << 31));
    assert_eq!(i.off2, 5 * below / 2);
    assert_eq!(i.sens2, 5 * below / 4);
    // Not the MS5637 family's 3·dT²/2^33 and 61(TEMP−2000)²/2^4.
    assert_ne!(i.t2, 3 * i.dt * i.dt / (1 << 33));
    assert_ne!(i.off2, 61 * below / 16);
}

#[test]
fn below_minus_15_celsius_adds_the_very_low_terms() {
    // Datasheet p. 8: OFF2 += 7(TEMP+1500)², SENS2 += 11(TEMP+1500)²/2.
    let i = Calibration::new(C)
        .intermediates(D1, d2_for_first_order(-3000))
        .expect("24-bit codes");
    assert!(i.temp < -1500);
    let below = (i.temp - 2000).pow(2);
    let very = (i.temp + 1500).pow(2);
    assert_eq!(i.off2, 5 * below / 2 + 7 * very);
    assert_eq!(i.sens2, 5 * below / 4 + 11 * very / 2);
    assert_eq!(i.temperature(), i.temp - i.dt * i.dt / (1 << 31));
}

#[test]
fn negative_intermediates_are_floored_like_arithmetic_shifts() {
    // dT < 0 here, so C4·dT/2^7 must round towards −∞ (datasheet integer code uses shifts).
    let i = Calibration::new(C)
        .intermediates(D1, d2_for_first_order(1000))
        .expect("24-bit codes");
    assert!(i.dt < 0);
    let c4_dt = i64::from(C[3]) * i.dt;
    assert_eq!(i.off - (i64::from(C[1]) << 16), c4_dt.div_euclid(128));
}

fn example_prom() -> Prom {
    Prom::with_crc(0x0000, C, 0x123)
}

#[test]
fn good_crc_is_accepted_and_yields_the_coefficients() {
    let cal = example_prom().calibration().expect("valid CRC");
    assert_eq!(cal.coefficients(), C);
}

#[test]
fn any_flipped_bit_is_caught_by_the_crc() {
    let words = example_prom().words();
    // Every single-bit error in the CRC-covered bits (word 7's low byte is not covered).
    for word in 0..8 {
        for bit in 0..16 {
            if word == 7 && bit < 8 {
                continue;
            }
            let mut bad = words;
            bad[word] ^= 1 << bit;
            match Prom::from_words(bad).calibration() {
                Err(PromError::Crc { stored, computed }) => assert_ne!(stored, computed),
                other => panic!("word {word} bit {bit}: {other:?}"),
            }
        }
    }
}

#[test]
fn crc_follows_an520_on_a_known_image() {
    // An image worked by hand through AN520's loop: one byte 0x01 in the low byte of word 0
    // ends up shifted by 8 × 15 bytes of zeros, with polynomial 0x3000.
    let mut remainder: u32 = 0x01;
    for _ in 0..(8 * 15) {
        remainder = if remainder & 0x8000 != 0 {
            ((remainder << 1) ^ 0x3000) & 0xFFFF
        } else {
            (remainder << 1) & 0xFFFF
        };
    }
    let expected = ((remainder >> 12) & 0xF) as u8;
    assert_eq!(crc4(&[0x0001, 0, 0, 0, 0, 0, 0, 0]), expected);
}

#[test]
fn all_zero_prom_is_blank_even_though_its_crc_matches() {
    assert_eq!(crc4(&[0; 8]), 0);
    assert_eq!(
        Prom::from_words([0; 8]).calibration(),
        Err(PromError::Blank)
    );
}

#[test]
fn all_ones_prom_is_blank() {
    assert_eq!(
        Prom::from_words([0xFFFF; 8]).calibration(),
        Err(PromError::Blank)
    );
}

#[test]
fn bad_crc_nibble_is_reported_with_both_values() {
    let mut words = example_prom().words();
    let good = (words[7] & 0xF) as u8;
    words[7] = (words[7] & 0xFFF0) | u16::from(good ^ 0x5);
    assert_eq!(
        Prom::from_words(words).calibration(),
        Err(PromError::Crc {
            stored: good ^ 0x5,
            computed: good
        })
    );
}
