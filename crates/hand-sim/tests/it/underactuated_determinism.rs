//! Same seed → same bytes, different seed → different bytes; a scene builds and steps the hand
//! only when it names it.

use hand_sim::scene::{Model, Scene, SceneConfig};
use hand_sim::underactuated::dataset::{self, Set};

/// Runs every third grasp of the dataset seeded with `seed` (all kinds and sets appear) and
/// renders it as the committed files would be.
fn subset_bytes(seed: u64) -> String {
    let grasps: Vec<_> = dataset::specs(seed)
        .unwrap()
        .iter()
        .step_by(3)
        .map(|s| dataset::run(s).unwrap())
        .collect();
    let mut out = dataset::grasps_csv(&grasps);
    for set in Set::ALL {
        out += &dataset::series_csv(&grasps, set);
    }
    out
}

#[test]
fn same_seed_same_bytes_other_seed_other_bytes() {
    let a = subset_bytes(42);
    assert!(a.lines().count() > 1000, "the subset holds series");
    assert_eq!(a, subset_bytes(42));
    assert_ne!(a, subset_bytes(43));
}

#[test]
fn a_scene_without_the_hand_never_builds_or_steps_it() {
    let mut scene = Scene::build(&SceneConfig::from_toml("seed = 3").unwrap()).unwrap();
    scene.step_to(5_000_000_000).unwrap();
    assert!(scene.underactuated.is_none());
    assert!(!scene.models().contains(&"underactuated"));
}

#[test]
fn a_scene_with_the_hand_builds_and_steps_it() {
    let text = "seed = 3\n[underactuated]\nclosing_speed_mm_s = 2.0\n[underactuated.object]\nmaterial = \"wood\"\n";
    let mut scene = Scene::build(&SceneConfig::from_toml(text).unwrap()).unwrap();
    assert_eq!(scene.models(), ["underactuated"]);
    scene.step_to(1_000_000_000).unwrap();
    let hand = scene.underactuated.as_ref().unwrap();
    assert_eq!(hand.steps(), 20, "1 s of 50 ms steps");
    assert!(SceneConfig::from_toml("seed = 3\n[underactuated]\nspeed = 1\n").is_err());
}

/// Driven from outside with the travel its own stepper would command at each step, the hand
/// is the same hand to the bit: `drive_to` is the constant-speed close with the input given.
#[test]
fn driving_the_tendon_from_outside_is_the_same_close() {
    use hand_sim::underactuated::{Material, Underactuated, UnderactuatedConfig};
    for material in Material::ALL {
        let mut config = UnderactuatedConfig::default();
        config.object.material = material;
        config.duration_s = 600.0;
        let mut own = Underactuated::new(&config, 9).unwrap();
        let mut driven = Underactuated::new(&config, 9).unwrap();
        let step = own.step_ns();
        for k in 1..=400u64 {
            let t = k * step;
            own.step_to(t).unwrap();
            let res = config.stepper_resolution_mm;
            let t_s = t as f64 * 1e-9;
            let steps = (config.closing_speed_mm_s * t_s / res).floor();
            driven.drive_to(t, steps * res * 1e-3).unwrap();
            assert_eq!(own.fingers(), driven.fingers(), "{material:?} at step {k}");
            assert_eq!(own.sensor_volts(), driven.sensor_volts());
        }
        assert!(own.first_contact_ns().is_some(), "{material:?}: 20 s touch");
        assert_eq!(own.first_contact_ns(), driven.first_contact_ns());
    }
}
