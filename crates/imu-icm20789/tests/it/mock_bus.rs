//! Every register write and read the driver does, checked byte for byte with embedded-hal-mock.

use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::delay::{CheckedDelay, Transaction as D};
use embedded_hal_mock::eh1::i2c::{Mock, Transaction as T};
use imu_icm20789::{
    AccelDlpf, AccelScale, BaroMode, Calibration, Error, FrameOrder, GyroDlpf, GyroScale, Icm20789,
    ImuAddress, RawSample, crc8,
};

const IMU: u8 = 0x68;
const BARO: u8 = 0x63;

fn word(w: u16) -> Vec<u8> {
    let [m, l] = w.to_be_bytes();
    vec![m, l, crc8(&[m, l])]
}

fn check(expectations: &[T], run: impl FnOnce(&mut Icm20789<Mock>)) {
    let mut icm = Icm20789::new_with_i2c(Mock::new(expectations));
    run(&mut icm);
    icm.destroy().done();
}

#[test]
fn who_am_i_accepts_the_part_and_its_r1_revision_and_rejects_others() {
    for (id, expected) in [
        (0x03, Ok(0x03)),
        (0x02, Ok(0x02)),
        (0x12, Err(Error::WrongImuId(0x12))),
    ] {
        check(&[T::write_read(IMU, vec![0x75], vec![id])], |icm| {
            assert_eq!(icm.who_am_i(), expected);
        });
    }
}

#[test]
fn the_ad0_high_address_is_used() {
    let mut icm = Icm20789::new_with_i2c_address(
        Mock::new(&[T::write_read(0x69, vec![0x75], vec![0x03])]),
        ImuAddress::Ad0High,
    );
    assert_eq!(icm.who_am_i(), Ok(0x03));
    icm.destroy().done();
}

#[test]
fn init_checks_id_resets_waits_100_ms_and_wakes() {
    let mut delay = CheckedDelay::new(&[D::delay_us(100_000)]);
    check(
        &[
            T::write_read(IMU, vec![0x75], vec![0x03]),
            T::write(IMU, vec![0x6B, 0x80]), // DEVICE_RESET
            T::write(IMU, vec![0x6B, 0x01]), // awake, CLKSEL = auto
            T::write(IMU, vec![0x6C, 0x00]), // all axes on
        ],
        |icm| assert_eq!(icm.init(&mut delay), Ok(0x03)),
    );
    delay.done();
}

#[test]
fn settings_write_their_fields_and_keep_the_others() {
    check(
        &[
            T::write(IMU, vec![0x1C, 0b1_1000]), // ±16 g
            T::write(IMU, vec![0x1C, 0b0_1000]), // ±4 g
            T::write(IMU, vec![0x1B, 0b1_0000]), // ±1000 °/s
            T::write(IMU, vec![0x1A, 0x03]),     // gyro DLPF 41 Hz
            T::write(IMU, vec![0x1D, 0x03]),     // accel DLPF 44.8 Hz (A_DLPF_CFG 3)
            T::write(IMU, vec![0x19, 32]),       // 1 kHz / 33 ≈ 30 Hz, the pad's rate
            T::write(IMU, vec![0x1B, 0b1_1000]), // ±2000 °/s
        ],
        |icm| {
            icm.set_accel_scale(AccelScale::G16).unwrap();
            icm.set_accel_scale(AccelScale::G4).unwrap();
            icm.set_gyro_scale(GyroScale::Dps1000).unwrap();
            icm.set_gyro_dlpf(GyroDlpf::Hz41).unwrap();
            icm.set_accel_dlpf(AccelDlpf::Hz45).unwrap();
            icm.set_sample_rate_divider(32).unwrap();
            icm.set_gyro_scale(GyroScale::Dps2000).unwrap();
        },
    );
}

