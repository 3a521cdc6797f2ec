//! A TCA9548A I2C switch model: a write to its address selects channels; other addresses go
//! to the devices on the selected channels.

use std::vec::Vec;

use embedded_hal::i2c::{ErrorType, I2c, Operation, SevenBitAddress};

use super::error::SimError;
use super::i2c::I2cTarget;
use super::timing::BusTiming;
use sim_clock::SimClock;

/// A TCA9548A with up to eight downstream channels of simulated I2C targets.
#[derive(Debug)]
pub struct Tca9548aSim<D> {
    address: u8,
    mask: u8,
    channels: Vec<(u8, D)>,
    clock: SimClock,
    timing: BusTiming,
}

impl<D: I2cTarget> Tca9548aSim<D> {
    /// A switch at `address` (0x70 … 0x77) on `clock`, nothing attached, no channel selected.
    pub fn new(address: u8, clock: SimClock, timing: BusTiming) -> Self {
        Self {
            address,
            mask: 0,
            channels: Vec::new(),
            clock,
            timing,
        }
    }

    /// Attaches `device` to channel `channel` (0 … 7).
    pub fn attach(mut self, channel: u8, device: D) -> Self {
        self.channels.push((channel & 0x07, device));
        self
    }

    /// The devices attached, with their channel.
    pub fn devices(&self) -> &[(u8, D)] {
        &self.channels
    }
}

impl<D: I2cTarget> ErrorType for Tca9548aSim<D> {
    type Error = SimError;
}

impl<D: I2cTarget> I2c for Tca9548aSim<D> {
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), SimError> {
        if address == self.address {
            for op in operations {
                match op {
                    Operation::Write(bytes) => {
                        self.clock
                            .advance_ns(self.timing.i2c_message_ns(bytes.len()));
                        if let Some(&m) = bytes.last() {
                            self.mask = m;
                        }
                    }
                    Operation::Read(buf) => {
                        self.clock.advance_ns(self.timing.i2c_message_ns(buf.len()));
                        buf.fill(self.mask);
                    }
                }
            }
            return Ok(());
        }
        let mask = self.mask;
        match self
            .channels
            .iter_mut()
            .find(|(ch, d)| mask & (1 << ch) != 0 && d.address() == address)
        {
            Some((_, device)) => device.transaction(address, operations),
            None => {
                self.clock.advance_ns(self.timing.i2c_message_ns(0));
                Err(SimError::NoAcknowledgeAddress(address))
            }
        }
    }
}
