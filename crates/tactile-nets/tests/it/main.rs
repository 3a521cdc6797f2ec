//! tactile-nets' integration tests, one binary: each model's seeded training, save → load bit
//! for bit, frozen inference against dfdx, typed errors on bad input and bad files, and
//! properties of the activations and the built-in models over arbitrary input. The training
//! data are synthetic, drawn from seeded generators in the tests; the papers' datasets and the
//! committed metrics are checked in paper-experiments.

mod common;
mod contact_cnn;
mod contact_mlp;
mod force_dnn;
mod softness;
