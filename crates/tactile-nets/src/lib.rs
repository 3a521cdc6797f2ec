//! Learned tactile models on [dfdx](https://docs.rs/dfdx) (CPU, stable Rust): the force / weight
//! DNN (seed 000 §2.2) and contact-area MLP (seed 000 §4) of a barometric fingertip, and the parts every model of the stack shares.
//!
//! - [`io`]: weights as safetensors for any dfdx module, plus extra named tensors;
//! - [`train`]: a seeded minibatch Adam loop with an indicatif progress bar;
//! - [`metrics`]: the committed metrics file and its drift check;
//! - [`error`]: typed errors (wrong shape, non-finite input or output, bad files);
//! - [`activations`]: sigmoid / softmax that stay finite for any logit;
//! - [`frozen`]: the allocation-free inference form of any trained dfdx dense stack;
//! - [`norm`]: input standardisation;
//! - [`data::weights`]: Table 1 and the simulated weight series, tared;
//! - [`force_dnn`]: the force / weight DNN and its [`hand_traits::ForceEstimator`];
//! - [`force_eval`]: its recipes, Table 1 fit / leave-one-out and held-out evaluation;
//! - [`data::fingertip`]: the simulated fingertip's tap dataset, baselines and arrival times;
//! - [`pad`]: the 4 × 6 pad, eq. 4 labels and cell sets;
//! - [`contact_mlp`]: the MLP, its two heads and its [`hand_traits::ContactLocator`];
//! - [`contact_eval`]: the held-out split, metrics and committed models;
//! - [`data::imu_pad`]: the simulated ICM-20789 pad's 4 × 38 tap windows (seed 002);
//! - [`cnn_layers`], [`cnn_frozen`]: im2col convolution and max-pool on stable dfdx, and the
//!   plain-array inference path;
//! - [`contact_cnn`]: the contact CNN of seed 002 §IV-A and its [`hand_traits::ContactLocator`];
//! - [`cnn_eval`]: 30 dB augmentation, 80 / 20 × 10 and 5-fold protocols, committed models;
//! - [`data::underactuated`]: the simulated underactuated hand's softness grasps;
//! - [`softness`]: the 8 → 4 → 4 → 3 softness classifier (seed 001) and its
//!   [`hand_traits::SoftnessClassifier`];
//! - [`softness_train`]: its Levenberg–Marquardt (and Adam) training;
//! - [`softness_eval`]: the paper's protocol, confusion matrices and committed models;
//! - [`softness_features`]: our variant's finger-order-invariant inputs.
//! - [`jobs`]: the training commands (`handstack train MODEL`, `cargo xtask train MODEL`).
//!
//! ```
//! use tactile_nets::contact_mlp::{ContactMlp, Head, features};
//! use tactile_nets::data::fingertip::{Tap, TapReading, TapRecord};
//! use tactile_nets::train::TrainConfig;
//! use hand_traits::ContactLocator;
//!
//! // Two taps: cell 0 (area 1.1) pressed hard near sensor 3, cell 5 (1.6) near sensor 1.
//! let tap = |mask: u32, held: [f32; 3], arrival: [Option<f32>; 3]| TapRecord {
//!     tap: Tap { id: 0, osr: 4096, shape: "1".into(), size: 1, mask,
//!                average_area: tactile_nets::pad::average_area(mask), aot_region: 0,
//!                force_kgf: 5.0, repeat: 0, held_pa: held },
//!     reading: TapReading { baseline_pa: [101_000.0; 3], held_pa: held, arrival_ms: arrival },
//! };
//! let taps = [
//!     tap(1, [102_000.0, 101_000.0, 104_000.0], [Some(9.0), None, Some(3.0)]),
//!     tap(1 << 5, [104_000.0, 101_000.0, 102_000.0], [Some(3.0), None, Some(9.0)]),
//! ];
//! let refs: Vec<&TapRecord> = taps.iter().collect();
//! let config = TrainConfig { epochs: 150, batch_size: 2, learning_rate: 1e-2, l2: 0.001,
//!                            seed: 1, progress: false, label: String::new() };
//! let (mut mlp, _) = ContactMlp::train(&refs, Head::CellSet, &config)?;
//! let contact = mlp.locate(&features(&taps[1].reading))?;
//! assert_eq!((contact.region, contact.regions), (5, 24));
//! assert!(mlp.locate(&[0.0; 3]).is_err()); // wrong shape: a typed error, not a panic
//! # Ok::<(), tactile_nets::NetError>(())
//! ```

pub mod activations;
pub mod cnn_eval;
pub mod cnn_frozen;
pub mod cnn_layers;
pub mod contact_cnn;
pub mod contact_eval;
pub mod contact_mlp;
pub mod error;
pub mod force_dnn;
pub mod force_eval;
pub mod frozen;
pub mod io;
pub mod jobs;
pub mod metrics;
pub mod norm;
pub mod pad;
pub mod softness;
pub mod softness_eval;
pub mod softness_features;
pub mod softness_train;
pub mod train;

/// Datasets the models train on.
pub mod data {
    pub mod fingertip;
    pub mod imu_pad;
    pub mod underactuated;
    pub mod weights;
}

pub use error::NetError;
