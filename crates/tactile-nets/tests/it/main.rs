//! tactile-nets' integration tests, one binary: each model's seeded training, save → load bit
//! for bit, frozen inference against dfdx, typed errors on bad input and bad files, and
//! properties of the activations and the built-in models over arbitrary input. The training
//! data are synthetic, drawn from seeded generators in the tests; the papers' datasets and the
//! committed metrics are checked in paper-experiments.
//! The building blocks (safetensors files, the Adam loop, metrics files, standardisation, the
//! CNN's layers, the frozen layers, the quadratic base, the softness net's Jacobian and the
//! built-in models) are tested here too, through the public API.

mod activations;
mod cnn_layers;
mod common;
mod contact_cnn;
mod contact_mlp;
mod contact_mlp_model;
mod fixed;
mod fixed_forms;
mod force_dnn;
mod frozen;
mod io;
mod metrics;
mod norm;
mod pretrained;
mod quadratic_base;
mod softness;
mod softness_layers;
mod train;
