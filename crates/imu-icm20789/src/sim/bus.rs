//! The bus-time account: the bits the model's I2C bus carried, on top of the shared clock.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use sim_clock::SimClock;

/// I2C bit time at 400 kHz, ns.
pub const BIT_NS_400KHZ: u64 = 2_500;

/// The bits the chip model's I2C bus has carried (START, address + ACK, data + ACK, repeated
/// START, STOP), counted on the clock the model runs on: clocking bits lets their time pass on
/// that clock. Clones share the count.
///
/// ```
/// use imu_icm20789::sim::{BIT_NS_400KHZ, ChipModel, Truth};
/// use imu_icm20789::Icm20789;
///
/// let chip = ChipModel::new(Truth::constant([0.0, 0.0, 9.81], [0.0; 3], 101_325.0), 1);
/// let (bus, mut delay) = (chip.bus(), chip.delay());
/// let mut icm = Icm20789::new_with_i2c(chip);
/// icm.init(&mut delay)?;
/// let before = bus.bits();
/// icm.read_imu()?; // S, addr·W, reg, Sr, addr·R, 14 data bytes, P
/// assert_eq!(bus.bits() - before, 156);
/// assert_eq!(bus.busy_ns(), bus.bits() * BIT_NS_400KHZ);
/// # Ok::<(), imu_icm20789::Error<imu_icm20789::sim::SimError>>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct BusAccount {
    // Atomic like the clock it sits on, so the model stays shareable across threads.
    bits: Arc<AtomicU64>,
    clock: SimClock,
}

impl BusAccount {
    /// An account with no bits yet, on `clock`.
    pub fn new(clock: SimClock) -> BusAccount {
        BusAccount {
            bits: Arc::default(),
            clock,
        }
    }

    /// Bits clocked on the bus so far.
    pub fn bits(&self) -> u64 {
        self.bits.load(Ordering::Relaxed)
    }

    /// Time the bus has been busy so far at 400 kHz, ns.
    pub fn busy_ns(&self) -> u64 {
        self.bits().saturating_mul(BIT_NS_400KHZ)
    }

    /// The clock the bits' time passes on.
    pub fn clock(&self) -> &SimClock {
        &self.clock
    }

    /// Accounts `bits` of bus traffic and lets the time they take pass.
    pub(crate) fn clock_bits(&self, bits: u64) {
        self.bits.fetch_add(bits, Ordering::Relaxed);
        self.clock.advance_ns(bits.saturating_mul(BIT_NS_400KHZ));
    }
}
