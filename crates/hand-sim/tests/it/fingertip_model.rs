//! The fingertip read end to end: physics → three MS5611 chip models → SPI → the real driver's
//! scheduler → `PressureFrame`s.

use hand_sim::fingertip::{
    Cell, CellSet, ContactPatch, Fingertip, FingertipConfig, LawParams, TapConfig,
};
use hand_sim::scene::{Model, Scene, SceneConfig};
use hand_traits::TactileSource;

fn tap(row: u8, col: u8, force_kgf: f64) -> TapConfig {
    TapConfig {
        at_s: 0.1,
        hold_s: 1.0,
        row,
        col,
        rows: 1,
        cols: 1,
        force_kgf,
        offset_mm: [0.0, 0.0],
    }
}

fn config(osr: u16, taps: Vec<TapConfig>) -> FingertipConfig {
    FingertipConfig {
        osr,
        drift_hpa_per_min: 0.0,
        taps,
        ..FingertipConfig::default()
    }
}

#[test]
fn a_held_tap_reads_baseline_plus_the_law_through_the_driver() {
    let mut tip = Fingertip::new(&config(4096, vec![tap(1, 1, 9.0)]), 1).unwrap();
    tip.step_to(90_000_000).unwrap(); // before the tap: baseline only
    let before = *tip.frames().last().unwrap();
    tip.step_to(900_000_000).unwrap(); // 0.8 s into the hold: ≫ 20 ms time constant
    let held = *tip.frames().last().unwrap();
    let expected = LawParams::CALIBRATED.steady_rise_hpa(&ContactPatch::from_kgf(
        CellSet::EMPTY.with(Cell::new(1, 1).unwrap()),
        9.0,
    ));
    for (k, want) in expected.iter().enumerate() {
        let rise_hpa = f64::from(held.pressure_pa[k] - before.pressure_pa[k]) / 100.0;
        // OSR 4096: 0.012 mbar RMS per reading, two readings, 1 Pa quantisation each.
        assert!(
            (rise_hpa - want).abs() < 0.1,
            "sensor {}: read {rise_hpa:.3} law {:.3}",
            k + 1,
            want
        );
        // Seed 000 §4: "Each pressure sensor has an initial value of 1010.xx".
        assert!(
            (101_000.0..101_100.0).contains(&before.pressure_pa[k]),
            "{before:?}"
        );
    }
}

#[test]
fn the_nearest_sensor_rises_first() {
    // Area 1.1 (centre (-7.5, 4.5) mm) is 4.2 mm from sensor 3, 11.7 mm from sensor 2 and
    // 12.4 mm from sensor 1: at OSR 256 (1.2 ms per cycle) sensor 3 must cross first.
    let mut tip = Fingertip::new(&config(256, vec![tap(1, 1, 9.0)]), 2).unwrap();
    tip.step_to(300_000_000).unwrap();
    let frames = tip.frames();
    let base: Vec<f32> = (0..3)
        .map(|k| frames[..50].iter().map(|f| f.pressure_pa[k]).sum::<f32>() / 50.0)
        .collect();
    let crossing = |k: usize, pa: f32| {
        frames
            .iter()
            .find(|f| f.t_us > 100_000 && f.pressure_pa[k] - base[k] > pa)
            .map(|f| f.t_us)
    };
    let (s1, s3) = (crossing(0, 50.0).unwrap(), crossing(2, 50.0).unwrap());
    assert!(s3 < s1, "sensor 3 at {s3} µs, sensor 1 at {s1} µs");
    let delays: Vec<f64> = (0..3)
        .map(|k| {
            LawParams::CALIBRATED.arrival_delay_ms(
                &ContactPatch::from_kgf(CellSet::EMPTY.with(Cell::new(1, 1).unwrap()), 9.0),
                k,
            )
        })
        .collect();
    assert!(delays[2] < delays[1] && delays[1] < delays[0], "{delays:?}");
}

