//! The grasp preset: monotone, smooth, bounded, and a working `GraspPolicy`.

use fuzzy_mamdani::{grasp_controller, grasp_engine};
use hand_traits::{GraspObservation, GraspPolicy};

fn grid() -> Vec<f64> {
    (0..=80).map(|k| -1.0 + 0.025 * k as f64).collect()
}

/// Monotone at far below the actuator's resolution (integer steps of the 0…1023 scale): the
/// Gaussian NH / PH tails reach, at ~1e-5, past their neighbours' feet.
const TOL: f64 = 0.01;

#[test]
fn surface_is_monotone_in_error_and_in_rate() {
    let engine = grasp_engine::<f64>();
    let mut s = engine.scratch();
    let g = grid();
    let mut surface = vec![vec![0.0; g.len()]; g.len()];
    for (i, &e) in g.iter().enumerate() {
        for (j, &de) in g.iter().enumerate() {
            surface[i][j] = engine.evaluate(&mut s, &[e, de]).expect("fires everywhere")[0];
        }
    }
    for i in 0..g.len() {
        for j in 0..g.len() {
            if i + 1 < g.len() {
                assert!(
                    surface[i + 1][j] >= surface[i][j] - TOL,
                    "torque fell with error at e={} de={}",
                    g[i],
                    g[j]
                );
            }
            if j + 1 < g.len() {
                assert!(
                    surface[i][j + 1] <= surface[i][j] + TOL,
                    "torque rose with rate at e={} de={}",
                    g[i],
                    g[j]
                );
            }
        }
    }
    // Corners reach the ends of the torque scale; the origin holds at mid-scale.
    assert!(
        surface[80][0] > 1000.0 && surface[0][80] < 23.0,
        "{} {}",
        surface[80][0],
        surface[0][80]
    );
    assert!((surface[40][40] - 511.5).abs() < 1e-9);
}

#[test]
fn surface_is_smooth_no_step_between_neighbouring_grid_points() {
    // A step of 0.025 in either input moves at most 1/8 of a term spacing: the torque may change
    // by at most about one output-term spacing (1023 / 8) times that fraction, times 2 for safety.
    let engine = grasp_engine::<f64>();
    let mut s = engine.scratch();
    let g = grid();
    let bound = 2.0 * (1023.0 / 8.0) * (0.025 / 0.25);
    for &e in &g {
        let mut prev: Option<f64> = None;
        for &de in &g {
            let t = engine.evaluate(&mut s, &[e, de]).expect("fires")[0];
            if let Some(p) = prev {
                assert!(
                    (t - p).abs() <= bound,
                    "jump {} at e={e} de={de}",
                    (t - p).abs()
                );
            }
            prev = Some(t);
        }
    }
}

#[test]
fn policy_saturates_far_outside_and_respects_a_table_5_band() {
    let mut c = grasp_controller();
    let huge = GraspObservation {
        pressure_error_pa: 1e30,
        pressure_rate_pa_per_s: -1e30,
    };
    assert_eq!(
        c.effort(&huge).expect("clamped").to_torque_limit_raw(),
        1023
    );
    let none = GraspObservation {
        pressure_error_pa: -1e30,
        pressure_rate_pa_per_s: 1e30,
    };
    assert!(c.effort(&none).expect("clamped").to_torque_limit_raw() <= 23);
    let nan = GraspObservation {
        pressure_error_pa: f32::NAN,
        pressure_rate_pa_per_s: 0.0,
    };
    assert!(c.effort(&nan).is_err());
    // Paper cup (Table 5): 50…1023.
    let mut cup = grasp_controller().with_torque_band(50, 1023);
    assert!(cup.effort(&none).expect("clamped").to_torque_limit_raw() >= 50);
    let mut tissue = grasp_controller().with_torque_band(160, 370);
    assert_eq!(
        tissue.effort(&huge).expect("clamped").to_torque_limit_raw(),
        370
    );
}

/// The controller's fixed-size tables give the general engine's torques, bit for bit (the same
/// arithmetic in the same order), inside the universes, beyond them (clamped) and at ±∞; NaN
/// is the same typed error.
#[test]
fn the_controllers_tables_give_the_engines_torques() {
    use fuzzy_mamdani::EvalError;
    let engine = grasp_engine::<f32>();
    let mut s = engine.scratch();
    let mut c = grasp_controller();
    let scales = fuzzy_mamdani::GraspScales::default();
    let mut values: Vec<f32> = (0..=96).map(|k| -1.2 + 0.025 * k as f32).collect();
    values.extend([f32::INFINITY, f32::NEG_INFINITY, 1e-30, -1e-30]);
    for &e in &values {
        for &de in &values {
            let obs = GraspObservation {
                pressure_error_pa: e * scales.error_pa,
                pressure_rate_pa_per_s: de * scales.rate_pa_per_s,
            };
            // The engine gets the inputs as the controller normalises them.
            let normalised = [
                obs.pressure_error_pa / scales.error_pa,
                obs.pressure_rate_pa_per_s / scales.rate_pa_per_s,
            ];
            let want = engine.evaluate(&mut s, &normalised).expect("fires")[0];
            let got = c.torque_raw(&obs).expect("fires");
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "e={e} de={de}: {got} vs {want}"
            );
        }
    }
    let nan = GraspObservation {
        pressure_error_pa: f32::NAN,
        pressure_rate_pa_per_s: 0.0,
    };
    assert_eq!(
        c.torque_raw(&nan),
        Err(EvalError::NonFiniteInput { input: 0 })
    );
}
