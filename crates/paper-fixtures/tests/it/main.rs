//! paper-fixtures' integration tests, one binary: every fixture file parses and has a loader,
//! and every row of seeds 000, 001 and 002 agrees with what its paper says.

mod every_fixture;
mod seed000_tables;
mod seed001_tables;
mod seed002_tables;
