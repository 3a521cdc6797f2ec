//! Six sensors (one fingertip module) sampled by the scheduler against one-by-one `measure`,
//! in simulated time: the scheduler's cycle must be within 10 % of the conversion-time bound.

use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock, Tca9548aSim};
use baro_drivers::{Address, Measurement, Ms5611, Osr, Ready, Scheduler, SpiInterface};

const SENSORS: usize = 6;

fn truth(i: usize) -> Conditions {
    Conditions {
        pressure_mbar: 1000.0 + 12.5 * i as f64,
        temperature_celsius: 24.0 + i as f64,
    }
}

type SpiBaro = Ms5611<SpiInterface<Ms5611Sim<Conditions>>, Ready>;

fn spi_bank(clock: &SimClock, timing: BusTiming) -> Vec<SpiBaro> {
    (0..SENSORS)
        .map(|i| {
            let chip = Ms5611Sim::new(truth(i), clock.clone())
                .with_timing(timing)
                .with_seed(i as u64);
            Ms5611::new_with_spi(chip)
                .init(&mut clock.delay())
                .map_err(|e| e.error)
                .unwrap()
        })
        .collect()
}

fn check_readings(out: &[Measurement], osr: Osr) {
    for (i, m) in out.iter().enumerate() {
        let tol = 6.0 * osr.pressure_noise_rms_mbar() + 0.1;
        assert!((m.pressure_mbar() as f64 - truth(i).pressure_mbar).abs() < f64::from(tol));
        assert!((m.temperature_celsius() as f64 - truth(i).temperature_celsius).abs() < 0.1);
    }
}

/// Simulated time of one scheduler cycle and of one pass of one-by-one `measure` calls.
fn cycle_and_serial<DI, E>(
    bank: &mut [Ms5611<DI, Ready>],
    clock: &SimClock,
    osr: Osr,
) -> ([Measurement; SENSORS], u64, u64)
where
    DI: baro_drivers::Transport<Error = E>,
    E: core::fmt::Debug,
{
    let scheduler = Scheduler::new(osr);
    let mut out = [Measurement {
        temperature_centi_celsius: 0,
        pressure_pa: 0,
    }; SENSORS];
    let mut delay = clock.delay();
    let (r, cycle) = clock.time(|| scheduler.sample_all(bank, &mut delay, &mut out));
    r.unwrap();
    check_readings(&out, osr);
    let (r, serial) = clock.time(|| {
        bank.iter_mut()
            .map(|b| b.measure(&mut delay, osr))
            .collect::<Result<Vec<_>, _>>()
    });
    check_readings(&r.unwrap(), osr);
    (out, cycle, serial)
}

#[test]
fn spi_scheduler_cycle_is_within_10_percent_of_the_conversion_bound() {
    for osr in Osr::ALL {
        let clock = SimClock::new();
        let mut bank = spi_bank(&clock, BusTiming::default());
        let (_, cycle, serial) = cycle_and_serial(&mut bank, &clock, osr);
        let bound = Scheduler::new(osr).cycle_bound_ns();
        let over = (cycle as f64 / bound as f64 - 1.0) * 100.0;
        println!(
            "SPI 20 MHz {osr:?}: scheduler {cycle} ns, bound {bound} ns (+{over:.2} %), one-by-one {serial} ns ({:.2}x)",
            serial as f64 / cycle as f64
        );
        assert!(
            cycle >= bound,
            "faster than the conversions allow: the model is wrong"
        );
        assert!(over <= 10.0, "{osr:?}: {over:.2} % over the bound");
        assert!(serial as f64 >= 5.0 * cycle as f64);
    }
}

#[test]
fn with_instant_transfers_the_cycle_is_exactly_the_bound() {
    for osr in Osr::ALL {
        let clock = SimClock::new();
        let mut bank = spi_bank(&clock, BusTiming::INSTANT);
        let scheduler = Scheduler::new(osr);
        let mut out = [Measurement {
            temperature_centi_celsius: 0,
            pressure_pa: 0,
        }; SENSORS];
        let (r, cycle) =
            clock.time(|| scheduler.sample_all(&mut bank, &mut clock.delay(), &mut out));
        r.unwrap();
        assert_eq!(cycle, scheduler.cycle_bound_ns());
    }
}

#[test]
fn i2c_behind_a_tca9548a_is_bus_limited_and_still_twice_as_fast_as_one_by_one() {
    for osr in Osr::ALL {
        let clock = SimClock::new();
        let timing = BusTiming::default();
        let mut mux = Tca9548aSim::new(0x70, clock.clone(), timing);
        for i in 0..SENSORS {
            let chip = Ms5611Sim::new(truth(i), clock.clone())
                .with_timing(timing)
                .with_seed(i as u64);
            mux = mux.attach(i as u8, chip);
        }
        let switch = xca9548a::Xca9548a::new(mux, xca9548a::SlaveAddr::default());
        let p = switch.split();
        let mut delay = clock.delay();
        let mut bank: Vec<_> = [p.i2c0, p.i2c1, p.i2c2, p.i2c3, p.i2c4, p.i2c5]
            .into_iter()
            .map(|port| {
                Ms5611::new_with_i2c(port, Address::CsbLow)
                    .init(&mut delay)
                    .map_err(|e| e.error)
                    .unwrap()
            })
            .collect();
        let (_, cycle, serial) = cycle_and_serial(&mut bank, &clock, osr);
        let bound = Scheduler::new(osr).cycle_bound_ns();
        println!(
            "I2C 400 kHz via TCA9548A {osr:?}: scheduler {cycle} ns, bound {bound} ns (+{:.1} %), one-by-one {serial} ns",
            (cycle as f64 / bound as f64 - 1.0) * 100.0
        );
        assert!(cycle > bound);
        assert!(serial as f64 >= 2.0 * cycle as f64);
    }
}
