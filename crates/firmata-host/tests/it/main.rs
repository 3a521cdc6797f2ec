//! firmata-host's integration tests, one binary: byte-level vectors from the Firmata documents
//! and firmware sources, the parser under interleaving, truncation and arbitrary bytes, and the
//! `Board` against a board that never answers. (The board against a simulated Arduino on a pty
//! is tested in `firmata-sim`, which depends on this crate.)

mod board_silent;
mod parser;
mod vectors;