#[test]
fn a_shifted_press_is_the_press_at_its_position() {
    // Cell 1.1 moved half a cell right and cell 1.2 moved half a cell left press the same
    // spot (x = -6 mm, exact in f64): the same rises and the same arrival delays.
    let law = LawParams::CALIBRATED;
    let at = |col, dx| {
        ContactPatch::from_kgf(CellSet::EMPTY.with(Cell::new(1, col).unwrap()), 7.0)
            .shifted([dx, 0.0])
    };
    let (a, b) = (at(1, 1.5), at(2, -1.5));
    assert_eq!(law.steady_rise_hpa(&a), law.steady_rise_hpa(&b));
    for k in 0..3 {
        assert_eq!(law.arrival_delay_ms(&a, k), law.arrival_delay_ms(&b, k));
    }
    // And the shift moves the reading: sensor 3 at (−4.5, 1.5) mm feels the press on 1.1
    // (−7.5, 4.5) more once it moves right, towards it.
    assert!(law.steady_rise_hpa(&a)[2] > law.steady_rise_hpa(&at(1, 0.0))[2]);
    let mut far = tap(1, 1, 5.0);
    far.offset_mm = [1.6, 0.0];
    match Fingertip::new(&config(256, vec![far]), 1) {
        Err(err) => assert!(err.to_string().contains("offset_mm"), "{err}"),
        Ok(_) => panic!("a shift beyond half a cell was accepted"),
    }
}

#[test]
fn same_seed_same_frames_other_seed_other_noise() {
    let run = |seed| {
        let mut tip = Fingertip::new(&config(1024, vec![tap(2, 3, 7.0)]), seed).unwrap();
        tip.step_to(400_000_000).unwrap();
        tip.frames().to_vec()
    };
    let a = run(5);
    assert_eq!(a, run(5));
    assert_ne!(a, run(6));
    assert!(a.len() > 50);
}

#[test]
fn drift_rises_and_rezero_removes_it() {
    let cfg = FingertipConfig {
        drift_hpa_per_min: 1.0,
        ..FingertipConfig::default()
    };
    let mut tip = Fingertip::new(&cfg, 3).unwrap();
    let first = tip.read_frame().unwrap();
    tip.step_to(60_000_000_000).unwrap(); // one minute
    let later = *tip.frames().last().unwrap();
    let drift_hpa = f64::from(later.pressure_pa[0] - first.pressure_pa[0]) / 100.0;
    assert!((drift_hpa - 1.0).abs() < 0.1, "{drift_hpa}");
    let now = tip.now_ns();
    tip.physics().rezero(now);
    let after = tip.read_frame().unwrap();
    assert!((after.pressure_pa[0] - first.pressure_pa[0]).abs() < 10.0);
}

#[test]
fn a_scene_builds_and_steps_only_what_it_names() {
    let empty = Scene::build(&SceneConfig::from_toml("seed = 1").unwrap()).unwrap();
    assert!(empty.models().is_empty() && empty.fingertip.is_none());
    let mut scene =
        Scene::build(&SceneConfig::from_toml("seed = 1\n[fingertip]\nosr = 512\n").unwrap())
            .unwrap();
    assert_eq!(scene.models(), ["fingertip"]);
    scene.step_to(50_000_000).unwrap();
    let tip = scene.fingertip.as_ref().unwrap();
    assert!(tip.steps() > 0 && tip.now_ns() >= 50_000_000);
}

#[test]
fn bad_configs_are_typed_errors_that_name_the_field() {
    let err = |toml: &str| match Scene::build(&SceneConfig::from_toml(toml).unwrap()) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{toml} built"),
    };
    assert!(err("seed = 1\n[fingertip]\nosr = 300").contains("osr"));
    assert!(err("seed = 1\n[fingertip]\ntaps = [{ at_s = 0.0, hold_s = 1.0, row = 5, col = 1, force_kgf = 5.0 }]").contains("row"));
    let overlap = "seed = 1\n[fingertip]\ntaps = [{ at_s = 0.0, hold_s = 1.0, row = 1, col = 1, force_kgf = 5.0 }, { at_s = 0.5, hold_s = 1.0, row = 2, col = 1, force_kgf = 5.0 }]";
    assert!(err(overlap).contains("overlap"));
    assert!(err("seed = 1\n[fingertip]\ntaps = [{ at_s = 0.0, hold_s = 1.0, row = 1, col = 1, force_kgf = -5.0 }]").contains("taps"));
    let unknown = SceneConfig::from_toml("seed = 1\n[fingertip]\nosrr = 256")
        .unwrap_err()
        .to_string();
    assert!(
        unknown.contains("osrr") && unknown.contains("line 3"),
        "{unknown}"
    );
}
