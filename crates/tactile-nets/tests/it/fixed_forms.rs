//! The fixed-point softness net and contact CNNs against their float models: the outputs
//! within a stated tolerance and the classes alike on seeded random input in and past the
//! training range, the built-in forms as their run-time quantisation, the float models' typed
//! errors, and weights no scale can be chosen for (non-finite: refused; all zero: exact). Their
//! accuracy on the held-out sets is measured in paper-experiments (`docs/trade.md`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use tactile_nets::contact_cnn::{ContactCnn, REGIONS, Variant, WINDOW, WINDOW_VALUES};
use tactile_nets::fixed::{FixedContactCnn, FixedSoftnessNet};
use tactile_nets::pretrained::{self, FIXED_SOFTNESS, SOFTNESS};
use tactile_nets::softness::{CLASSES, InputScale, N_PARAMS, N_VARIABLES, SoftnessNet};
use tactile_nets::{ContactLocator, NetError, RunError, SoftnessClassifier};

/// A grasp-like series of `samples` readings drawn over each variable's training range
/// widened by 20 % of its span on each side.
fn series(rng: &mut ChaCha8Rng, scale: &InputScale, samples: usize) -> Vec<f32> {
    let range = scale.range();
    (0..samples * N_VARIABLES)
        .map(|i| {
            let [lo, hi] = range[i % N_VARIABLES];
            let margin = 0.2 * (hi - lo);
            rng.random_range(lo - margin..=hi + margin)
        })
        .collect()
}

/// The gap between the largest value and the next.
fn margin(v: &[f32]) -> f32 {
    let mut s = v.to_vec();
    s.sort_by(|a, b| b.total_cmp(a));
    s[0] - s[1]
}

#[test]
fn the_fixed_softness_net_scores_and_classifies_as_the_float_one() -> Result<(), RunError> {
    // Tolerances: a sample's outputs within 0.02 (the logistic table's 1e-4 through the second
    // layer's weights of up to ~70), a series' mean scores within 0.005; the class alike unless
    // the float scores' top two lie within twice that.
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut worst_sample, mut worst_score, mut alike, mut decided) = (0.0f32, 0.0f32, 0, 0);
    for _ in 0..300 {
        let len = rng.random_range(1..=141);
        let s = series(&mut rng, SOFTNESS.scale(), len);
        for sample in s.chunks_exact(N_VARIABLES) {
            let (a, b) = (
                SOFTNESS.sample_outputs(sample)?,
                FIXED_SOFTNESS.sample_outputs(sample)?,
            );
            for k in 0..CLASSES {
                worst_sample = worst_sample.max((a[k] - b[k]).abs());
            }
        }
        let (a, b) = (SOFTNESS.assess(&s)?, FIXED_SOFTNESS.assess(&s)?);
        for k in 0..CLASSES {
            worst_score = worst_score.max((a.scores[k] - b.scores[k]).abs());
        }
        assert_eq!(
            (a.samples, a.readings_outside),
            (b.samples, b.readings_outside)
        );
        if margin(&a.scores) > 0.01 {
            decided += 1;
            alike += usize::from(a.class == b.class);
        }
        assert_eq!(FIXED_SOFTNESS.predict(&s)?, b.class);
    }
    println!(
        "softness: worst sample output gap {worst_sample:.5}, worst score gap {worst_score:.5}, \
         {alike} of {decided} decided series alike"
    );
    assert!(worst_sample < 0.02, "{worst_sample}");
    assert!(worst_score < 0.005, "{worst_score}");
    assert_eq!(alike, decided);
    assert!(decided >= 250, "{decided}");
    Ok(())
}

#[test]
fn the_built_in_fixed_softness_net_is_its_float_net_quantised_at_run_time() -> Result<(), NetError>
{
    // One rule: build.rs's integers are the run-time quantisation's, from the static arrays or
    // from the weights file.
    assert_eq!(FixedSoftnessNet::quantise(&SOFTNESS)?, FIXED_SOFTNESS);
    assert_eq!(
        FixedSoftnessNet::quantise(&pretrained::softness()?)?,
        FIXED_SOFTNESS
    );
    assert_eq!(FIXED_SOFTNESS.scale(), SOFTNESS.scale());
    Ok(())
}

