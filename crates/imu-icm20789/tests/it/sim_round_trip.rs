//! Driver ↔ chip-model round trips: accel / gyro at every full scale, pressure 30…110 kPa in
//! every mode, conversion timing, bypass, FIFO, IDs, and the async driver.
#![cfg(feature = "sim")]

use embedded_hal::delay::DelayNs;
use embedded_hal::i2c::{ErrorKind, NoAcknowledgeSource};
use imu_icm20789::sim::{ChipModel, SimError, SimNoise, TrueState, Truth};
use imu_icm20789::{
    AccelScale, BaroMode, Error, FrameOrder, GyroDlpf, GyroScale, Icm20789, ImuAddress,
};

const NACK: Error<SimError> = Error::I2c(SimError(ErrorKind::NoAcknowledge(
    NoAcknowledgeSource::Address,
)));

fn started(chip: ChipModel) -> (Icm20789<ChipModel>, imu_icm20789::sim::SimDelay) {
    let mut delay = chip.delay();
    let mut icm = Icm20789::new_with_i2c(chip);
    icm.init(&mut delay).unwrap();
    icm.init_barometer(&mut delay).unwrap();
    (icm, delay)
}

#[test]
fn accel_and_gyro_round_trip_at_every_full_scale() {
    // 70 % of full scale with mixed signs on each axis; noise on (seeded).
    let mut worst_accel = [0.0_f32; 4];
    let mut worst_gyro = [0.0_f32; 4];
    for (i, (accel_fs, gyro_fs)) in AccelScale::ALL.into_iter().zip(GyroScale::ALL).enumerate() {
        let a = 0.7 * accel_fs.full_scale_g() * 9.806_65;
        let g = (0.7 * gyro_fs.full_scale_dps()).to_radians();
        let accel = [a, -0.5 * a, 0.25 * a];
        let gyro = [-g, 0.5 * g, -0.25 * g];
        let noise = SimNoise::default();
        let (mut icm, mut delay) = started(ChipModel::new(
            Truth::constant(accel, gyro, 101_325.0),
            11 + i as u64,
        ));
        icm.set_accel_scale(accel_fs).unwrap();
        icm.set_gyro_scale(gyro_fs).unwrap();
        for _ in 0..20 {
            delay.delay_ms(1); // a new 1 kHz sample each time
            let s = icm.read_imu().unwrap();
            for axis in 0..3 {
                let ea = (s.accel_mps2[axis] - accel[axis]).abs();
                let eg = (s.gyro_rps[axis] - gyro[axis]).abs();
                // One count plus 5 σ of the model's noise.
                assert!(
                    ea <= 9.806_65 / accel_fs.lsb_per_g() + 5.0 * noise.accel_mps2_rms,
                    "{accel_fs:?} {ea}"
                );
                assert!(
                    eg <= (1.0 / gyro_fs.lsb_per_dps()).to_radians() + 5.0 * noise.gyro_rps_rms,
                    "{gyro_fs:?} {eg}"
                );
                worst_accel[i] = worst_accel[i].max(ea);
                worst_gyro[i] = worst_gyro[i].max(eg);
            }
            assert!((s.temperature_c - 25.0).abs() < 0.01);
        }
    }
    println!("worst accel error per FS (m/s²): {worst_accel:?}; gyro (rad/s): {worst_gyro:?}");
}

#[test]
fn without_noise_accel_and_gyro_are_exact_to_half_a_count_and_saturate_beyond_full_scale() {
    for (accel_fs, gyro_fs) in AccelScale::ALL.into_iter().zip(GyroScale::ALL) {
        let a = 0.3 * accel_fs.full_scale_g() * 9.806_65;
        let g = (0.3 * gyro_fs.full_scale_dps()).to_radians();
        let over_a = 2.0 * accel_fs.full_scale_g() * 9.806_65;
        let chip = ChipModel::new(
            Truth::constant([a, over_a, -over_a], [g, 0.0, 0.0], 90_000.0),
            3,
        )
        .with_noise(SimNoise::NONE);
        let (mut icm, _) = started(chip);
        icm.set_accel_scale(accel_fs).unwrap();
        icm.set_gyro_scale(gyro_fs).unwrap();
        let raw = icm.read_imu_raw().unwrap();
        assert_eq!(raw.accel[1], i16::MAX);
        assert_eq!(raw.accel[2], i16::MIN);
        let s = icm.read_imu().unwrap();
        assert!((s.accel_mps2[0] - a).abs() <= 0.5 * 9.806_65 / accel_fs.lsb_per_g() + 1e-5);
        assert!(
            (s.gyro_rps[0] - g).abs() <= 0.5 * (1.0 / gyro_fs.lsb_per_dps()).to_radians() + 1e-6
        );
    }
}

