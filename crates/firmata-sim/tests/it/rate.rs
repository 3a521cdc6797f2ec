//! The I2C read rate through the board at 57 600 and 115 200 baud: an MS5611 ADC read (3 bytes
//! from register 0x00, the read a fingertip loop makes per sample), round trips for 1 s each.
//! The line is paced as a UART, so the rate is what the wire allows: about 9 bytes out and 12
//! back per read, plus the I2C transfer at 100 kHz.

use std::time::{Duration, Instant};

use firmata_host::{Board, Options};
use firmata_sim::{FirmwareKind, MS5611_ADDRESS, MUX_ADDRESS, SimBoard, SimConfig};

use crate::BOOT;

fn reads_per_second(baud: u32) -> f64 {
    let sim = SimBoard::spawn(
        SimConfig::default()
            .firmware(FirmwareKind::Standard)
            .baud(baud)
            .boot_delay(BOOT),
    )
    .unwrap();
    let options = Options {
        baud,
        ..Options::default()
    };
    let mut board = Board::open(sim.path(), &options).unwrap();
    board.i2c_write(MUX_ADDRESS, &[1]).unwrap();
    let mut adc = [0u8; 3];
    let start = Instant::now();
    let mut n = 0u32;
    while start.elapsed() < Duration::from_secs(1) {
        board
            .i2c_read(MS5611_ADDRESS, Some(0x00), true, &mut adc)
            .unwrap();
        n += 1;
    }
    f64::from(n) / start.elapsed().as_secs_f64()
}

#[test]
fn i2c_read_rate_at_57600_and_115200_baud() {
    let slow = reads_per_second(57_600);
    let fast = reads_per_second(115_200);
    println!(
        "I2C 3-byte register reads through the board: {slow:.0}/s at 57600 baud, {fast:.0}/s at 115200 baud"
    );
    // Wire time alone: 21 bytes × 10 bits at 57 600 baud = 3.6 ms, plus ~0.6 ms of I2C.
    let bound = |baud: f64| 1.0 / (21.0 * 10.0 / baud + 0.00058);
    assert!(
        slow <= bound(57_600.0) * 1.02,
        "{slow} above the wire's bound"
    );
    assert!(slow >= bound(57_600.0) * 0.5, "{slow}");
    assert!(fast <= bound(115_200.0) * 1.02, "{fast}");
    assert!(fast > slow * 1.4, "{fast} vs {slow}");
}
