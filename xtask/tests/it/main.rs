//! xtask's integration tests, in one test binary: the architecture rules and the drawn crate
//! graph ([`architecture`]), and the fixtures check ([`fixtures_check`]).

mod architecture;
mod fixtures_check;
