//! The trade run's own CPU timing: a small loop, median of repeats. One-run wall-clock figures
//! on a shared machine; the criterion benches (`cargo xtask bench`) are the reference.

use std::hint::black_box;
use std::time::Instant;

/// How many times each measurement is repeated (the median is kept).
pub const REPEATS: usize = 31;

/// Median wall time of one call of `f`, in µs: `REPEATS` batches of `calls` calls each, after
/// one warm-up batch. The closure's result goes through [`black_box`] so it is not optimised
/// away.
pub fn median_us<R>(calls: usize, mut f: impl FnMut() -> R) -> f64 {
    let calls = calls.max(1);
    let mut batch = || {
        let t = Instant::now();
        for _ in 0..calls {
            black_box(f());
        }
        t.elapsed().as_secs_f64() * 1e6 / calls as f64
    };
    batch();
    let mut times: Vec<f64> = (0..REPEATS).map(|_| batch()).collect();
    times.sort_by(f64::total_cmp);
    times[REPEATS / 2]
}

/// The machine the costs were measured on: CPU model, logical CPUs, 1-minute load average.
pub fn machine() -> String {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| l.strip_prefix("model name")?.split(':').nth(1))
        .map_or("unknown CPU", str::trim)
        .to_owned();
    let cpus = std::thread::available_parallelism().map_or(0, usize::from);
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "?".into());
    format!("{model}, {cpus} logical CPUs, load average {load} at the start of the run")
}
