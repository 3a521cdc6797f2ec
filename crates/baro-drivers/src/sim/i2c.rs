//! The chip model as an I2C target.

use embedded_hal::i2c::{ErrorType, I2c, Operation, SevenBitAddress};

use super::chip::Ms5611Sim;
use super::environment::Environment;
use super::error::SimError;

/// An I2C device model that can sit on a simulated bus with others.
pub trait I2cTarget: I2c<Error = SimError> {
    /// The 7-bit address it answers at.
    fn address(&self) -> u8;
}

impl<Env: Environment> ErrorType for Ms5611Sim<Env> {
    type Error = SimError;
}

impl<Env: Environment> I2c for Ms5611Sim<Env> {
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), SimError> {
        if address != self.address {
            self.clock.advance_ns(self.timing.i2c_message_ns(0));
            return Err(SimError::NoAcknowledgeAddress(address));
        }
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    self.clock
                        .advance_ns(self.timing.i2c_message_ns(bytes.len()));
                    // The chip takes one command per message; further bytes are ignored.
                    if let Some(&first) = bytes.first() {
                        self.command(first)?;
                    }
                }
                Operation::Read(buf) => {
                    self.clock.advance_ns(self.timing.i2c_message_ns(buf.len()));
                    for b in buf.iter_mut() {
                        *b = self.answer_byte();
                    }
                }
            }
        }
        Ok(())
    }
}

impl<Env: Environment> I2cTarget for Ms5611Sim<Env> {
    fn address(&self) -> u8 {
        self.address
    }
}

#[cfg(feature = "async")]
impl<Env: Environment> embedded_hal_async::i2c::I2c for Ms5611Sim<Env> {
    async fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), SimError> {
        I2c::transaction(self, address, operations)
    }
}
