//! Packs a grown corpus folder into its archive, or unpacks an archive into a folder
//! (`cargo xtask fuzz` runs it around each fuzzing run):
//!
//! - `fuzz-corpus pack DIR ARCHIVE`: every file of `DIR` into `ARCHIVE` (replaced), written
//!   deterministically (`handstack_fuzz::corpus`).
//! - `fuzz-corpus unpack ARCHIVE DIR`: every entry of `ARCHIVE` into `DIR`, which must be
//!   missing or empty.

use std::path::PathBuf;
use std::process::ExitCode;

use handstack_fuzz::corpus;

const USAGE: &str = "usage: fuzz-corpus pack DIR ARCHIVE | unpack ARCHIVE DIR";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [command, from, to] = args.as_slice() else {
        eprintln!("{USAGE}");
        return ExitCode::FAILURE;
    };
    let (from, to) = (PathBuf::from(from), PathBuf::from(to));
    let done = match command.as_str() {
        "pack" => corpus::pack(&from, &to),
        "unpack" => corpus::unpack(&from, &to),
        _ => {
            eprintln!("{USAGE}");
            return ExitCode::FAILURE;
        }
    };
    match done {
        Ok(n) => {
            println!(
                "{command}ed {n} inputs: {} -> {}",
                from.display(),
                to.display()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("fuzz-corpus: {e}");
            ExitCode::FAILURE
        }
    }
}
