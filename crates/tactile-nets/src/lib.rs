//! Learned tactile models: the force / weight DNN and the contact-area MLP of a barometric
//! fingertip (Kim, Lee, Chung & Lee, "Artificial Intelligence-Based Optimal Grasping Control",
//! Sensors 2020, §2.2 and §4), the contact CNN of an IMU pad (Al & Martinez-Hernandez,
//! "Multimodal barometric and inertial measurement unit based tactile sensor for robot
//! control", §IV-A) and the Levenberg–Marquardt softness network of an underactuated hand
//! ("Distinguish the Textures of Grasped Objects by Robotic Hand Using Artificial
//! Neural-Network", §3.3; below, the underactuated-hand softness paper). Data in, weights and
//! metrics out: the crate reads no dataset and prints nothing of its own (training shows an
//! indicatif progress bar only when its configuration asks for one).
//!
//! Three feature levels:
//! - none (`default-features = false`): `no_std` and allocation-free — all four built-in
//!   models run from `'static` arrays ([`force_dnn::StaticForceDnn`],
//!   [`contact_mlp::StaticContactMlp`], [`contact_cnn::StaticContactCnn`],
//!   [`softness::SoftnessNet`]), in `f32` or fixed point ([`fixed`]), on a fingertip's
//!   Cortex-M3 / M4F;
//! - `std` (default): every model's weights files (a user's own, or the built-in ones) read
//!   with the `safetensors` crate and run on plain arrays — no ML framework in the dependency
//!   tree;
//! - `train`: training on [dfdx](https://docs.rs/dfdx) (CPU, stable Rust) and nalgebra
//!   (Levenberg–Marquardt), and dfdx's forward of each model as a reference.
//!
//! Modules:
//! - `pretrained`: the trained models, built in;
//! - `io` (`std`): weights files, named tensors in safetensors (dfdx modules too, with `train`);
//! - `metrics` (`std`): a metrics file and its drift check;
//! - `train` (`train`): a seeded minibatch Adam loop;
//! - `error`: typed errors (wrong shape, non-finite input or output, bad files);
//! - `activations`: sigmoid / softmax that stay finite for any logit;
//! - `frozen`: the allocation-free inference form of a dense stack;
//! - `fixed`: the models in fixed point, for cores without an FPU (the force DNNs, contact MLPs
//!   and softness net built in; the contact CNNs quantised at run time, `std`);
//! - `norm`: input standardisation;
//! - `force_dnn`: the force / weight DNN and its [`hand_traits::ForceEstimator`];
//! - `contact_mlp`: the MLP, its two heads and its [`hand_traits::ContactLocator`] (the pad
//!   and its eq. 4 labels are `aot-locate`'s);
//! - `contact_cnn`: the contact CNN of Al & Martinez-Hernandez, §IV-A, its `'static` and
//!   weights-file (`std`, through `cnn_frozen`) plain-array inference and its
//!   [`hand_traits::ContactLocator`]; `cnn_layers` (`train`): im2col convolution and max-pool
//!   on stable dfdx;
//! - `softness`: the 8 → 4 → 4 → 3 softness classifier (the underactuated-hand softness
//!   paper, §3.3) and its [`hand_traits::SoftnessClassifier`]; `softness_train` (`train`): its
//!   Levenberg–Marquardt (and Adam) training; `softness_features` (`train`): our variant's
//!   finger-order-invariant inputs.
//!
//! ```
//! # #[cfg(feature = "train")] {
//! use tactile_nets::contact_mlp::{ContactExample, ContactMlp, Head, TapReading, features};
//! use tactile_nets::train::TrainConfig;
//! use hand_traits::ContactLocator;
//!
//! // Two taps: cell 0 (area 1.1) pressed hard near sensor 3, cell 5 (1.6) near sensor 1.
//! let tap = |mask: u32, held_pa: [f32; 3], arrival_ms: [Option<f32>; 3]| {
//!     let reading = TapReading { baseline_pa: [101_000.0; 3], held_pa, arrival_ms };
//!     ContactExample::new(reading, mask)
//! };
//! let taps = [
//!     tap(1, [102_000.0, 101_000.0, 104_000.0], [Some(9.0), None, Some(3.0)]),
//!     tap(1 << 5, [104_000.0, 101_000.0, 102_000.0], [Some(3.0), None, Some(9.0)]),
//! ];
//! let config = TrainConfig { epochs: 150, batch_size: 2, learning_rate: 1e-2, l2: 0.001,
//!                            seed: 1, progress: false, label: String::new() };
//! let (mut mlp, _) = ContactMlp::train(&taps, Head::CellSet, &config)?;
//! let contact = mlp.locate(&features(&taps[1].reading))?;
//! assert_eq!((contact.region, contact.regions), (5, 24));
//! assert!(mlp.locate(&[0.0; 3]).is_err()); // wrong shape: a typed error, not a panic
//! # }
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

#![cfg_attr(not(feature = "std"), no_std)]

pub mod activations;
pub mod contact_mlp;
pub mod error;
pub mod fixed;
pub mod force_dnn;
pub mod frozen;
pub mod norm;
pub mod pretrained;
pub mod softness;

#[cfg(feature = "std")]
pub mod cnn_frozen;
#[cfg(feature = "train")]
pub mod cnn_layers;
pub mod contact_cnn;
#[cfg(feature = "std")]
pub mod io;
#[cfg(feature = "std")]
pub mod metrics;
#[cfg(feature = "train")]
pub mod softness_features;
#[cfg(feature = "train")]
mod softness_layers;
#[cfg(feature = "train")]
pub mod softness_train;
#[cfg(feature = "std")]
mod stored;
#[cfg(feature = "train")]
pub mod train;

#[cfg(feature = "std")]
pub use error::NetError;
pub use error::RunError;
/// The `hand-traits` traits and values the models implement and return, so that a user needs
/// no other crate.
pub use hand_traits::{
    Contact, ContactLocator, ForceEstimate, ForceEstimator, Softness, SoftnessClassifier,
};
