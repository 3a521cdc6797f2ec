//! The contact MLP's quadratic base: a quadratic surface is fitted exactly, and too few rows
//! are refused.

use tactile_nets::contact_mlp::{N_FEATURES, QuadraticBase};

#[test]
fn a_quadratic_surface_is_fitted_exactly() {
    // row = 2 + a − 0.5·b·c, column = 3 + c² over a grid of inputs: a base recovers both.
    let mut rows = Vec::new();
    let mut targets = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            for k in 0..5 {
                let (a, b, c) = (i as f32 - 2.0, j as f32 * 0.5 - 1.0, k as f32 - 2.0);
                let mut z = [0.0f32; N_FEATURES];
                z[..3].copy_from_slice(&[a, b, c]);
                rows.push(z);
                targets.push([2.0 + a - 0.5 * b * c, 3.0 + c * c]);
            }
        }
    }
    let base = QuadraticBase::fit(&rows, &targets).expect("fits");
    for (z, t) in rows.iter().zip(&targets) {
        let p = base.at(z);
        assert!(
            (p[0] - t[0]).abs() < 1e-4 && (p[1] - t[1]).abs() < 1e-4,
            "{p:?} {t:?}"
        );
    }
    assert_eq!(QuadraticBase::fit(&[], &[]), None);
    assert_eq!(QuadraticBase::fit(&rows[..2], &targets[..1]), None);
}
