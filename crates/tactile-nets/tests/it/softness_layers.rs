//! The softness net's layers: the flat parameter vector round trips, and the analytic
//! Jacobian matches finite differences.

use nalgebra::SVector;
use tactile_nets::softness::{CLASSES, N_PARAMS, N_VARIABLES};
use tactile_nets::softness_train::Layers;

#[test]
fn flat_round_trip_and_jacobian_matches_finite_differences() {
    let p: Vec<f64> = (0..N_PARAMS)
        .map(|i| ((i * 37 % 17) as f64 - 8.0) / 9.0)
        .collect();
    let l = Layers::from_flat(&p).unwrap_or_else(|| unreachable!());
    assert_eq!(l.flat(), p);
    let z = SVector::<f64, N_VARIABLES>::from_fn(|i, _| (i as f64 - 3.5) / 4.0);
    let j = l.jacobian(&z, &l.forward(&z));
    let h = 1e-6;
    for q in 0..N_PARAMS {
        let mut up = p.clone();
        let mut dn = p.clone();
        up[q] += h;
        dn[q] -= h;
        let fu = Layers::from_flat(&up).map(|l| l.forward(&z).y);
        let fd = Layers::from_flat(&dn).map(|l| l.forward(&z).y);
        let (Some(fu), Some(fd)) = (fu, fd) else {
            unreachable!()
        };
        for k in 0..CLASSES {
            let num = (fu[k] - fd[k]) / (2.0 * h);
            assert!(
                (num - j[(k, q)]).abs() < 1e-7,
                "param {q} output {k}: {num} vs {}",
                j[(k, q)]
            );
        }
    }
}
