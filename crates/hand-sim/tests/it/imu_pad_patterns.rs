//! Fig. 5 of seed 002 (§III-C): accelerometer and gyroscope x / y along the rows, per column.

use crate::imu_pad_common;

use hand_sim::imu_pad::TapPosition;
use imu_pad_common::{mean_by_position, taps, window_mean, window_peak_abs};

/// Signals of the window.
const AX: usize = 0;
const AY: usize = 1;
const GX: usize = 2;
const GY: usize = 3;

/// Mean over repeats of `f` at (column, row 1) and (column, row 24).
fn ends(depth: f64, f: impl Fn(&hand_sim::imu_pad::dataset::TapRecord) -> f64) -> [[f64; 2]; 3] {
    let positions: Vec<TapPosition> = (1..=3)
        .flat_map(|c| [1, 24].map(|r| TapPosition::new(c, r).unwrap()))
        .collect();
    let recs = taps(&positions, &[depth], 5, 21);
    let means = mean_by_position(&recs, depth, f);
    let at = |c: u8, r: u8| {
        means
            .iter()
            .find(|(p, _)| p.column() == c && p.row() == r)
            .unwrap()
            .1
    };
    [1, 2, 3].map(|c| [at(c, 1), at(c, 24)])
}

/// "Near zero": below a tenth of the column-2 swing of the same signal.
fn near_zero(v: f64, scale: f64) -> bool {
    v.abs() < 0.1 * scale
}

#[test]
fn accelerometer_x_and_y_follow_fig_5_in_every_column() {
    // acc x: col 1 positive → ~0, col 2 positive → negative, col 3 ~0 → negative. acc y:
    // Fig. 5's "opposite" read as a rigid tilt allows (docs/sim-calibration/imu_pad.md): the
    // acc x traces run from row 24 to row 1 — col 1 ~0 → positive, col 2 negative → positive,
    // col 3 negative → ~0. (The earlier law pinned acc y = −acc x at every place, one reading
    // for two axes, which no tilt seen through gravity gives.)
    for depth in [0.8, 1.6] {
        let ax = ends(depth, |r| window_mean(r, AX));
        let ay = ends(depth, |r| window_mean(r, AY));
        let scale = ax[1][0].abs() + ax[1][1].abs();
        assert!(
            ax[0][0] > 0.0 && near_zero(ax[0][1], scale),
            "{depth} col 1 acc x {:?}",
            ax[0]
        );
        assert!(
            ax[1][0] > 0.0 && ax[1][1] < 0.0,
            "{depth} col 2 acc x {:?}",
            ax[1]
        );
        assert!(
            near_zero(ax[2][0], scale) && ax[2][1] < 0.0,
            "{depth} col 3 acc x {:?}",
            ax[2]
        );
        assert!(
            near_zero(ay[0][0], scale) && ay[0][1] > 0.0,
            "{depth} col 1 acc y {:?}",
            ay[0]
        );
        assert!(
            ay[1][0] < 0.0 && ay[1][1] > 0.0,
            "{depth} col 2 acc y {:?}",
            ay[1]
        );
        assert!(
            ay[2][0] < 0.0 && near_zero(ay[2][1], scale),
            "{depth} col 3 acc y {:?}",
            ay[2]
        );
    }
}

#[test]
fn a_tap_and_its_row_column_mirror_read_differently() {
    // The finding the tilt law fixes (docs/learning.md §3): column 1 row 12 (region 3) and
    // column 2 row 1 (region 1) gave the same window. Their arms differ (3.5 mm across vs
    // 12.5 mm along), and so must the mean acc x / y over the hold, by more than the chip noise.
    for (p, q) in [((1, 12), (2, 1)), ((3, 1), (1, 24)), ((3, 13), (2, 24))] {
        let pos = [p, q].map(|(c, r)| TapPosition::new(c, r).unwrap());
        let recs = taps(&pos, &[1.6], 5, 24);
        let mean = |s: usize, at: TapPosition| {
            mean_by_position(&recs, 1.6, |r| window_mean(r, s))
                .iter()
                .find(|(q, _)| *q == at)
                .unwrap()
                .1
        };
        let [ax, ay] = [AX, AY].map(|s| pos.map(|at| mean(s, at)));
        let gap = (ax[0] - ax[1]).abs() + (ay[0] - ay[1]).abs();
        assert!(gap > 0.1, "{p:?} vs {q:?}: acc x {ax:?}, acc y {ay:?}");
    }
}

