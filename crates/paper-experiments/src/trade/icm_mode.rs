//! ICM-20789 pressure-mode knob (seed 002's pad chip): conversion time against the pressure
//! noise measured through the driver on the simulated chip.

use super::error::TradeError;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use imu_icm20789::sim::{ChipModel, Truth};
use imu_icm20789::{BaroMode, FrameOrder, Icm20789};

/// Task id.
pub const TASK: &str = "icm-pressure-mode";
/// Readings per mode.
pub const READINGS: usize = 400;
/// The constant true pressure, Pa.
pub const TRUE_PA: f64 = 101_325.0;
/// The chip model's seed.
pub const SEED: u64 = 20_789;

/// The task.
pub fn task() -> Task {
    Task {
        id: TASK,
        title: "ICM-20789 barometer: pressure mode",
        cost: CostKind::Wire,
        cost_label: "conversion time (datasheet max), µs — not CPU",
        better: Better::Lower,
        unit: "pressure rms error (Pa)",
        note: format!(
            "Cost: the mode's maximum conversion time (DS-000169 operation-mode table, \
             `BaroMode::conversion_time_max_us`): time the sensor converts, during which the \
             CPU is free. Quality: rms error of {READINGS} readings of a constant {TRUE_PA} Pa \
             through `Icm20789::measure_pressure` on `imu_icm20789::sim::ChipModel` (seed \
             {SEED}). The chip model draws its noise from the same datasheet table (LP 3.2, N \
             1.6, LN 0.8, ULN 0.4 Pa rms; seed 002 §III-A quotes LP / N / LN), so this checks \
             the driver's integer conversion path end to end and the model's noise rather \
             than discovering a new figure. The pad paper ran Low Noise; at its F(p) slope \
             near the 263-count (3.5 N) end, 1 Pa ≈ 7 mN."
        ),
    }
}

/// Each mode's rms error over [`READINGS`] readings.
pub fn noise_pa() -> Result<Vec<(BaroMode, f64)>, TradeError> {
    BaroMode::ALL
        .into_iter()
        .enumerate()
        .map(|(m, mode)| {
            let chip = ChipModel::new(
                Truth::constant([0.0; 3], [0.0; 3], TRUE_PA),
                SEED + m as u64,
            );
            let mut delay = chip.delay();
            let mut icm = Icm20789::new_with_i2c(chip);
            let err = |e| TradeError::input("simulated ICM-20789", format!("{e:?}"));
            icm.init(&mut delay).map_err(err)?;
            icm.init_barometer(&mut delay).map_err(err)?;
            let mut sum_sq = 0.0;
            for _ in 0..READINGS {
                let s = icm
                    .measure_pressure(mode, FrameOrder::PressureFirst, &mut delay)
                    .map_err(err)?;
                sum_sq += (f64::from(s.pressure_pa) - TRUE_PA).powi(2);
            }
            Ok((mode, (sum_sq / READINGS as f64).sqrt()))
        })
        .collect()
}

/// The setting label of a mode.
pub fn setting(mode: BaroMode) -> String {
    format!("{mode:?}")
}

/// One point per mode.
pub fn points() -> Result<Vec<Point>, TradeError> {
    Ok(noise_pa()?
        .into_iter()
        .map(|(mode, rms)| Point {
            task: TASK,
            knob: "pressure mode".into(),
            setting: setting(mode),
            cost_us: f64::from(mode.conversion_time_max_us()),
            accuracy: rms,
            pareto: false,
        })
        .collect())
}