#[test]
fn the_fixed_softness_net_gives_the_float_nets_errors() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut s = series(&mut rng, SOFTNESS.scale(), 5);
    for bad in [&[][..], &s[..7], &s[..N_VARIABLES + 1]] {
        assert_eq!(FIXED_SOFTNESS.scores(bad), SOFTNESS.scores(bad));
        assert!(matches!(
            FIXED_SOFTNESS.scores(bad),
            Err(RunError::Shape { .. })
        ));
    }
    // A NaN in the third sample: its index in the series.
    s[2 * N_VARIABLES + 5] = f32::NAN;
    let e = Some(RunError::NonFinite {
        index: 2 * N_VARIABLES + 5,
    });
    assert_eq!(FIXED_SOFTNESS.scores(&s).err(), e);
    assert_eq!(SOFTNESS.scores(&s).err(), e);
    assert_eq!(FIXED_SOFTNESS.assess(&s).err(), e);
    let mut classifier = FIXED_SOFTNESS;
    assert_eq!(classifier.classify(&s).err(), e);
    assert_eq!(
        FIXED_SOFTNESS.sample_outputs(&s[..3]),
        Err(RunError::Shape {
            expected: N_VARIABLES,
            got: 3
        })
    );
    // A finite reading whose distance from the training minimum overflows, on a variable that
    // never varied (gain 0): both models report the overflow.
    let mut scale = *SOFTNESS.scale();
    scale.gain[0] = 0.0;
    scale.min[0] = -3e38;
    let flat = SOFTNESS.flat();
    let float = SoftnessNet::from_flat(&flat, scale).expect("N_PARAMS values");
    let fixed = FixedSoftnessNet::quantise(&float).expect("finite weights");
    let mut sample = s[..N_VARIABLES].to_vec();
    sample[0] = 3e38;
    assert!(matches!(
        float.sample_outputs(&sample),
        Err(RunError::NonFiniteOutput { .. })
    ));
    assert!(matches!(
        fixed.sample_outputs(&sample),
        Err(RunError::NonFiniteOutput { .. })
    ));
}

#[test]
fn quantising_a_softness_net_refuses_non_finite_weights_and_keeps_zeros_exact()
-> Result<(), NetError> {
    let flat = SOFTNESS.flat();
    // Parameter 32 + 4 + 3 is `net.1.weight`'s fourth value (flat order: w1, b1, w2, …).
    for (at, tensor, index) in [(3, "net.0.weight", 3), (32 + 4 + 3, "net.1.weight", 3)] {
        for bad in [f32::NAN, f32::INFINITY] {
            let mut p = flat;
            p[at] = bad;
            let net = SoftnessNet::from_flat(&p, *SOFTNESS.scale()).expect("N_PARAMS values");
            match FixedSoftnessNet::quantise(&net) {
                Err(NetError::NonFiniteWeight {
                    tensor: t,
                    index: i,
                }) => {
                    assert_eq!((t.as_str(), i), (tensor, index));
                }
                other => panic!("{bad} in {tensor}: {other:?}"),
            }
        }
    }
    // All zeros: no scale to choose, and none needed. Every logistic reads 0 (σ = ½), every
    // score is its bias exactly.
    let mut p = [0.0f32; N_PARAMS];
    let b3 = [0.25f32, -1.5, 3.0];
    p[N_PARAMS - CLASSES..].copy_from_slice(&b3);
    let net = SoftnessNet::from_flat(&p, *SOFTNESS.scale()).expect("N_PARAMS values");
    let fixed = FixedSoftnessNet::quantise(&net)?;
    let s = series(&mut ChaCha8Rng::seed_from_u64(13), SOFTNESS.scale(), 4);
    assert_eq!(fixed.scores(&s)?, b3);
    assert_eq!(net.scores(&s)?, b3);
    Ok(())
}

