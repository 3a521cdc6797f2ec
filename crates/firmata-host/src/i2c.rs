//! embedded-hal 1.0 `I2c` over the board, so a chip driver runs unchanged through an Arduino.
//!
//! Firmata carries I2C as separate requests (i2c.md 2.6.0), each a complete bus transfer the
//! board makes with the `Wire` library, so an embedded-hal transaction maps onto them so:
//!
//! | embedded-hal | Firmata request | on the bus |
//! |---|---|---|
//! | `write(a, bytes)` | I2C write (≤ [`MAX_I2C_WRITE`] bytes) | START a+W bytes STOP |
//! | `read(a, buf)` | read once, no register (≤ [`MAX_I2C_READ`]) | START a+R buf STOP |
//! | `write_read(a, [r], buf)` | read once with register `r`, auto-restart bit set | START a+W r Sr a+R buf STOP |
//! | `write_read(a, bytes, buf)`, 2+ bytes | a write, then a read without register | … STOP START … |
//! | `transaction(a, ops)` | each operation as above, a one-byte write followed by a read merged into a register read | a STOP between requests |
//!
//! What this means for a driver:
//! - A register is one byte: the firmware writes `(byte)theRegister` (StandardFirmata 2.5.9
//!   `readAndReportData`); a multi-byte register address goes as a plain write, then a read.
//! - Only reads can fail with a NACK ([`ErrorKind::I2cNack`]): the board reports no status for a
//!   write. A driver that writes a command and then reads the result finds out at the read.
//! - Reads of more than 32 bytes or writes of more than 30 are refused before anything is sent
//!   ([`ErrorKind::I2cTooLong`]), not split: a split read would re-address the device.
//! - Every read is a round trip over the serial line; at 57 600 baud a 3-byte register read is
//!   about 21 bytes on the wire, a few milliseconds.

use embedded_hal::i2c::{ErrorType, I2c, Operation, SevenBitAddress};

use crate::board::Board;
use crate::error::{Error, ErrorKind};
use crate::protocol::{MAX_I2C_READ, MAX_I2C_WRITE};

impl ErrorType for Board {
    type Error = Error;
}

impl I2c<SevenBitAddress> for Board {
    fn transaction(
        &mut self,
        address: SevenBitAddress,
        operations: &mut [Operation<'_>],
    ) -> Result<(), Error> {
        // Check every operation before sending any: nothing half-done for a bad shape.
        for op in operations.iter() {
            match op {
                Operation::Write(w) if w.len() > MAX_I2C_WRITE => {
                    return Err(Error::new(
                        self.port_name(),
                        ErrorKind::I2cTooLong {
                            what: "write",
                            len: w.len(),
                            max: MAX_I2C_WRITE,
                        },
                    ));
                }
                Operation::Read(r) if r.len() > MAX_I2C_READ => {
                    return Err(Error::new(
                        self.port_name(),
                        ErrorKind::I2cTooLong {
                            what: "read",
                            len: r.len(),
                            max: MAX_I2C_READ,
                        },
                    ));
                }
                _ => {}
            }
        }
        let mut k = 0;
        while k < operations.len() {
            let (head, tail) = operations.split_at_mut(k + 1);
            match (&mut head[k], tail.first_mut()) {
                (Operation::Write(w), Some(Operation::Read(r))) if w.len() == 1 => {
                    let register = w[0];
                    self.i2c_read(address, Some(register), true, r)?;
                    k += 2;
                }
                (Operation::Write(w), _) => {
                    self.i2c_write(address, w)?;
                    k += 1;
                }
                (Operation::Read(r), _) => {
                    if !r.is_empty() {
                        self.i2c_read(address, None, false, r)?;
                    }
                    k += 1;
                }
            }
        }
        Ok(())
    }
}