#[test]
fn one_14_byte_burst_is_scaled_to_si_units() {
    // +1 g on z at ±2 g (16 384 LSB/g), −1 g on x; 131 LSB = 1 °/s at ±250 °/s;
    // TEMP 0 LSB = 25 °C, 3268 LSB = 35 °C (326.8 LSB/°C).
    let mut burst = vec![];
    for w in [-16_384_i16, 0, 16_384, 3_268, 131, -262, 0] {
        burst.extend_from_slice(&w.to_be_bytes());
    }
    check(&[T::write_read(IMU, vec![0x3B], burst)], |icm| {
        let s = icm.read_imu().unwrap();
        assert_eq!(s.accel_mps2, [-9.806_65, 0.0, 9.806_65]);
        let one_dps = 1.0_f32.to_radians();
        assert!(
            (s.gyro_rps[0] - one_dps).abs() < 1e-7 && (s.gyro_rps[1] + 2.0 * one_dps).abs() < 1e-7
        );
        assert!((s.temperature_c - 35.0).abs() < 1e-4);
    });
}

#[test]
fn fifo_enable_count_and_record_read() {
    let mut record = vec![];
    for w in [0_i16, 0, 8_192, 0, 0, 655] {
        record.extend_from_slice(&w.to_be_bytes());
    }
    check(
        &[
            T::write(IMU, vec![0x1C, 0b0_1000]), // ±4 g: 8 192 LSB/g
            T::write(IMU, vec![0x23, 0x78]),     // gyro xyz + accel into the FIFO
            T::write(IMU, vec![0x6A, 0x44]),     // FIFO_EN + FIFO_RST
            T::write_read(IMU, vec![0x72], vec![0x00, 0x18]),
            T::write_read(IMU, vec![0x74], record),
        ],
        |icm| {
            icm.set_accel_scale(AccelScale::G4).unwrap();
            icm.enable_fifo().unwrap();
            assert_eq!(icm.fifo_count(), Ok(24));
            let s = icm.read_fifo_record().unwrap();
            assert_eq!(s.accel_mps2, [0.0, 0.0, 9.806_65]);
            assert!((s.gyro_rps[2] - 5.0_f32.to_radians()).abs() < 1e-6);
            assert!(s.temperature_c.is_nan());
        },
    );
}

fn barometer_init_transactions(otp: [i16; 4]) -> Vec<T> {
    let mut t = vec![
        T::write(IMU, vec![0x37, 0x02]), // INT_PIN_CFG.BYPASS_EN
        T::write(BARO, vec![0x80, 0x5D]),
        T::write(BARO, vec![0xEF, 0xC8]),
        T::read(BARO, word(0x0148)),
        T::write(BARO, vec![0xC5, 0x95, 0x00, 0x66, 0x9C]),
    ];
    for c in otp {
        t.push(T::write(BARO, vec![0xC7, 0xF7]));
        t.push(T::read(BARO, word(c as u16)));
    }
    t
}

#[test]
fn barometer_init_bypass_reset_id_and_crc_checked_otp() {
    let otp = [1_850, -780, 2_410, 4_174];
    let mut delay = CheckedDelay::new(&[D::delay_us(10_000)]);
    check(&barometer_init_transactions(otp), |icm| {
        assert_eq!(
            icm.init_barometer(&mut delay),
            Ok(Calibration::from_otp(otp))
        );
        assert_eq!(icm.calibration(), Some(Calibration::from_otp(otp)));
    });
    delay.done();
}

#[test]
fn a_wrong_barometer_id_or_a_bad_crc_is_a_typed_error() {
    check(
        &[
            T::write(BARO, vec![0xEF, 0xC8]),
            T::read(BARO, word(0x0149)),
        ],
        |icm| {
            assert_eq!(icm.barometer_id(), Err(Error::WrongBaroId(0x0149)));
        },
    );
    let mut bad = word(0x0148);
    bad[2] ^= 0xFF;
    let received = bad[2];
    check(
        &[T::write(BARO, vec![0xEF, 0xC8]), T::read(BARO, bad)],
        |icm| {
            assert_eq!(
                icm.barometer_id(),
                Err(Error::Crc {
                    received,
                    computed: crc8(&[0x01, 0x48])
                })
            );
        },
    );
}

