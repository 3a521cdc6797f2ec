//! The pad in a scene: built and stepped only when the scene names it.

use hand_sim::SimError;
use hand_sim::scene::{Scene, SceneConfig};
use hand_traits::TactileSource;

#[test]
fn a_scene_without_imu_pad_never_builds_or_steps_it() {
    let cfg = SceneConfig::from_toml("seed = 3").unwrap();
    assert!(cfg.imu_pad.is_none());
    let mut scene = Scene::build(&cfg).unwrap();
    scene.step_to(5_000_000_000).unwrap();
    assert!(scene.imu_pad.is_none());
    assert!(!scene.models().contains(&"imu_pad"));
}

#[test]
fn a_scene_with_imu_pad_builds_and_steps_it_at_30_hz() {
    let cfg = SceneConfig::from_toml("seed = 3\n[imu_pad]\n").unwrap();
    let mut scene = Scene::build(&cfg).unwrap();
    assert_eq!(scene.models(), vec!["imu_pad"]);
    scene.step_to(1_000_000_000).unwrap();
    let pad = scene.imu_pad.as_mut().unwrap();
    use hand_sim::scene::Model;
    // Frames from the first sample after the driver's initialisation (~0.13 s) to 1 s.
    let steps = pad.steps();
    assert!(
        (26..=27).contains(&steps),
        "{steps} frames in the first second"
    );
    let frame = pad.read_frame().unwrap();
    assert!(frame.pressure_pa.is_some());
    assert!((frame.accel_mps2[2] - 9.81).abs() < 0.1);
}

#[test]
fn scene_tables_reject_unknown_keys_and_bad_taps() {
    let unknown = SceneConfig::from_toml("seed = 1\n[imu_pad]\nwobble = 2\n");
    assert!(matches!(unknown, Err(SimError::Scene(_))));
    let off_grid = SceneConfig::from_toml(
        "seed = 1\n[imu_pad]\ntaps = [{ column = 4, row = 1, depth_mm = 1.0 }]\n",
    )
    .unwrap();
    assert!(matches!(
        Scene::build(&off_grid),
        Err(SimError::Config {
            field: "column",
            ..
        })
    ));
}
