//! Learned tactile models on [dfdx](https://docs.rs/dfdx) (CPU, stable Rust): the force / weight
//! DNN and the contact-area MLP of a barometric fingertip (Kim, Lee, Chung & Lee, "Artificial
//! Intelligence-Based Optimal Grasping Control", Sensors 2020, §2.2 and §4), the contact CNN of
//! an IMU pad (Al & Martinez-Hernandez, "Multimodal barometric and inertial measurement unit
//! based tactile sensor for robot control", §IV-A) and the Levenberg–Marquardt softness network
//! of an underactuated hand ("Distinguish the Textures of Grasped Objects by Robotic Hand Using
//! Artificial Neural-Network", §3.3; below, the underactuated-hand softness paper). Data in,
//! weights and metrics out: the crate reads no dataset and prints nothing of its own (training
//! shows an indicatif progress bar only when [`train::TrainConfig::progress`] asks for one).
//!
//! The trained models are built in ([`pretrained`]). Without the default `std` feature the
//! crate is `no_std` and allocation-free: the built-in force DNN and contact MLPs run from
//! `'static` arrays ([`force_dnn::StaticForceDnn`], [`contact_mlp::StaticContactMlp`]) on a
//! fingertip's Cortex-M3 / M4F; everything marked `std` below needs the feature.
//!
//! - [`pretrained`]: the trained models, built in (`'static` arrays without `std`);
//! - [`io`]: weights as safetensors for any dfdx module, plus extra named tensors;
//! - [`train`]: a seeded minibatch Adam loop;
//! - [`metrics`]: a metrics file and its drift check;
//! - [`error`]: typed errors (wrong shape, non-finite input or output, bad files);
//! - [`activations`]: sigmoid / softmax that stay finite for any logit;
//! - [`frozen`]: the allocation-free inference form of any trained dfdx dense stack;
//! - [`norm`]: input standardisation;
//! - [`force_dnn`]: the force / weight DNN and its [`hand_traits::ForceEstimator`];
//! - [`contact_mlp`]: the MLP, its two heads and its [`hand_traits::ContactLocator`] (the pad
//!   and its eq. 4 labels are `aot-locate`'s);
//! - [`cnn_layers`], [`cnn_frozen`]: im2col convolution and max-pool on stable dfdx, and the
//!   plain-array inference path;
//! - [`contact_cnn`]: the contact CNN of Al & Martinez-Hernandez, §IV-A, and its
//!   [`hand_traits::ContactLocator`];
//! - [`softness`]: the 8 → 4 → 4 → 3 softness classifier (the underactuated-hand softness
//!   paper, §3.3) and its
//!   [`hand_traits::SoftnessClassifier`];
//! - [`softness_train`]: its Levenberg–Marquardt (and Adam) training;
//! - [`softness_features`]: our variant's finger-order-invariant inputs.
//!
//! ```
//! # #[cfg(feature = "std")] {
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
pub mod force_dnn;
pub mod frozen;
pub mod norm;
pub mod pretrained;

#[cfg(feature = "std")]
pub mod cnn_frozen;
#[cfg(feature = "std")]
pub mod cnn_layers;
#[cfg(feature = "std")]
pub mod contact_cnn;
#[cfg(feature = "std")]
pub mod io;
#[cfg(feature = "std")]
pub mod metrics;
#[cfg(feature = "std")]
pub mod softness;
#[cfg(feature = "std")]
pub mod softness_features;
#[cfg(feature = "std")]
pub mod softness_train;
#[cfg(feature = "std")]
pub mod train;

#[cfg(feature = "std")]
pub use error::NetError;
pub use error::RunError;
/// The `hand-traits` traits and values the models implement and return, so that a user needs
/// no other crate.
pub use hand_traits::{
    Contact, ContactLocator, ForceEstimate, ForceEstimator, Softness, SoftnessClassifier,
};
