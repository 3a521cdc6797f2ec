//! Sampling many sensors at once: every conversion overlaps every other, so N sensors take
//! about as long as one.

use crate::compensation::Measurement;
use crate::error::Error;
use crate::mode::Ready;
use crate::osr::Osr;

/// A sensor's failure inside a scheduled cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleError<E> {
    /// Index of the sensor in the slice given to the scheduler.
    pub sensor: usize,
    /// What went wrong.
    pub error: Error<E>,
}

#[maybe_async_cfg::maybe(
    idents(Scheduler(sync, async = "SchedulerAsync")),
    sync(keep_self),
    async(feature = "async")
)]
/// Samples N sensors sharing a bus (SPI with one chip select each, or I2C behind a mux such
/// as the TCA9548A) in three bus phases separated by one conversion time each:
///
/// 1. start D2 on every sensor;
/// 2. wait; read each D2 and at once start that sensor's D1;
/// 3. wait; read each D1 and compensate.
///
/// A cycle therefore lasts 2 × the maximum conversion time plus the bus transfers, against
/// N × that for one-by-one `measure` calls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scheduler {
    osr: Osr,
}

#[maybe_async_cfg::maybe(
    idents(
        Scheduler(sync, async = "SchedulerAsync"),
        Ms5611(sync, async = "Ms5611Async"),
        Transport(sync, async = "AsyncTransport"),
        hal(sync = "embedded_hal", async = "embedded_hal_async")
    ),
    sync(keep_self),
    async(feature = "async", keep_self)
)]
impl Scheduler {
    /// A scheduler converting at `osr`.
    pub const fn new(osr: Osr) -> Self {
        Self { osr }
    }

    /// The ratio it converts at.
    pub const fn osr(&self) -> Osr {
        self.osr
    }

    /// The shortest cycle the conversion times allow: two maximum conversion times (D2, then
    /// D1), whatever the number of sensors.
    pub fn cycle_bound_ns(&self) -> u64 {
        2 * u64::from(self.osr.conversion_time_max_ns())
    }

    /// One cycle over `sensors`, writing sensor `i`'s result to `out[i]`; samples
    /// `min(sensors.len(), out.len())` sensors. Stops at the first failing sensor and names it.
    pub async fn sample_all<DI, E, D>(
        &self,
        sensors: &mut [crate::Ms5611<DI, Ready>],
        delay: &mut D,
        out: &mut [Measurement],
    ) -> Result<(), SampleError<E>>
    where
        DI: crate::Transport<Error = E>,
        D: hal::delay::DelayNs,
    {
        let n = sensors.len().min(out.len());
        let sensors = &mut sensors[..n];
        let wait = self.osr.conversion_time_max_ns();
        let at = |sensor: usize| move |error| SampleError { sensor, error };

        for (i, s) in sensors.iter_mut().enumerate() {
            s.start_temperature(self.osr).await.map_err(at(i))?;
        }
        // Sensor i started before the last one, so it is done too when the last one is.
        delay.delay_ns(wait).await;
        for (i, s) in sensors.iter_mut().enumerate() {
            s.read_result().await.map_err(at(i))?;
            s.start_pressure(self.osr).await.map_err(at(i))?;
        }
        delay.delay_ns(wait).await;
        for (i, (s, o)) in sensors.iter_mut().zip(out.iter_mut()).enumerate() {
            let d1 = s.read_result().await.map_err(at(i))?.code;
            *o = s.compensate(d1).map_err(at(i))?;
        }
        Ok(())
    }
}
