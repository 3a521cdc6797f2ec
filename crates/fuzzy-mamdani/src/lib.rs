#![doc = include_str!("../README.md")]
#![no_std]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

mod builder;
mod defuzz;
mod engine;
mod error;
mod exact;
mod mf;
mod norms;
mod real;
mod rules;
mod variable;

pub use builder::{EngineBuilder, MAX_SAMPLES};
pub use defuzz::{Defuzzifier, Resolution};
pub use engine::{Engine, Scratch};
pub use error::{BuildError, EvalError};
pub use mf::{Mf, MfError};
pub use norms::{SNorm, TNorm};
pub use real::Real;
pub use rules::{Consequent, Expr, Rule, parse_rule, rule_text};
pub use variable::{InputVariable, OutOfRange, OutputVariable, Term};
