//! The frozen inference form: frozen stacks agree with dfdx, the activations and the dense
//! layers give known values, and bad shapes and inputs are typed errors.

use dfdx::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tactile_nets::frozen::{
    Dense, Freeze, HyperbolicTangent, Identity, Layer, Logistic, Relu, StaticDense, input,
};
use tactile_nets::{NetError, RunError};

/// Largest `|dfdx − frozen|` over `n` seeded inputs in `-span..span`.
fn max_gap<M, const I: usize, const O: usize>(net: &M, n: usize, span: f32) -> f32
where
    M: Module<Tensor<Rank1<I>, f32, Cpu>, Output = Tensor<Rank1<O>, f32, Cpu>> + Freeze,
    M::Frozen: Layer<[f32; I], Output = [f32; O]>,
    M::Error: core::fmt::Debug,
{
    let dev = Cpu::default();
    let fast = net.freeze().expect("a built module freezes");
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut gap = 0.0f32;
    for _ in 0..n {
        let x: [f32; I] = core::array::from_fn(|_| rng.random_range(-span..span));
        let slow = net.forward(dev.tensor(x)).array();
        let quick = fast.forward(x);
        for (a, b) in slow.iter().zip(quick) {
            gap = gap.max((a - b).abs());
        }
    }
    gap
}

#[test]
fn frozen_stacks_agree_with_dfdx() {
    let dev = Cpu::seed_from_u64(5);
    let a = dev.build_module::<(
        (Linear<3, 32>, Sigmoid),
        (Linear<32, 32>, ReLU),
        (Linear<32, 32>, Sigmoid),
        (Linear<32, 1>, Sigmoid),
    ), f32>();
    assert!(max_gap(&a, 200, 3.0) <= 1e-5);
    let mut b = dev.build_module::<(
        (Linear<9, 64>, ReLU, Dropout),
        (Linear<64, 32>, ReLU, Dropout),
        Linear<32, 24>,
    ), f32>();
    b.0.2.p = 0.3;
    assert!(max_gap(&b, 200, 3.0) <= 1e-5);
    let c = dev.build_module::<(Linear<40, 320>, Tanh, Linear<320, 9>), f32>();
    assert!(max_gap(&c, 50, 1.0) <= 1e-5);
    // The check can fail: a frozen copy of another network does not agree.
    let other =
        Cpu::seed_from_u64(6).build_module::<(Linear<40, 320>, Tanh, Linear<320, 9>), f32>();
    let (x, fast) = ([0.5f32; 40], other.freeze().expect("freezes"));
    let gap = (c.forward(dev.tensor(x)).array()[0] - fast.forward(x)[0]).abs();
    assert!(gap > 1e-3, "gap {gap}");
}

#[test]
fn activations_and_checks() -> Result<(), NetError> {
    let x = [-2.0f32, 0.0, 3.0, f32::MAX, -f32::MAX];
    assert_eq!(Relu.forward(x), [0.0, 0.0, 3.0, f32::MAX, 0.0]);
    assert_eq!(Identity.forward(x), x);
    let s = Logistic.forward(x);
    assert!(s.iter().all(|v| (0.0..=1.0).contains(v)) && s[1] == 0.5);
    assert!(HyperbolicTangent.forward(x).iter().all(|v| v.abs() <= 1.0));
    assert!(matches!(
        Dense::<2, 2>::new(&[1.0; 3], &[0.0; 2]),
        Err(NetError::TensorMismatch { .. })
    ));
    assert!(Dense::<2, 2>::new(&[1.0; 4], &[0.0; 3]).is_err());
    let d = Dense::<2, 2>::new(&[1.0, 2.0, 3.0, 4.0], &[0.5, -0.5])?;
    assert_eq!(d.forward([1.0, 1.0]), [3.5, 6.5]);
    assert_eq!(input::<2>(&[1.0, 2.0])?, [1.0, 2.0]);
    assert!(matches!(
        input::<2>(&[1.0]),
        Err(RunError::Shape {
            expected: 2,
            got: 1
        })
    ));
    assert!(matches!(
        input::<2>(&[1.0, f32::NAN]),
        Err(RunError::NonFinite { index: 1 })
    ));
    static W: [[f32; 2]; 2] = [[1.0, 2.0], [3.0, 4.0]];
    static B: [f32; 2] = [0.5, -0.5];
    assert_eq!(
        StaticDense::new(&W, &B).forward([1.0, 1.0]),
        d.forward([1.0, 1.0])
    );
    Ok(())
}
