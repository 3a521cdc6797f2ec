//! The contact CNN against the papers' data: the IMU-pad dataset is the paper's collection,
//! and the drift check of the committed metrics. (Its own behaviour is tested in tactile-nets.)

use crate::common::root;
use paper_experiments::cnn_eval::{
    self, Case, METRICS_FILE, MODEL_DIR, NOISY_COPIES, SEED, SNR_DB,
};
use paper_experiments::data::imu_pad::{self, CHANNELS, Dataset, WINDOW};
use tactile_nets::NetError;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use tactile_nets::metrics::MetricsFile;

fn taps() -> Dataset {
    imu_pad::load(&root()).expect("the committed imu_pad dataset parses")
}

#[test]
fn dataset_is_the_papers_collection() {
    let taps = taps();
    assert_eq!(taps.len(), 2880, "72 positions x 8 depths x 5 repeats");
    assert_eq!(taps.windows.dim(), (2880, CHANNELS, WINDOW));
    assert_eq!(
        taps.depths_um(),
        [200, 400, 600, 800, 1000, 1200, 1400, 1600]
    );
    // Region = 3 · row group + column − 1 (§IV-A: 3 groups of 8 rows × 3 columns).
    assert!(
        taps.taps.iter().all(|t| usize::from(t.region)
            == 3 * ((usize::from(t.row) - 1) / 8) + usize::from(t.column) - 1)
    );
    // Augmentation: 1 + 20 windows per tap (5 → 105 per position); the copies are the tap
    // plus noise at 30 dB per signal.
    let one = Case::Depth(800).taps(&taps);
    let a = cnn_eval::augment(&taps, &one[..2], NOISY_COPIES, SNR_DB, SEED);
    assert_eq!(a.windows.len(), 2 * 21);
    let (orig, copies) = (&a.windows[0], &a.windows[1..21]);
    assert_eq!(Some(*orig), taps.window_values(one[0]));
    for c in 0..4 {
        let s = &orig[c * 38..(c + 1) * 38];
        let power = s.iter().map(|v| v * v).sum::<f32>() / 38.0;
        let noise: f32 = copies
            .iter()
            .flat_map(|w| (0..38).map(move |i| (w[c * 38 + i] - s[i]).powi(2)))
            .sum::<f32>()
            / (20.0 * 38.0);
        let snr_db = 10.0 * (power / noise).log10();
        assert!((snr_db - 30.0).abs() < 0.6, "signal {c}: {snr_db} dB");
    }
}

#[test]
fn committed_metrics_match_a_re_evaluation_of_the_committed_weights() -> Result<(), NetError> {
    let taps = taps();
    let committed = MetricsFile::from_json(&std::fs::read_to_string(
        root().join(MODEL_DIR).join(METRICS_FILE),
    )?)?;
    // Every Table I row × protocol × grouping of every net is committed.
    for variant in Variant::ALL {
        for grouping in ["samples", "taps"] {
            for protocol in ["trials", "kfold"] {
                for case in Case::all(&taps) {
                    let label = format!("{}/{grouping}/{protocol}/{}", variant.name(), case.name());
                    assert!(committed.row(&label).is_some(), "{label} not committed");
                }
            }
        }
    }
    let mut fresh = Vec::new();
    for which in cnn_eval::COMMITTED {
        let (acc, conf) = cnn_eval::evaluate_committed(&root(), &taps, which)?;
        fresh.push(cnn_eval::committed_row(which, acc, &conf));
    }
    let only_committed = MetricsFile {
        rows: committed
            .rows
            .iter()
            .filter(|r| r.label.starts_with("committed/"))
            .cloned()
            .collect(),
        ..committed.clone()
    };
    let drift = only_committed.drift(&cnn_eval::metrics_file(fresh, SEED), 1e-9);
    assert!(drift.is_empty(), "committed metrics drifted: {drift:#?}");
    // Each committed file says where its training windows sit after a tap's trigger: where
    // hand-sim cuts them.
    for which in cnn_eval::COMMITTED {
        let model = ContactCnn::load(&root().join(MODEL_DIR).join(which.file()))?;
        assert_eq!(
            model.trigger_offset(),
            Some(cnn_eval::training_centre_frames()),
            "{}",
            which.file()
        );
    }
    Ok(())
}

/// The range the CNNs state (`contact_cnn::Z_RANGE` spreads of each channel's training
/// values) holds every window of the pad's dataset, for every built-in variant; the most
/// extreme tap at three times its rates is flagged.
#[test]
fn every_dataset_window_is_in_range_and_three_times_the_most_extreme_is_not() -> Result<(), NetError>
{
    use tactile_nets::contact_cnn::WINDOW_VALUES;
    let taps = taps();
    let window = |i: usize| -> [f32; WINDOW_VALUES] {
        core::array::from_fn(|k| taps.windows[[i, k / WINDOW, k % WINDOW]])
    };
    for variant in Variant::ALL {
        let cnn = tactile_nets::pretrained::contact_cnn(variant)?;
        let (mean, scale) = cnn.input_scale();
        let mut extreme = (0, 0.0f32);
        for i in 0..taps.len() {
            let w = window(i);
            assert!(cnn.predict(&w)?.in_range, "{variant:?}, tap {i}");
            for (k, v) in w.iter().enumerate() {
                let z = ((v - mean[k / WINDOW]) / scale[k / WINDOW]).abs();
                if z > extreme.1 {
                    extreme = (i, z);
                }
            }
        }
        let tripled = window(extreme.0).map(|v| 3.0 * v);
        assert!(!cnn.predict(&tripled)?.in_range, "{variant:?}: {extreme:?}");
    }
    assert_eq!(CHANNELS * WINDOW, tactile_nets::contact_cnn::WINDOW_VALUES);
    Ok(())
}
