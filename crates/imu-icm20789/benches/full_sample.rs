//! One full fingertip sample (IMU burst + barometer start and read) against the chip model:
//! CPU cost per sample, and the simulated bus time against the 400 kHz bound.
//!
//! Bound, counted on the wire (START, STOP and repeated START one bit time each, every byte
//! 8 bits + ACK): IMU burst = S + addr·W + reg + Sr + addr·R + 14 data + P = 156 bits;
//! barometer start = S + addr·W + 2 command bytes + P = 29 bits; barometer read =
//! S + addr·R + 9 data + P = 92 bits. 277 bits × 2.5 µs = 692.5 µs at 400 kHz.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use embedded_hal::delay::DelayNs;
use imu_icm20789::sim::{BIT_NS_400KHZ, ChipModel, Truth};
use imu_icm20789::{BaroMode, FrameOrder, Icm20789, RawSample};

/// Bits of one sample, from the frame layouts above (independent of the model's accounting).
const fn bits(writes: u64, reads: u64) -> u64 {
    let mut bits = 2; // START + STOP
    if writes > 0 {
        bits += 9 + 9 * writes;
    }
    if reads > 0 {
        bits += 9 + 9 * reads + if writes > 0 { 1 } else { 0 }; // Sr after a write
    }
    bits
}
const SAMPLE_BITS: u64 = bits(1, 14) + bits(2, 0) + bits(0, 9);

fn full_sample(c: &mut Criterion) {
    let chip = ChipModel::new(Truth::constant([0.0, 0.0, 9.81], [0.0; 3], 101_325.0), 42);
    let bus = chip.bus();
    let mut delay = chip.delay();
    let mut icm = Icm20789::new_with_i2c(chip);
    icm.init(&mut delay).expect("model answers");
    icm.init_barometer(&mut delay).expect("model answers");

    let sample = |icm: &mut Icm20789<ChipModel>, delay: &mut imu_icm20789::sim::SimDelay| {
        let conversion = icm
            .start_pressure(BaroMode::LowNoise, FrameOrder::PressureFirst)
            .expect("start");
        let imu = icm.read_imu().expect("imu");
        delay.delay_us(conversion.wait_us());
        let baro = icm.read_pressure(conversion).expect("baro");
        (imu, baro)
    };
    let before = bus.bits();
    black_box(sample(&mut icm, &mut delay));
    let sim_bits = bus.bits() - before;
    let bound_us = (SAMPLE_BITS * BIT_NS_400KHZ) as f64 / 1_000.0;
    let sim_us = (sim_bits * BIT_NS_400KHZ) as f64 / 1_000.0;
    println!(
        "bus time per sample at 400 kHz: bound {SAMPLE_BITS} bits = {bound_us} µs; \
         chip model clocked {sim_bits} bits = {sim_us} µs ({:.3} of the bound)",
        sim_us / bound_us
    );

    c.bench_function("full_sample (IMU burst + LN pressure, chip model)", |b| {
        b.iter(|| black_box(sample(&mut icm, &mut delay)))
    });

    let cal = icm.calibration().expect("read at init");
    let raw = RawSample {
        p_lsb: 9_000_000,
        t_lsb: 27_000,
    };
    c.bench_function("conversion float (f64, vendor A/B/C)", |b| {
        b.iter(|| cal.pressure_pa(black_box(raw)))
    });
    c.bench_function("conversion integer (i128 cross-ratio, mPa)", |b| {
        b.iter(|| cal.pressure_milli_pa(black_box(raw)))
    });
}

criterion_group!(benches, full_sample);
criterion_main!(benches);