#[test]
fn every_mode_and_order_sends_its_command_and_decodes_its_frame() {
    let otp = [0, 0, 0, 4_181];
    let cal = Calibration::from_otp(otp);
    // t = 0 and p = LUT1 = 2048·4181: exactly the 80 kPa calibration point.
    let raw = RawSample {
        p_lsb: 2_048 * 4_181,
        t_lsb: 32_768,
    };
    let commands = [
        (BaroMode::LowPower, FrameOrder::PressureFirst, [0x40, 0x1A]),
        (BaroMode::Normal, FrameOrder::PressureFirst, [0x48, 0xA3]),
        (BaroMode::LowNoise, FrameOrder::PressureFirst, [0x50, 0x59]),
        (
            BaroMode::UltraLowNoise,
            FrameOrder::PressureFirst,
            [0x58, 0xE0],
        ),
        (
            BaroMode::LowPower,
            FrameOrder::TemperatureFirst,
            [0x60, 0x9C],
        ),
        (BaroMode::Normal, FrameOrder::TemperatureFirst, [0x68, 0x25]),
        (
            BaroMode::LowNoise,
            FrameOrder::TemperatureFirst,
            [0x70, 0xDF],
        ),
        (
            BaroMode::UltraLowNoise,
            FrameOrder::TemperatureFirst,
            [0x78, 0x66],
        ),
    ];
    for (mode, order, command) in commands {
        let p_words = [
            word((raw.p_lsb >> 8) as u16),
            word(((raw.p_lsb & 0xFF) << 8) as u16),
        ];
        let t_word = word(raw.t_lsb);
        let frame: Vec<u8> = match order {
            FrameOrder::PressureFirst => [p_words[0].clone(), p_words[1].clone(), t_word].concat(),
            FrameOrder::TemperatureFirst => {
                [t_word, p_words[0].clone(), p_words[1].clone()].concat()
            }
        };
        let mut expectations = barometer_init_transactions(otp);
        expectations.push(T::write(BARO, command.to_vec()));
        expectations.push(T::read(BARO, frame));
        let mut delay = CheckedDelay::new(&[
            D::delay_us(10_000),
            D::delay_us(mode.conversion_time_max_us()),
        ]);
        check(&expectations, |icm| {
            icm.init_barometer(&mut delay).unwrap();
            let sample = icm.measure_pressure(mode, order, &mut delay).unwrap();
            assert_eq!(sample.raw, raw);
            assert_eq!(sample.pressure_pa, 80_000.0);
            assert_eq!(sample.temperature_c, 42.5);
            assert_eq!(cal.pressure_milli_pa(sample.raw), Ok(80_000_000));
        });
        delay.done();
    }
}

#[test]
fn bus_errors_come_back_inside_the_error_and_reading_before_init_is_refused() {
    check(
        &[
            T::write(BARO, vec![0x50, 0x59]),
            T::read(BARO, vec![0; 9]).with_error(ErrorKind::NoAcknowledge(
                embedded_hal::i2c::NoAcknowledgeSource::Address,
            )),
        ],
        |icm| {
            let conversion = icm
                .start_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst)
                .unwrap();
            assert_eq!(conversion.wait_us(), 23_800);
            assert!(matches!(
                icm.read_pressure_raw(conversion),
                Err(Error::I2c(ErrorKind::NoAcknowledge(_)))
            ));
        },
    );
    check(&[], |icm| {
        let conversion = imu_icm20789::BaroConversion {
            mode: BaroMode::Normal,
            order: FrameOrder::PressureFirst,
        };
        assert_eq!(
            icm.read_pressure(conversion),
            Err(Error::BaroNotInitialised)
        );
    });
}