#[test]
fn pressure_round_trips_from_30_to_110_kpa_in_every_mode_and_both_orders() {
    for (m, mode) in BaroMode::ALL.into_iter().enumerate() {
        let sigma = f64::from(mode.noise_pa_rms());
        let mut worst: f64 = 0.0;
        let mut sum_sq = 0.0;
        let mut n = 0.0;
        for kpa in (30_u32..=110).step_by(5) {
            let truth = f64::from(kpa) * 1_000.0;
            for (o, order) in [FrameOrder::PressureFirst, FrameOrder::TemperatureFirst]
                .into_iter()
                .enumerate()
            {
                let chip = ChipModel::new(
                    Truth::constant([0.0; 3], [0.0; 3], truth).at_temperature(31.0),
                    u64::from(kpa) * 8 + (m * 2 + o) as u64,
                );
                let (mut icm, mut delay) = started(chip);
                for _ in 0..4 {
                    let s = icm.measure_pressure(mode, order, &mut delay).unwrap();
                    let err = f64::from(s.pressure_pa) - truth;
                    // 5 σ of the mode's noise, plus f32 output rounding (≤ 0.008 Pa) and a code.
                    assert!(
                        err.abs() < 5.0 * sigma + 0.02,
                        "{mode:?} {order:?} {kpa} kPa: {err}"
                    );
                    assert!((s.temperature_c - 31.0).abs() < 0.003);
                    worst = worst.max(err.abs());
                    sum_sq += err * err;
                    n += 1.0;
                }
            }
        }
        let rms = (sum_sq / n).sqrt();
        // The spread is the mode's noise: within ±40 % of the datasheet σ over 136 samples.
        assert!(
            (0.6 * sigma..1.4 * sigma).contains(&rms),
            "{mode:?}: rms {rms} vs σ {sigma}"
        );
        println!("{mode:?}: worst |error| {worst:.3} Pa, rms {rms:.3} Pa (datasheet σ {sigma} Pa)");
    }
}

#[test]
fn without_noise_pressure_is_exact_to_a_hundredth_of_a_pascal_on_both_paths() {
    for kpa in (30..=110).step_by(10) {
        let truth = f64::from(kpa) * 1_000.0;
        let chip = ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], truth), 1)
            .with_noise(SimNoise::NONE);
        let (mut icm, mut delay) = started(chip);
        let s = icm
            .measure_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst, &mut delay)
            .unwrap();
        let cal = icm.calibration().unwrap();
        assert!((cal.pressure_pa(s.raw).unwrap() - truth).abs() < 0.01);
        assert!((cal.pressure_milli_pa(s.raw).unwrap() as f64 / 1_000.0 - truth).abs() < 0.01);
    }
}

#[test]
fn reading_before_the_conversion_ends_is_nacked_and_the_imu_can_be_read_meanwhile() {
    let chip = ChipModel::new(Truth::constant([0.0, 0.0, 9.81], [0.0; 3], 100_000.0), 5);
    let clock = chip.clock();
    let (mut icm, mut delay) = started(chip);
    for mode in BaroMode::ALL {
        let start = clock.now_ns();
        let conversion = icm.start_pressure(mode, FrameOrder::PressureFirst).unwrap();
        let imu = icm.read_imu().unwrap(); // overlap: the IMU is at another address
        assert!((imu.accel_mps2[2] - 9.81).abs() < 0.2);
        assert_eq!(icm.read_pressure(conversion), Err(NACK));
        // Typical time has passed: the model is done (the driver's wait_us is the maximum).
        let elapsed_us = (clock.now_ns() - start) / 1_000;
        delay.delay_us(mode.conversion_time_typ_us() - elapsed_us as u32);
        let s = icm.read_pressure(conversion).unwrap();
        assert!(
            (f64::from(s.pressure_pa) - 100_000.0).abs() < 5.0 * f64::from(mode.noise_pa_rms())
        );
        // The frame is consumed: a second read has nothing to return.
        assert_eq!(icm.read_pressure(conversion), Err(NACK));
    }
}

/// A non-finite truth is NACKed: a NaN temperature must not read as code 0, nor an infinite
/// pressure as the pole's code.
#[test]
fn a_non_finite_truth_is_nacked_not_turned_into_a_sample() {
    let bad = [
        Truth::constant([0.0; 3], [0.0; 3], f64::NAN),
        Truth::constant([0.0; 3], [0.0; 3], f64::INFINITY),
        Truth::constant([0.0; 3], [0.0; 3], 100_000.0).at_temperature(f32::NAN),
    ];
    for truth in bad {
        let chip = ChipModel::new(truth, 3).with_noise(SimNoise::NONE);
        let (mut icm, mut delay) = started(chip);
        assert_eq!(
            icm.measure_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst, &mut delay),
            Err(NACK)
        );
    }
    // Beyond the temperature ADC's range the model saturates its code, as before.
    let hot = Truth::constant([0.0; 3], [0.0; 3], 100_000.0).at_temperature(150.0);
    let chip = ChipModel::new(hot, 3).with_noise(SimNoise::NONE);
    let (mut icm, mut delay) = started(chip);
    let s = icm
        .measure_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst, &mut delay)
        .unwrap();
    assert_eq!(s.raw.t_lsb, u16::MAX);
    assert!((f64::from(s.pressure_pa) - 100_000.0).abs() < 1.0);
}

