//! An MS5611 on a Linux SPI device (mode 0, its own chip select): `cargo run --example
//! ms5611_linux_spi -- /dev/spidev0.0` prints ten readings at OSR 1024.

use baro_drivers::{Ms5611, Osr};
use linux_embedded_hal::spidev::{SpiModeFlags, SpidevOptions};
use linux_embedded_hal::{Delay, SpidevDevice};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "/dev/spidev0.0".into());
    let mut spi = SpidevDevice::open(&path).map_err(|e| format!("{path}: {e}"))?;
    // The MS5611 takes SPI mode 0 or 3 up to 20 MHz (datasheet p. 1); 1 MHz is safe on jumpers.
    spi.configure(
        &SpidevOptions::new()
            .mode(SpiModeFlags::SPI_MODE_0)
            .max_speed_hz(1_000_000)
            .build(),
    )
    .map_err(|e| format!("{path}: {e}"))?;
    let mut delay = Delay;
    let mut baro = Ms5611::new_with_spi(spi)
        .init(&mut delay)
        .map_err(|e| format!("MS5611 on {path}: {:?}", e.error))?;
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
