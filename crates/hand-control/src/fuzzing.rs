//! Byte-level entry points for the coverage-guided fuzzer (`fuzz/`, `cargo xtask fuzz`) and
//! its corpus replay: each runs the crate's own parsing code on untrusted bytes, without a port.
//! Not a stable API.

pub use crate::servo_hand::{DecodedAnswer, decode_replies};

/// The bytes a simulated bus of `config`'s servos sends back for `input`, fed in chunks of at
/// most `chunk` bytes through the simulator thread's parse → execute path; a clock packet
/// advances at most `max_clock_step`.
#[cfg(feature = "sim")]
pub fn sim_answers(
    config: &crate::sim::SimConfig,
    input: &[u8],
    chunk: usize,
    max_clock_step: std::time::Duration,
) -> Vec<u8> {
    crate::sim::answer_bytes(config, input, chunk, max_clock_step)
}
