//! Driver ↔ chip model over I2C and SPI across the datasheet range (10 … 1200 mbar,
//! −40 … 85 °C), for every OSR.

use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock, SimError, Tca9548aSim};
use baro_drivers::{Address, Error, Measurement, Ms5611, Osr, Prom, PromError};

const PRESSURES_MBAR: [f64; 8] = [10.0, 100.0, 300.0, 600.0, 900.0, 1013.25, 1100.0, 1200.0];
const TEMPERATURES_C: [f64; 8] = [-40.0, -20.0, -15.2, 0.0, 19.95, 20.0, 45.5, 85.0];

#[derive(Clone, Copy)]
enum Link {
    I2c,
    Spi,
}

fn measure(link: Link, truth: Conditions, osr: Osr, noise: bool, seed: u64) -> Measurement {
    let clock = SimClock::new();
    let mut delay = clock.delay();
    let chip = Ms5611Sim::new(truth, clock)
        .with_noise(noise)
        .with_seed(seed);
    match link {
        Link::I2c => Ms5611::new_with_i2c(chip, Address::CsbLow)
            .init(&mut delay)
            .map_err(|e| e.error)
            .and_then(|mut b| b.measure(&mut delay, osr)),
        Link::Spi => Ms5611::new_with_spi(chip)
            .init(&mut delay)
            .map_err(|e| e.error)
            .and_then(|mut b| b.measure(&mut delay, osr)),
    }
    .expect("in-range conditions measure")
}

/// Worst |error| in Pa and 0.01 °C, and the RMS pressure error, over the grid.
fn sweep(link: Link, osr: Osr, noise: bool) -> (f64, f64, f64) {
    let (mut worst_p, mut worst_t, mut sum_sq, mut n) = (0.0f64, 0.0f64, 0.0, 0.0);
    for (i, &p) in PRESSURES_MBAR.iter().enumerate() {
        for (j, &t) in TEMPERATURES_C.iter().enumerate() {
            let truth = Conditions {
                pressure_mbar: p,
                temperature_celsius: t,
            };
            let m = measure(link, truth, osr, noise, (i * 31 + j) as u64);
            let ep = f64::from(m.pressure_pa) - p * 100.0;
            let et = f64::from(m.temperature_centi_celsius) - t * 100.0;
            worst_p = worst_p.max(ep.abs());
            worst_t = worst_t.max(et.abs());
            sum_sq += ep * ep;
            n += 1.0;
        }
    }
    (worst_p, worst_t, (sum_sq / n).sqrt())
}

#[test]
fn without_noise_the_round_trip_is_exact_to_the_output_resolution() {
    for link in [Link::I2c, Link::Spi] {
        let (p, t, _) = sweep(link, Osr::Osr4096, false);
        // Integer Pa and 0.01 °C outputs: at most one unit off (rounding, then a floor).
        assert!(p <= 1.0, "pressure off by {p} Pa");
        assert!(t <= 1.0, "temperature off by {t} centi-°C");
    }
}

#[test]
fn with_noise_every_osr_stays_within_its_datasheet_resolution() {
    for link in [Link::I2c, Link::Spi] {
        for osr in Osr::ALL {
            let sigma_p = f64::from(osr.pressure_noise_rms_mbar()) * 100.0;
            let sigma_t = f64::from(osr.temperature_noise_rms_celsius()) * 100.0;
            let (p, t, rms) = sweep(link, osr, true);
            println!(
                "{osr:?}: worst {p:.1} Pa (σ {sigma_p:.1}), {t:.1} c°C (σ {sigma_t:.1}), rms {rms:.2} Pa"
            );
            // Temperature noise also moves the compensated pressure (about 1.9 Pa per 0.01 °C
            // with the example PROM), hence the allowance beyond σ_p.
            let allowed_p = 5.0 * (sigma_p.powi(2) + (1.9 * sigma_t).powi(2)).sqrt() + 1.0;
            assert!(p <= allowed_p, "{osr:?}: {p} Pa > {allowed_p}");
            assert!(t <= 5.0 * sigma_t + 1.0, "{osr:?}: {t} c°C");
            assert!(rms <= 2.0 * sigma_p + 1.0, "{osr:?}: rms {rms}");
        }
    }
}

#[test]
fn a_noisier_osr_really_is_noisier() {
    let (_, _, rms_fast) = sweep(Link::Spi, Osr::Osr256, true);
    let (_, _, rms_slow) = sweep(Link::Spi, Osr::Osr4096, true);
    assert!(rms_fast > 2.0 * rms_slow, "{rms_fast} vs {rms_slow}");
}

