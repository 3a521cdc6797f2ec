//! The async driver and scheduler (same source as the blocking ones) against the chip model.
#![cfg(all(feature = "async", feature = "sim"))]

use core::future::Future;
use core::pin::pin;
use core::task::{Context, Poll, Waker};

use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock};
use baro_drivers::{Measurement, Ms5611Async, Osr, SchedulerAsync};

/// Polls to completion: the model and its delay never pend, so no executor is needed.
fn block_on<F: Future>(f: F) -> F::Output {
    let mut f = pin!(f);
    let mut cx = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(v) = f.as_mut().poll(&mut cx) {
            return v;
        }
    }
}

#[test]
fn async_measure_and_scheduler_match_the_truth_and_the_bound() {
    let clock = SimClock::new();
    let truth = |i: usize| Conditions {
        pressure_mbar: 980.0 + 10.0 * i as f64,
        temperature_celsius: -5.0 + 3.0 * i as f64,
    };
    let mut delay = clock.delay();
    let mut bank = Vec::new();
    for i in 0..3 {
        let chip = Ms5611Sim::new(truth(i), clock.clone())
            .with_timing(BusTiming::INSTANT)
            .with_noise(false);
        let dev = block_on(Ms5611Async::new_with_spi(chip).init(&mut delay)).map_err(|e| e.error);
        bank.push(dev.unwrap());
    }
    let single = block_on(bank[0].measure(&mut delay, Osr::Osr512)).unwrap();
    assert_eq!(single.pressure_pa, 98_000);
    assert_eq!(single.temperature_centi_celsius, -500);

    let scheduler = SchedulerAsync::new(Osr::Osr2048);
    let mut out = [Measurement {
        temperature_centi_celsius: 0,
        pressure_pa: 0,
    }; 3];
    let (r, cycle) = clock.time(|| block_on(scheduler.sample_all(&mut bank, &mut delay, &mut out)));
    r.unwrap();
    assert_eq!(cycle, scheduler.cycle_bound_ns());
    for (i, m) in out.iter().enumerate() {
        assert!((f64::from(m.pressure_pa) - truth(i).pressure_mbar * 100.0).abs() <= 1.0);
        assert!(
            (f64::from(m.temperature_centi_celsius) - truth(i).temperature_celsius * 100.0).abs()
                <= 1.0
        );
    }
}

#[test]
fn async_i2c_sends_the_same_bytes_as_blocking() {
    use embedded_hal_mock::eh1::i2c::{Mock, Transaction as I2c};
    // Datasheet example coefficients (MS5611-01BA03, p. 7).
    let prom = baro_drivers::Prom::with_crc(0, [40127, 36924, 23317, 23282, 33464, 28312], 9);
    let mut t = vec![I2c::write(0x76, vec![0x1E])];
    for (i, w) in (0u8..).zip(prom.words()) {
        t.push(I2c::write(0x76, vec![0xA0 + 2 * i]));
        t.push(I2c::read(0x76, w.to_be_bytes().to_vec()));
    }
    t.push(I2c::write(0x76, vec![0x46])); // D1, OSR 2048
    let mut bus = Mock::new(&t);
    let mut baro = block_on(
        Ms5611Async::new_with_i2c(bus.clone(), baro_drivers::Address::CsbHigh)
            .init(&mut embedded_hal_mock::eh1::delay::NoopDelay),
    )
    .map_err(|e| e.error)
    .unwrap();
    block_on(baro.start_pressure(Osr::Osr2048)).unwrap();
    baro.destroy();
    bus.done();
}