thread_local! {
    /// Heap allocations made on this thread (each test runs on its own).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// The system allocator, counting each thread's allocations: what shows that a call made
/// none.
struct Counting;

// SAFETY: every call is passed to the system allocator unchanged; the count is a
// thread-local `Cell` whose access allocates nothing.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract, passed on.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn the_fixed_softness_net_is_static_and_allocation_free() -> Result<(), RunError> {
    // What a `no_std` firmware needs of it: a `'static` value it can copy (flash), calls that
    // touch no heap. (That it builds without `std` is `cargo xtask test`'s no_std build for
    // the Cortex-M3: the module is not behind the `std` feature.)
    fn copy_static<T: Copy + Send + Sync + 'static>(t: &'static T) -> T {
        *t
    }
    let mut net = copy_static(&FIXED_SOFTNESS);
    let s = series(&mut ChaCha8Rng::seed_from_u64(14), SOFTNESS.scale(), 141);
    let before = ALLOCATIONS.with(Cell::get);
    let scores = net.scores(&s)?;
    let class = net.classify(&s)?;
    let assessment = net.assess(&s)?;
    let sample = net.sample_outputs(&s[..N_VARIABLES])?;
    let err = net.scores(&s[..3]);
    assert_eq!(ALLOCATIONS.with(Cell::get), before, "a call allocated");
    assert_eq!((assessment.scores, assessment.class), (scores, class));
    assert!(sample.iter().all(|v| v.is_finite()) && err.is_err());
    Ok(())
}

/// A tap-like window of `float`'s inputs: a pulse of random height and timing on each channel
/// (up to 4 training spreads), on noise of 0.3 spreads.
fn window(rng: &mut ChaCha8Rng, float: &ContactCnn) -> [f32; WINDOW_VALUES] {
    let (mean, scale) = float.input_scale();
    let height: [f32; 4] = core::array::from_fn(|_| rng.random_range(-4.0..4.0));
    let centre: f32 = rng.random_range(12.0..26.0);
    core::array::from_fn(|i| {
        let (c, t) = (i / WINDOW, (i % WINDOW) as f32);
        let pulse = height[c] * (-(t - centre).powi(2) / 20.0).exp();
        mean[c] + scale[c] * (pulse + rng.random_range(-0.3..0.3))
    })
}

#[test]
fn each_fixed_contact_cnn_locates_as_its_float_model() -> Result<(), NetError> {
    // Tolerances: each logit within 1e-3 of the largest logit's magnitude (block scaling keeps
    // 15 bits of each layer's largest value, ~3e-5 of it per layer); the region alike unless
    // the float logits' top two lie within twice that; the confidence within 0.01.
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    for variant in Variant::ALL {
        let float = pretrained::contact_cnn(variant)?;
        let fixed = FixedContactCnn::quantise(&float)?;
        assert_eq!(fixed.variant(), variant);
        assert_eq!(fixed.trigger_offset(), float.trigger_offset());
        let mut locator = fixed.clone();
        let (mut worst, mut worst_conf, mut alike, mut decided) = (0.0f32, 0.0f32, 0, 0);
        let windows: Vec<_> = (0..500).map(|_| window(&mut rng, &float)).collect();
        for w in &windows {
            let (a, b) = (float.logits(w)?, fixed.logits(w)?);
            let top = a.iter().fold(0.0f32, |m, v| m.max(v.abs()));
            let gap = a
                .iter()
                .zip(&b)
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            worst = worst.max(gap / top);
            let (pa, pb) = (float.predict(w)?, fixed.predict(w)?);
            if margin(&a) > 2e-3 * top {
                decided += 1;
                alike += usize::from(pa.region == pb.region);
            }
            if pa.region == pb.region {
                worst_conf = worst_conf.max((pa.confidence - pb.confidence).abs());
            }
            let c = locator.locate(w)?;
            assert_eq!(
                (c.region, c.regions, c.confidence),
                (u16::from(pb.region), REGIONS as u16, pb.confidence)
            );
        }
        println!(
            "{variant:?}: worst logit gap {worst:.2e} of the largest logit, {alike} of {decided} \
             decided windows alike, worst confidence gap {worst_conf:.4}"
        );
        assert!(worst < 1e-3, "{variant:?}: {worst}");
        assert!(worst_conf < 0.01, "{variant:?}: {worst_conf}");
        assert_eq!(alike, decided, "{variant:?}");
        assert!(decided >= 450, "{variant:?}: {decided}");
        assert_eq!(
            fixed.classify_batch(&windows)?,
            windows
                .iter()
                .map(|w| fixed.predict(w).map(|p| p.region))
                .collect::<Result<Vec<_>, _>>()?
        );
    }
    Ok(())
}

