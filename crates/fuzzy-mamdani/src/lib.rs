#![doc = include_str!("../README.md")]
#![no_std]
#![forbid(unsafe_code)]
// `!(x > 0)` is deliberate throughout: NaN must take the empty / degenerate branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

mod activation;
mod block;
mod builder;
mod defuzz;
mod engine;
mod error;
mod exact;
#[cfg(feature = "std")]
mod fis;
#[cfg(feature = "std")]
mod fll;
#[cfg(feature = "std")]
mod format;
mod hedge;
mod mf;
mod norms;
mod preset;
mod real;
mod rules;
#[cfg(feature = "std")]
mod surface;
mod variable;

pub use activation::{Activation, Comparison};
pub use block::RuleBlock;
pub use builder::{EngineBuilder, MAX_SAMPLES};
pub use defuzz::{Defuzzifier, Resolution};
pub use engine::{Engine, Scratch};
pub use error::{BuildError, EvalError};
#[cfg(feature = "std")]
pub use fis::{from_fis, to_fis};
#[cfg(feature = "std")]
pub use fll::{from_fll, to_fll};
#[cfg(feature = "std")]
pub use format::FileError;
pub use hedge::{Hedge, Hedges};
pub use mf::{Mf, MfError};
pub use norms::{SNorm, TNorm};
pub use preset::{
    GraspController, GraspScales, TERM_NAMES, TORQUE_RAW_MAX, grasp_controller, grasp_engine,
};
pub use real::Real;
pub use rules::{Consequent, Expr, Rule, parse_rule, rule_text};
#[cfg(feature = "plot")]
pub use surface::plot_surface;
#[cfg(feature = "std")]
pub use surface::{MAX_SURFACE_STEPS, surface, write_surface_csv};
pub use variable::{InputVariable, OutOfRange, OutputVariable, Term};
