//! An MS5611 on a Linux I2C bus (a Raspberry Pi's `/dev/i2c-1`, a USB–I2C adapter):
//! `cargo run --example ms5611_linux_i2c -- /dev/i2c-1 [0x76|0x77]` prints ten readings at OSR 1024.

use baro_drivers::{Address, Ms5611, Osr};
use linux_embedded_hal::{Delay, I2cdev};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let bus = args.next().unwrap_or_else(|| "/dev/i2c-1".into());
    let address = match args.next().as_deref() {
        Some("0x76") => Address::CsbHigh,
        _ => Address::CsbLow,
    };
    let i2c = I2cdev::new(&bus).map_err(|e| format!("{bus}: {e}"))?;
    let mut delay = Delay;
    let mut baro = Ms5611::new_with_i2c(i2c, address)
        .init(&mut delay)
        .map_err(|e| format!("MS5611 on {bus}: {:?}", e.error))?;
    for _ in 0..10 {
        let m = baro
            .measure(&mut delay, Osr::Osr1024)
            .map_err(|e| format!("{e:?}"))?;
        println!(
            "{:.2} mbar at {:.2} °C",
            m.pressure_mbar(),
            m.temperature_celsius()
        );
    }
    Ok(())
}
