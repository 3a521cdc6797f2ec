//! Type states of the driver: a chip is only sampled once its PROM passed the CRC.

use crate::compensation::Calibration;

/// Created, PROM not read yet: call `init`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Uninit;

/// PROM read and checked: ready to convert.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ready {
    pub(crate) calibration: Calibration,
}
