//! The activations: known values of the sigmoid, its log and the softmax, at and beyond the
//! infinities.

use tactile_nets::activations::{log_sigmoid, sigmoid, softmax};

#[test]
fn sigmoid_known_values() {
    assert_eq!(sigmoid(0.0), 0.5);
    assert_eq!(sigmoid(f32::INFINITY), 1.0);
    assert_eq!(sigmoid(f32::NEG_INFINITY), 0.0);
    assert!((sigmoid(2.0) - 0.880_797).abs() < 1e-6);
    assert!((log_sigmoid(-100.0) + 100.0).abs() < 1e-4);
}

#[test]
fn softmax_known_values() {
    let p = softmax(&[0.0, (2.0f32).ln()]).unwrap_or_default();
    assert_eq!(p.len(), 2);
    assert!((p[0] - 1.0 / 3.0).abs() < 1e-6 && (p[1] - 2.0 / 3.0).abs() < 1e-6);
    assert_eq!(
        softmax(&[f32::INFINITY, 1.0, f32::INFINITY]),
        Some(vec![0.5, 0.0, 0.5])
    );
    assert_eq!(softmax(&[]), None);
    assert_eq!(softmax(&[1.0, f32::NAN]), None);
}
