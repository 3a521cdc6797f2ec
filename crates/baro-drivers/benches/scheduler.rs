//! Six MS5611 (one hand module) per cycle: the split-phase scheduler against one-by-one
//! blocking `measure`, over SPI at 20 MHz, per OSR. Criterion reports *simulated* time (the
//! chip model's clock), so the figures are the bus and conversion schedule, not host speed.

use std::time::Duration;

use baro_drivers::sim::{BusTiming, Conditions, Ms5611Sim, SimClock};
use baro_drivers::{Measurement, Ms5611, Osr, Ready, Scheduler, SpiInterface};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

const SENSORS: usize = 6;

type SpiBaro = Ms5611<SpiInterface<Ms5611Sim<Conditions>>, Ready>;

fn bank(clock: &SimClock) -> Vec<SpiBaro> {
    (0..SENSORS)
        .map(|i| {
            let air = Conditions {
                pressure_mbar: 1000.0 + i as f64,
                temperature_celsius: 25.0,
            };
            let chip = Ms5611Sim::new(air, clock.clone())
                .with_timing(BusTiming::default())
                .with_seed(i as u64);
            Ms5611::new_with_spi(chip)
                .init(&mut clock.delay())
                .map_err(|e| e.error)
                .expect("model PROM is valid")
        })
        .collect()
}

fn six_sensors(c: &mut Criterion) {
    let mut group = c.benchmark_group("six_ms5611_spi_simulated_time");
    for osr in Osr::ALL {
        let scheduler = Scheduler::new(osr);
        group.bench_function(BenchmarkId::new("scheduler", osr.ratio()), |b| {
            let clock = SimClock::new();
            let mut sensors = bank(&clock);
            let mut delay = clock.delay();
            let mut out = [Measurement {
                temperature_centi_celsius: 0,
                pressure_pa: 0,
            }; SENSORS];
            b.iter_custom(|iters| {
                let start = clock.now_ns();
                for _ in 0..iters {
                    scheduler
                        .sample_all(&mut sensors, &mut delay, &mut out)
                        .expect("model answers");
                }
                Duration::from_nanos(clock.now_ns() - start)
            });
        });
        group.bench_function(BenchmarkId::new("one_by_one", osr.ratio()), |b| {
            let clock = SimClock::new();
            let mut sensors = bank(&clock);
            let mut delay = clock.delay();
            b.iter_custom(|iters| {
                let start = clock.now_ns();
                for _ in 0..iters {
                    for s in sensors.iter_mut() {
                        s.measure(&mut delay, osr).expect("model answers");
                    }
                }
                Duration::from_nanos(clock.now_ns() - start)
            });
        });
        println!(
            "OSR {}: conversion-time bound {} ns per cycle",
            osr.ratio(),
            scheduler.cycle_bound_ns()
        );
    }
    group.finish();
}

criterion_group!(benches, six_sensors);
criterion_main!(benches);
