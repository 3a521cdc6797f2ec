//! The board's I2C bus: the chip models the sketch's `Wire` calls reach.
//!
//! The models come from the drivers' own `sim` features: `baro_drivers::sim::Ms5611Sim` (three
//! fingertip barometers at 0x77, each on its own channel 0–2 of a `Tca9548aSim` switch at 0x70)
//! and `imu_icm20789::sim::ChipModel` (the IMU at 0x68, its barometer at 0x63 once the driver
//! turns the bypass on). They run on one `SimClock`, which the bus moves to the wall-clock time
//! since the board started before each transfer: conversion times then pass in real time, as
//! the client's delays expect.

use std::time::Instant;

use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock, Tca9548aSim};
use embedded_hal::i2c::{I2c, Operation};
use imu_icm20789::sim::{ChipModel, TrueState};

/// What a fingertip barometer senses over time (ns since the board started): constant air, or
/// a physics model's contact pressure.
pub type BaroEnv = Box<dyn FnMut(u64) -> Conditions + Send>;
/// What the ICM-20789 senses over time (µs since the board started).
pub type ImuEnv = Box<dyn FnMut(u64) -> TrueState + Send>;

/// The TCA9548A's address (A2..A0 low).
pub const MUX_ADDRESS: u8 = 0x70;
/// The fingertip barometers' address (CSB low), one per mux channel.
pub const MS5611_ADDRESS: u8 = 0x77;
/// The ICM-20789's IMU (AD0 low) and barometer addresses.
pub const ICM20789_ADDRESSES: [u8; 2] = [0x68, 0x63];

/// The chips on the simulated board's I2C bus.
pub struct ChipBus {
    clock: SimClock,
    start: Instant,
    fingertips: Option<Tca9548aSim<Ms5611Sim<BaroEnv>>>,
    imu: Option<ChipModel>,
}

impl core::fmt::Debug for ChipBus {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ChipBus")
            .field("fingertips", &self.fingertips.is_some())
            .field("imu", &self.imu.is_some())
            .finish_non_exhaustive()
    }
}

impl ChipBus {
    /// A bus with nothing on it.
    pub fn empty() -> ChipBus {
        ChipBus {
            clock: SimClock::new(),
            start: Instant::now(),
            fingertips: None,
            imu: None,
        }
    }

    /// Puts three MS5611s behind a TCA9548A (channels 0, 1, 2), each sensing its environment.
    pub fn with_fingertips(mut self, envs: [BaroEnv; 3], seed: u64) -> ChipBus {
        let mut mux = Tca9548aSim::new(MUX_ADDRESS, self.clock.clone(), BusTiming::default());
        for (channel, env) in envs.into_iter().enumerate() {
            let chip = Ms5611Sim::new(env, self.clock.clone())
                .with_seed(seed + channel as u64)
                // A long run must not grow the heap with the command log.
                .with_command_log(false);
            mux = mux.attach(channel as u8, chip);
        }
        self.fingertips = Some(mux);
        self
    }

    /// Puts an ICM-20789 on the bus, sensing `env`.
    pub fn with_icm20789(mut self, env: ImuEnv, seed: u64) -> ChipBus {
        self.imu = Some(ChipModel::new(env, seed).with_clock(self.clock.clone()));
        self
    }

    /// The simulated clock, moved up to the wall clock.
    fn sync(&self) {
        let ns = self.start.elapsed().as_nanos().min(u128::from(u64::MAX)) as u64;
        self.clock.advance_to_ns(ns);
    }

    /// One `Wire` transaction: the operations between START and STOP. `false` when no
    /// device acknowledged (the sketch then receives nothing).
    pub fn transaction(&mut self, address: u8, operations: &mut [Operation<'_>]) -> bool {
        self.sync();
        if ICM20789_ADDRESSES.contains(&address) {
            if let Some(imu) = self.imu.as_mut() {
                return imu.transaction(address, operations).is_ok();
            }
        }
        match self.fingertips.as_mut() {
            Some(mux) => mux.transaction(address, operations).is_ok(),
            None => false,
        }
    }
}
