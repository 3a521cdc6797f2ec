//! The chip model as an SPI device behind its own chip select: within one chip-select
//! assertion the first byte clocked in is the command, the following bytes clock its answer
//! out.

use embedded_hal::spi::{Operation, SpiDevice};

use super::chip::Ms5611Sim;
use super::environment::Environment;
use super::error::SimError;

impl<Env: Environment> embedded_hal::spi::ErrorType for Ms5611Sim<Env> {
    type Error = SimError;
}

impl<Env: Environment> Ms5611Sim<Env> {
    /// One byte exchanged: `mosi` in, the returned byte out.
    fn spi_byte(&mut self, mosi: u8, first: &mut bool) -> Result<u8, SimError> {
        self.clock.advance_ns(self.timing.spi_bytes_ns(1));
        if std::mem::take(first) {
            self.command(mosi)?;
            Ok(0)
        } else {
            Ok(self.answer_byte())
        }
    }
}

impl<Env: Environment> SpiDevice for Ms5611Sim<Env> {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), SimError> {
        let mut first = true;
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    for &b in bytes.iter() {
                        self.spi_byte(b, &mut first)?;
                    }
                }
                // A read clocks 0x00 out on SDI, which the chip takes as ADC READ if first.
                Operation::Read(buf) => {
                    for b in buf.iter_mut() {
                        *b = self.spi_byte(0x00, &mut first)?;
                    }
                }
                Operation::Transfer(read, write) => {
                    let n = read.len().max(write.len());
                    for i in 0..n {
                        let out = self.spi_byte(write.get(i).copied().unwrap_or(0), &mut first)?;
                        if let Some(r) = read.get_mut(i) {
                            *r = out;
                        }
                    }
                }
                Operation::TransferInPlace(buf) => {
                    for b in buf.iter_mut() {
                        *b = self.spi_byte(*b, &mut first)?;
                    }
                }
                Operation::DelayNs(ns) => self.clock.advance_ns(u64::from(*ns)),
            }
        }
        Ok(())
    }
}

#[cfg(feature = "async")]
impl<Env: Environment> embedded_hal_async::spi::SpiDevice for Ms5611Sim<Env> {
    async fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), SimError> {
        SpiDevice::transaction(self, operations)
    }
}
