//! Every byte the driver puts on SPI, checked against embedded-hal-mock expectations: one
//! chip-select assertion per command, the answer read inside the same assertion.

use baro_drivers::{Ms5611, Osr, Prom, RESET_TIME_NS};
use embedded_hal_mock::eh1::delay::{CheckedDelay, Transaction as Wait};
use embedded_hal_mock::eh1::spi::{Mock, Transaction as Spi};

// Datasheet example coefficients (MS5611-01BA03, p. 7).
const C: [u16; 6] = [40127, 36924, 23317, 23282, 33464, 28312];

fn command(byte: u8) -> [Spi<u8>; 3] {
    [
        Spi::transaction_start(),
        Spi::write_vec(vec![byte]),
        Spi::transaction_end(),
    ]
}

fn command_read(byte: u8, answer: &[u8]) -> [Spi<u8>; 4] {
    [
        Spi::transaction_start(),
        Spi::write_vec(vec![byte]),
        Spi::read_vec(answer.to_vec()),
        Spi::transaction_end(),
    ]
}

#[test]
fn init_split_phase_and_measure_send_the_datasheet_commands() {
    let prom = Prom::with_crc(0, C, 0x7E1);
    let mut t: Vec<Spi<u8>> = command(0x1E).to_vec();
    for (i, w) in (0u8..).zip(prom.words()) {
        t.extend(command_read(0xA0 + 2 * i, &w.to_be_bytes()));
    }
    // Split phase at OSR 1024: D2 then D1.
    t.extend(command(0x54));
    t.extend(command_read(0x00, &8_569_150u32.to_be_bytes()[1..]));
    t.extend(command(0x44));
    t.extend(command_read(0x00, &9_085_466u32.to_be_bytes()[1..]));
    // measure() at OSR 256.
    t.extend(command(0x50));
    t.extend(command_read(0x00, &8_569_150u32.to_be_bytes()[1..]));
    t.extend(command(0x40));
    t.extend(command_read(0x00, &9_085_466u32.to_be_bytes()[1..]));
    let mut spi = Mock::new(&t);
    let mut delay = CheckedDelay::new(&[
        Wait::delay_ns(RESET_TIME_NS),
        Wait::delay_ns(600_000),
        Wait::delay_ns(600_000),
    ]);

    let mut baro = Ms5611::new_with_spi(spi.clone())
        .init(&mut delay)
        .map_err(|e| e.error)
        .unwrap();
    baro.start_temperature(Osr::Osr1024).unwrap();
    let d2 = baro.read_result().unwrap();
    assert_eq!((d2.code, d2.osr), (8_569_150, Osr::Osr1024));
    baro.start_pressure(Osr::Osr1024).unwrap();
    let d1 = baro.read_result().unwrap();
    let split = baro.compensate(d1.code).unwrap();
    let blocking = baro.measure(&mut delay, Osr::Osr256).unwrap();
    assert_eq!(split, blocking);
    assert_eq!(
        (split.temperature_centi_celsius, split.pressure_pa),
        (2007, 100_009)
    );

    baro.destroy();
    spi.done();
    delay.done();
}