#[test]
fn gyroscope_amplitude_follows_fig_5_in_every_column() {
    // gyro x: col 1 zero → ±, col 2 ± throughout, col 3 ± → zero; gyro y opposite in cols 1
    // and 3, the same in col 2. "Zero" here: under a third of the far end (the chip model's
    // 1.5 mrad/s noise keeps the peak |ω| off zero).
    for depth in [0.8, 1.6] {
        let gx = ends(depth, |r| window_peak_abs(r, GX));
        let gy = ends(depth, |r| window_peak_abs(r, GY));
        // From zero at the first end to at least 3× that at the second.
        let from_zero = |what: &str, [zero, full]: [f64; 2]| {
            assert!(zero < full / 3.0, "{depth} {what}: {zero} then {full}");
        };
        let reversed = |[a, b]: [f64; 2]| [b, a];
        from_zero("col 1 gyro x, row 1 → 24", gx[0]);
        from_zero("col 3 gyro x, row 24 → 1", reversed(gx[2]));
        from_zero("col 1 gyro y, row 24 → 1", reversed(gy[0]));
        from_zero("col 3 gyro y, row 1 → 24", gy[2]);
        for g in [gx[1], gy[1]] {
            assert!((g[0] - g[1]).abs() < 0.25 * g[0], "{depth} col 2 {g:?}");
        }
    }
}

#[test]
fn gyroscope_swings_one_way_pressing_and_back_releasing() {
    // "positive and negative values": the pad tilts while pressing and tilts back while
    // releasing, so each rate has one sign, then the other; at column 1 row 24 the press
    // turns gyro x positive (a − c > 0) and at column 1 row 1 gyro y negative (a + c < 0).
    for (column, row, s, press_positive) in [(1, 24, GX, true), (1, 1, GY, false)] {
        let recs = taps(&[TapPosition::new(column, row).unwrap()], &[1.2], 3, 22);
        for r in &recs {
            let w = &r.window.signals[s];
            let (imax, max) = w
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .unwrap();
            let (imin, min) = w
                .iter()
                .enumerate()
                .min_by(|a, b| a.1.total_cmp(b.1))
                .unwrap();
            assert!(*max > 0.0 && *min < 0.0, "signal {s}: {w:?}");
            assert_eq!(imax < imin, press_positive, "signal {s}: {w:?}");
        }
    }
}

#[test]
fn imu_amplitude_grows_with_depth() {
    // §III-C / Table I: larger depths give stronger accelerometer and gyroscope signals. Each
    // signal is read where its tilt is large: acc x and gyro y at column 1 row 1, acc y and
    // gyro x at column 1 row 24.
    let p = [
        TapPosition::new(1, 1).unwrap(),
        TapPosition::new(1, 24).unwrap(),
    ];
    let depths = [0.2, 0.4, 0.8, 1.6];
    let recs = taps(&p, &depths, 5, 23);
    let amp = |d: f64, s: usize, at: usize| {
        mean_by_position(&recs, d, |r| window_peak_abs(r, s))
            .iter()
            .find(|(q, _)| *q == p[at])
            .unwrap()
            .1
    };
    for (s, at) in [(AX, 0), (GY, 0), (AY, 1), (GX, 1)] {
        for w in depths.windows(2) {
            assert!(
                amp(w[1], s, at) > amp(w[0], s, at),
                "signal {s}: {} mm vs {} mm",
                w[1],
                w[0]
            );
        }
    }
}