/// Non-finite conditions are refused: NaN °C must not become the code for 0.00 °C, a plausible
/// reading.
#[test]
fn non_finite_conditions_are_refused_not_turned_into_a_code() {
    for (pressure_mbar, temperature_celsius) in [
        (1013.25, f64::NAN),
        (f64::NAN, 20.0),
        (f64::INFINITY, 20.0),
        (1013.25, f64::NEG_INFINITY),
    ] {
        let clock = SimClock::new();
        let mut delay = clock.delay();
        let air = Conditions {
            pressure_mbar,
            temperature_celsius,
        };
        let mut baro = Ms5611::new_with_i2c(Ms5611Sim::new(air, clock), Address::CsbLow)
            .init(&mut delay)
            .map_err(|e| e.error)
            .unwrap();
        assert_eq!(
            baro.measure(&mut delay, Osr::Osr256),
            Err(Error::Comm(SimError::NonFiniteConditions)),
            "{air:?}"
        );
    }
}

#[test]
fn reading_before_the_conversion_ends_returns_zero_like_the_chip() {
    let clock = SimClock::new();
    let mut delay = clock.delay();
    let truth = Conditions {
        pressure_mbar: 950.0,
        temperature_celsius: 30.0,
    };
    let chip = Ms5611Sim::new(truth, clock.clone());
    let mut baro = Ms5611::new_with_spi(chip)
        .init(&mut delay)
        .map_err(|e| e.error)
        .unwrap();
    baro.start_temperature(Osr::Osr4096).unwrap();
    clock.advance_ns(9_000_000); // typ 8.22 ms < 9.0 ms < max 9.04 ms: the model takes the max
    assert_eq!(baro.read_result(), Err(Error::AdcNotReady));
    // The early read spoiled that conversion; a fresh one, waited out, works.
    baro.start_temperature(Osr::Osr4096).unwrap();
    clock.advance_ns(9_040_000);
    assert!(baro.read_result().is_ok());
}

#[test]
fn a_corrupt_prom_in_the_model_is_caught_by_the_driver() {
    let clock = SimClock::new();
    let mut words = Prom::with_crc(0, baro_drivers::sim::DATASHEET_COEFFICIENTS, 1).words();
    words[5] ^= 0x0004;
    let truth = Conditions {
        pressure_mbar: 1000.0,
        temperature_celsius: 20.0,
    };
    let chip = Ms5611Sim::new(truth, clock.clone()).with_prom(Prom::from_words(words));
    let err = Ms5611::new_with_i2c(chip, Address::CsbLow)
        .init(&mut clock.delay())
        .expect_err("bad CRC");
    assert!(matches!(err.error, Error::Prom(PromError::Crc { .. })));
}

#[test]
fn a_wrong_address_is_a_nack() {
    let clock = SimClock::new();
    let truth = Conditions {
        pressure_mbar: 1000.0,
        temperature_celsius: 20.0,
    };
    let chip = Ms5611Sim::new(truth, clock.clone()).with_address(Address::CsbHigh);
    let err = Ms5611::new_with_i2c(chip, Address::CsbLow)
        .init(&mut clock.delay())
        .expect_err("nobody at 0x77");
    assert_eq!(err.error, Error::Comm(SimError::NoAcknowledgeAddress(0x77)));
}

#[test]
fn through_a_tca9548a_each_channel_reaches_its_own_chip() {
    let clock = SimClock::new();
    let mut delay = clock.delay();
    let mut mux = Tca9548aSim::new(0x70, clock.clone(), BusTiming::default());
    for ch in 0..3u8 {
        let truth = Conditions {
            pressure_mbar: 900.0 + 50.0 * f64::from(ch),
            temperature_celsius: 10.0 * f64::from(ch),
        };
        mux = mux.attach(ch, Ms5611Sim::new(truth, clock.clone()).with_noise(false));
    }
    let switch = xca9548a::Xca9548a::new(mux, xca9548a::SlaveAddr::default());
    let parts = switch.split();
    for (ch, port) in [parts.i2c0, parts.i2c1, parts.i2c2].into_iter().enumerate() {
        let mut baro = Ms5611::new_with_i2c(port, Address::CsbLow)
            .init(&mut delay)
            .map_err(|e| e.error)
            .unwrap();
        let m = baro.measure(&mut delay, Osr::Osr1024).unwrap();
        assert!((m.pressure_mbar() - (900.0 + 50.0 * ch as f32)).abs() <= 0.011);
        assert!((m.temperature_celsius() - 10.0 * ch as f32).abs() <= 0.011);
    }
}
