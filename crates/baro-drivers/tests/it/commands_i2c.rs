//! Every byte the driver puts on an I2C bus, checked against embedded-hal-mock expectations.

use baro_drivers::{Address, Error, Ms5611, Osr, Prom, PromError, RESET_TIME_NS};
use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::delay::{CheckedDelay, Transaction as Wait};
use embedded_hal_mock::eh1::i2c::{Mock, Transaction as I2c};

const ADDR: u8 = 0x77;
// Datasheet example coefficients (MS5611-01BA03, p. 7).
const C: [u16; 6] = [40127, 36924, 23317, 23282, 33464, 28312];

/// Reset (0x1E) then PROM reads 0xA0, 0xA2, … 0xAE, each a command write and a 2-byte read.
fn init_expectations(addr: u8, prom: &Prom) -> Vec<I2c> {
    let mut t = vec![I2c::write(addr, vec![0x1E])];
    for (i, w) in (0u8..).zip(prom.words()) {
        t.push(I2c::write(addr, vec![0xA0 + 2 * i]));
        t.push(I2c::read(addr, w.to_be_bytes().to_vec()));
    }
    t
}

fn adc(addr: u8, code: u32) -> [I2c; 2] {
    [
        I2c::write(addr, vec![0x00]),
        I2c::read(addr, code.to_be_bytes()[1..].to_vec()),
    ]
}

#[test]
fn init_then_measure_sends_the_datasheet_command_sequence() {
    let prom = Prom::with_crc(0, C, 0x0AB);
    let mut t = init_expectations(ADDR, &prom);
    t.push(I2c::write(ADDR, vec![0x58])); // convert D2, OSR 4096
    t.extend(adc(ADDR, 8_569_150));
    t.push(I2c::write(ADDR, vec![0x48])); // convert D1, OSR 4096
    t.extend(adc(ADDR, 9_085_466));
    let mut bus = Mock::new(&t);
    let mut delay = CheckedDelay::new(&[
        Wait::delay_ns(RESET_TIME_NS),
        Wait::delay_ns(9_040_000),
        Wait::delay_ns(9_040_000),
    ]);

    let mut baro = Ms5611::new_with_i2c(bus.clone(), Address::CsbLow)
        .init(&mut delay)
        .map_err(|e| e.error)
        .unwrap();
    assert_eq!(baro.calibration().coefficients(), C);
    let m = baro.measure(&mut delay, Osr::Osr4096).unwrap();
    assert_eq!(
        (m.temperature_centi_celsius, m.pressure_pa),
        (2007, 100_009)
    );

    baro.destroy();
    bus.done();
    delay.done();
}

#[test]
fn every_osr_has_its_convert_command_at_either_address() {
    let prom = Prom::with_crc(0, C, 0);
    for (address, addr) in [(Address::CsbLow, 0x77), (Address::CsbHigh, 0x76)] {
        let mut t = init_expectations(addr, &prom);
        for off in [0u8, 2, 4, 6, 8] {
            t.push(I2c::write(addr, vec![0x40 + off]));
            t.push(I2c::write(addr, vec![0x50 + off]));
        }
        let mut bus = Mock::new(&t);
        let mut baro = Ms5611::new_with_i2c(bus.clone(), address)
            .init(&mut embedded_hal_mock::eh1::delay::NoopDelay)
            .map_err(|e| e.error)
            .unwrap();
        for osr in Osr::ALL {
            baro.start_pressure(osr).unwrap();
            baro.start_temperature(osr).unwrap();
        }
        baro.destroy();
        bus.done();
    }
}

#[test]
fn bad_crc_hands_the_device_back_with_a_typed_error() {
    let mut words = Prom::with_crc(0, C, 0x321).words();
    words[3] ^= 0x0100;
    let prom = Prom::from_words(words);
    let mut bus = Mock::new(&init_expectations(ADDR, &prom));
    let err = Ms5611::new_with_i2c(bus.clone(), Address::CsbLow)
        .init(&mut embedded_hal_mock::eh1::delay::NoopDelay)
        .expect_err("corrupt PROM");
    assert!(matches!(err.error, Error::Prom(PromError::Crc { .. })));
    err.dev.destroy();
    bus.done();
}

#[test]
fn a_nack_is_a_comm_error_not_a_panic() {
    let mut bus = Mock::new(&[I2c::write(ADDR, vec![0x1E]).with_error(ErrorKind::Other)]);
    let err = Ms5611::new_with_i2c(bus.clone(), Address::CsbLow)
        .init(&mut embedded_hal_mock::eh1::delay::NoopDelay)
        .expect_err("bus fails");
    assert_eq!(err.error, Error::Comm(ErrorKind::Other));
    err.dev.destroy();
    bus.done();
}

#[test]
fn an_adc_read_of_zero_means_not_ready_and_reading_twice_needs_a_new_conversion() {
    let prom = Prom::with_crc(0, C, 0);
    let mut t = init_expectations(ADDR, &prom);
    t.push(I2c::write(ADDR, vec![0x50])); // D2, OSR 256
    t.extend(adc(ADDR, 0));
    let mut bus = Mock::new(&t);
    let mut baro = Ms5611::new_with_i2c(bus.clone(), Address::CsbLow)
        .init(&mut embedded_hal_mock::eh1::delay::NoopDelay)
        .map_err(|e| e.error)
        .unwrap();
    baro.start_temperature(Osr::Osr256).unwrap();
    assert_eq!(baro.read_result(), Err(Error::AdcNotReady));
    // The failed read consumed the conversion: nothing is sent now.
    assert_eq!(baro.read_result(), Err(Error::NoConversionStarted));
    assert_eq!(baro.compensate(9_000_000), Err(Error::NoTemperature));
    baro.destroy();
    bus.done();
}