#[test]
fn the_fixed_contact_cnn_gives_the_float_models_errors() -> Result<(), NetError> {
    let float = pretrained::contact_cnn(Variant::Small)?;
    let fixed = FixedContactCnn::quantise(&float)?;
    let w = window(&mut ChaCha8Rng::seed_from_u64(16), &float);
    let shape = |r: Result<[f32; REGIONS], NetError>| match r {
        Err(NetError::Shape { expected, got }) => Some((expected, got)),
        _ => None,
    };
    assert_eq!(shape(fixed.logits(&w[..151])), Some((WINDOW_VALUES, 151)));
    assert_eq!(shape(float.logits(&w[..151])), Some((WINDOW_VALUES, 151)));
    let mut nan = w;
    nan[40] = f32::NAN;
    assert!(matches!(
        fixed.predict(&nan),
        Err(NetError::NonFinite { index: 40 })
    ));
    // Finite, but the network's values overflow `f32`: both report it.
    let huge = [f32::MAX; WINDOW_VALUES];
    for r in [fixed.logits(&huge), float.logits(&huge)] {
        assert!(matches!(r, Err(NetError::NonFiniteOutput { .. })), "{r:?}");
    }
    assert!(fixed.clone().locate(&[0.0; 3]).is_err());
    Ok(())
}

/// `cnn` with tensor `name` replaced by `f(values)`.
fn edited(cnn: &ContactCnn, name: &str, f: impl Fn(&mut [f32])) -> Result<ContactCnn, NetError> {
    let mut file = cnn.to_file()?;
    let t = file.tensor(name).expect("a CNN tensor");
    let (shape, mut values) = (t.shape.clone(), t.data.clone());
    f(&mut values);
    file.insert(name, &shape, &values)?;
    ContactCnn::from_file(&file)
}

#[test]
fn quantising_a_cnn_refuses_non_finite_weights_and_keeps_zeros_exact() -> Result<(), NetError> {
    let paper = pretrained::contact_cnn(Variant::Paper)?;
    // A file cannot store a NaN, but a model built in memory (a diverged training) can hold
    // one: the float model runs into a NaN output, the quantisation refuses it by name.
    for (name, index) in [("net.1.0.weight", 1000), ("net.1.2.bias", 8)] {
        let bad = edited(&paper, name, |v| v[index] = f32::NAN)?;
        match FixedContactCnn::quantise(&bad) {
            Err(NetError::NonFiniteWeight { tensor, index: i }) => {
                assert_eq!((tensor.as_str(), i), (name, index));
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    let inf = edited(&paper, "net.0.1.weight", |v| v[0] = f32::NEG_INFINITY)?;
    assert!(matches!(
        FixedContactCnn::quantise(&inf),
        Err(NetError::NonFiniteWeight { .. })
    ));
    // A kernel of zeros: each conv value is its filter's bias, so the logits do not depend on
    // the window; the fixed form keeps that (exact zeros, at an exponent that leaves the bias
    // they meet unrounded).
    let flat = edited(&paper, "net.0.1.weight", |v| v.fill(0.0))?;
    let fixed = FixedContactCnn::quantise(&flat)?;
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let (w1, w2) = (window(&mut rng, &paper), window(&mut rng, &paper));
    assert_eq!(fixed.logits(&w1)?, fixed.logits(&w2)?);
    let (a, b) = (flat.logits(&w1)?, fixed.logits(&w1)?);
    let top = a.iter().fold(0.0f32, |m, v| m.max(v.abs()));
    assert!(a.iter().zip(&b).all(|(a, b)| (a - b).abs() <= 1e-3 * top));
    // Every tensor zero: logits of exactly 0, confidence 1/9, region 0 (ties: the lower).
    let mut zero = paper.clone();
    for name in [
        "net.0.1.weight",
        "net.0.1.bias",
        "net.1.0.weight",
        "net.1.0.bias",
        "net.1.2.weight",
        "net.1.2.bias",
    ] {
        zero = edited(&zero, name, |v| v.fill(0.0))?;
    }
    let fixed = FixedContactCnn::quantise(&zero)?;
    assert_eq!(fixed.logits(&w1)?, [0.0; REGIONS]);
    let p = fixed.predict(&w1)?;
    assert_eq!(p.region, 0);
    assert!((p.confidence - 1.0 / 9.0).abs() < 1e-3, "{}", p.confidence);
    Ok(())
}
