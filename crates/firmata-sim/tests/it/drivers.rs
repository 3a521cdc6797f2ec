//! The real chip drivers through the board: `baro_drivers::Ms5611` on each fingertip channel of
//! the TCA9548A (also through the `xca9548a` driver), `imu_icm20789::Icm20789` with its
//! barometer, and continuous I2C reads.

use std::time::{Duration, Instant};

use baro_drivers::sim::Conditions;
use baro_drivers::{Address, Ms5611, Osr};
use embedded_hal::i2c::I2c;
use firmata_host::{Board, Options, StdDelay};
use firmata_sim::{ChipBus, FirmwareKind, MS5611_ADDRESS, MUX_ADDRESS, SimBoard, SimConfig};
use imu_icm20789::sim::TrueState;
use imu_icm20789::{BaroMode, FrameOrder, Icm20789};

use crate::{BOOT, board};

/// Three fingertips at 1000, 1010 and 1020 mbar, an ICM-20789 tilted on its side.
fn config() -> SimConfig {
    let tip = |p: f64| -> firmata_sim::BaroEnv {
        Box::new(move |_| Conditions {
            pressure_mbar: p,
            temperature_celsius: 21.0,
        })
    };
    let bus = ChipBus::empty()
        .with_fingertips([tip(1000.0), tip(1010.0), tip(1020.0)], 5)
        .with_icm20789(
            Box::new(|_| TrueState {
                accel_mps2: [9.81, 0.0, 0.0],
                gyro_rps: [0.0, 0.5, 0.0],
                pressure_pa: 100_500.0,
                temperature_c: 25.0,
            }),
            6,
        );
    SimConfig {
        bus,
        ..SimConfig::default().boot_delay(BOOT)
    }
}

#[test]
fn the_ms5611_driver_reads_each_fingertip_through_the_board_and_its_switch() {
    for kind in [FirmwareKind::Standard, FirmwareKind::Configurable] {
        let sim = SimBoard::spawn(config().firmware(kind)).unwrap();
        let mut board = Board::open(sim.path(), &Options::default()).unwrap();
        let mut delay = StdDelay;
        for (channel, mbar) in [(0u8, 1000.0f32), (1, 1010.0), (2, 1020.0)] {
            board.i2c_write(MUX_ADDRESS, &[1 << channel]).unwrap();
            let mut baro = Ms5611::new_with_i2c(&mut board, Address::CsbLow)
                .init(&mut delay)
                .map_err(|e| e.error)
                .unwrap();
            let m = baro.measure(&mut delay, Osr::Osr4096).unwrap();
            assert!(
                (m.pressure_mbar() - mbar).abs() < 0.1,
                "{kind:?} ch {channel}: {m:?}"
            );
            assert!((m.temperature_celsius() - 21.0).abs() < 0.05, "{m:?}");
        }
    }
}

#[test]
fn the_xca9548a_driver_splits_the_board_bus_into_fingertip_channels() {
    let sim = SimBoard::spawn(config()).unwrap();
    let board = Board::open(sim.path(), &Options::default()).unwrap();
    let switch = xca9548a::Xca9548a::new(board, xca9548a::SlaveAddr::default());
    let parts = switch.split();
    let mut delay = StdDelay;
    for (k, port) in [parts.i2c0, parts.i2c1, parts.i2c2].into_iter().enumerate() {
        let mut baro = Ms5611::new_with_i2c(port, Address::CsbLow)
            .init(&mut delay)
            .map_err(|e| e.error)
            .unwrap();
        let m = baro.measure(&mut delay, Osr::Osr1024).unwrap();
        assert!(
            (m.pressure_mbar() - (1000.0 + 10.0 * k as f32)).abs() < 0.2,
            "{m:?}"
        );
    }
}

#[test]
fn the_icm20789_driver_reads_motion_and_pressure_through_the_board() {
    let sim = SimBoard::spawn(config()).unwrap();
    let mut board = Board::open(sim.path(), &Options::default()).unwrap();
    let mut delay = StdDelay;
    let mut icm = Icm20789::new_with_i2c(&mut board);
    icm.init(&mut delay).unwrap();
    icm.init_barometer(&mut delay).unwrap();
    let conversion = icm
        .start_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst)
        .unwrap();
    let imu = icm.read_imu().unwrap(); // a 14-byte register burst: one Firmata read
    embedded_hal::delay::DelayNs::delay_us(&mut delay, conversion.wait_us());
    let baro = icm.read_pressure(conversion).unwrap();
    assert!((imu.accel_mps2[0] - 9.81).abs() < 0.1, "{imu:?}");
    assert!((imu.gyro_rps[1] - 0.5).abs() < 0.02, "{imu:?}");
    assert!((baro.pressure_pa - 100_500.0).abs() < 10.0, "{baro:?}");
}

#[test]
fn a_continuous_read_delivers_at_the_sampling_interval_until_stopped() {
    let (_sim, mut board) = board(FirmwareKind::Standard);
    board.set_sampling_interval(10).unwrap();
    board.i2c_write(MUX_ADDRESS, &[1]).unwrap();
    // PROM word 1 (C1) of the fingertip on channel 0, read by the board every 10 ms.
    board
        .i2c_read_continuously(MS5611_ADDRESS, Some(0xA2), 2)
        .unwrap();
    let mut buf = [0u8; 2];
    let start = Instant::now();
    for _ in 0..5 {
        let n = board
            .i2c_wait_next(MS5611_ADDRESS, 0xA2, &mut buf, Duration::from_millis(200))
            .unwrap();
        assert_eq!(n, 2);
        assert_eq!(u16::from_be_bytes(buf), 40127);
    }
    assert!(
        start.elapsed() >= Duration::from_millis(35),
        "{:?}",
        start.elapsed()
    );
    board.i2c_stop_reading(MS5611_ADDRESS).unwrap();
    // A reply already on the line may still come; after it, none.
    let _ = board.i2c_wait_next(MS5611_ADDRESS, 0xA2, &mut buf, Duration::from_millis(30));
    assert!(
        board
            .i2c_wait_next(MS5611_ADDRESS, 0xA2, &mut buf, Duration::from_millis(100))
            .is_err()
    );
    // A one-shot read with a STOP between register and read, and the embedded-hal write_read.
    let mut c2 = [0u8; 2];
    board
        .i2c_read(MS5611_ADDRESS, Some(0xA4), false, &mut c2)
        .unwrap();
    assert_eq!(u16::from_be_bytes(c2), 36924);
    board.write_read(MS5611_ADDRESS, &[0xA6], &mut c2).unwrap();
    assert_eq!(u16::from_be_bytes(c2), 23317);
}