#[test]
fn the_barometer_needs_bypass_and_ids_are_checked() {
    let chip = ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], 100_000.0), 1);
    let mut icm = Icm20789::new_with_i2c(chip);
    assert_eq!(icm.barometer_id(), Err(NACK)); // bypass off after power-up
    icm.enable_bypass().unwrap();
    assert_eq!(icm.barometer_id().map(|id| id & 0x3F), Ok(0x08));

    let wrong_baro =
        ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], 1e5), 1).with_baro_id(0x0147);
    let mut delay = wrong_baro.delay();
    let mut icm = Icm20789::new_with_i2c(wrong_baro);
    assert_eq!(
        icm.init_barometer(&mut delay),
        Err(Error::WrongBaroId(0x0147))
    );

    let r1 = ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], 1e5), 1)
        .with_who_am_i(0x02)
        .with_imu_address(ImuAddress::Ad0High);
    let mut delay = r1.delay();
    let mut icm = Icm20789::new_with_i2c_address(r1, ImuAddress::Ad0High);
    assert_eq!(icm.init(&mut delay), Ok(0x02));
    let wrong = ChipModel::new(Truth::constant([0.0; 3], [0.0; 3], 1e5), 1).with_who_am_i(0x70);
    let mut delay = wrong.delay();
    assert_eq!(
        Icm20789::new_with_i2c(wrong).init(&mut delay),
        Err(Error::WrongImuId(0x70))
    );
}

#[test]
fn the_imu_reads_zero_until_woken() {
    let chip = ChipModel::new(Truth::constant([0.0, 0.0, 9.81], [0.0; 3], 1e5), 1)
        .with_noise(SimNoise::NONE);
    let mut delay = chip.delay();
    let mut icm = Icm20789::new_with_i2c(chip);
    assert_eq!(icm.read_imu_raw().unwrap().accel, [0, 0, 0]); // asleep after power-up (0x41)
    icm.init(&mut delay).unwrap();
    assert_eq!(icm.read_imu_raw().unwrap().accel[2], 16_390); // round(9.81 / 9.80665 · 16384)
}

#[test]
fn the_fifo_collects_one_record_per_sample_period() {
    // DLPF 41 Hz with divider 9: 100 Hz. A ramp in x lets each record be told apart.
    let env = |t_us: u64| TrueState {
        accel_mps2: [t_us as f32 * 1e-4, 0.0, 9.81],
        gyro_rps: [0.0, 0.0, 0.5],
        pressure_pa: 1e5,
        temperature_c: 25.0,
    };
    let chip = ChipModel::new(env, 9).with_noise(SimNoise::NONE);
    let (mut icm, mut delay) = started(chip);
    icm.set_accel_scale(AccelScale::G8).unwrap();
    icm.set_gyro_dlpf(GyroDlpf::Hz41).unwrap();
    icm.set_sample_rate_divider(9).unwrap();
    icm.enable_fifo().unwrap();
    assert_eq!(icm.fifo_count(), Ok(0));
    delay.delay_ms(50);
    let count = icm.fifo_count().unwrap();
    assert!(
        (4 * 12..=5 * 12).contains(&count),
        "{count} bytes after 50 ms at 100 Hz"
    );
    let mut previous = f32::NEG_INFINITY;
    for _ in 0..count / 12 {
        let r = icm.read_fifo_record().unwrap();
        // Ramp 1 m/s² per 10 ms: consecutive records 10 ms apart differ by 1 m/s².
        if previous.is_finite() {
            assert!(
                (r.accel_mps2[0] - previous - 1.0).abs() < 0.01,
                "{} after {previous}",
                r.accel_mps2[0]
            );
        }
        previous = r.accel_mps2[0];
        assert!((r.gyro_rps[2] - 0.5).abs() < 0.001);
    }
    assert_eq!(icm.fifo_count(), Ok(count % 12));
}

#[cfg(feature = "async")]
#[test]
fn the_async_driver_does_the_same_sample() {
    use crate::common::block_on;
    use imu_icm20789::Icm20789Async;
    let chip = ChipModel::new(
        Truth::constant([1.0, 2.0, 9.0], [0.1, 0.0, 0.0], 95_000.0),
        2,
    )
    .with_noise(SimNoise::NONE);
    let mut delay = chip.delay();
    let mut icm = Icm20789Async::new_with_i2c(chip);
    block_on(async {
        icm.init(&mut delay).await.unwrap();
        icm.set_accel_scale(AccelScale::G16).await.unwrap();
        icm.init_barometer(&mut delay).await.unwrap();
        let conversion = icm
            .start_pressure(BaroMode::Normal, FrameOrder::TemperatureFirst)
            .await
            .unwrap();
        let imu = icm.read_imu().await.unwrap();
        embedded_hal_async::delay::DelayNs::delay_us(&mut delay, conversion.wait_us()).await;
        let baro = icm.read_pressure(conversion).await.unwrap();
        assert!((imu.accel_mps2[1] - 2.0).abs() < 0.005);
        assert!((imu.gyro_rps[0] - 0.1).abs() < 0.001);
        assert!((baro.pressure_pa - 95_000.0).abs() < 0.02);
    });
}
