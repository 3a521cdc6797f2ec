//! fuzzylite's own Mamdani examples (and their `matlab/` and `octave/` ones), read in place from the pyfuzzylite 8.0.6 package in the
//! workspace venv (`$HANDSTACK_PYTHON`; `cargo xtask test` sets it, and without it the test is
//! skipped, saying so). Each `examples/mamdani/NAME.fll` comes with fuzzylite's rows in
//! `NAME.fld`; the files are fuzzylite's (GPL), so none is copied into this repository.
#![cfg(feature = "std")]

use std::path::PathBuf;
use std::process::Command;

use fuzzy_mamdani::{FileError, from_fll};

use fuzzy_mamdani::{Engine, EvalError};

use crate::reference_fixtures::{Dataset, TOLERANCE, read_fld};

/// The chained examples: an output variable read in a later rule's antecedent.
const CHAINED: [&str; 3] = ["Laundry", "SimpleDimmerChained", "SimpleDimmerInverse"];

/// pyfuzzylite's `examples/mamdani` directory, asked of the venv's Python.
fn examples_dir() -> Option<PathBuf> {
    let Some(python) = std::env::var_os("HANDSTACK_PYTHON") else {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
        return None;
    };
    let out = Command::new(python)
        .args([
            "-c",
            "import fuzzylite, pathlib; \
             print(pathlib.Path(fuzzylite.__file__).parent / 'examples' / 'mamdani')",
        ])
        .output()
        .expect("run the venv's python");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()))
}

/// Every example with rows either imports and gives fuzzylite's rows, or is refused as
/// unsupported, naming what; the chained ones import and agree.
#[test]
fn fuzzylites_mamdani_examples_replay_or_are_refused_by_name() {
    let Some(dir) = examples_dir() else { return };
    // The examples and the `matlab/` and `octave/` ones below them.
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten()
        .map(|e| e.path())
        .flat_map(|p| match std::fs::read_dir(&p) {
            Ok(sub) => sub.flatten().map(|e| e.path()).collect(),
            Err(_) => vec![p],
        })
        .filter(|p| p.extension().is_some_and(|e| e == "fld"))
        .collect();
    entries.sort();
    let (mut agreed, mut failures) = (Vec::new(), Vec::new());
    for fld in &entries {
        let fll = std::fs::read_to_string(fld.with_extension("fll")).expect("an .fll beside");
        let engine = match from_fll::<f64>(&fll) {
            Ok(engine) => engine,
            Err(e @ FileError::Unsupported { .. }) => {
                println!("{}: refused: {e}", fld.display());
                continue;
            }
            Err(e) => panic!("{}: {e}", fld.display()),
        };
        let data = read_fld(fld);
        assert!(!data.rows.is_empty(), "{}: no rows", fld.display());
        match agreement(&engine, &data) {
            Ok((worst, silent)) => println!(
                "{:<20} worst relative error {worst:.2e} over {} rows ({silent} where no rule \
                 fires: fuzzylite's NaN, our NoRuleFired)",
                engine.name(),
                data.rows.len()
            ),
            Err(e) => failures.push(format!("{}: {e}", engine.name())),
        }
        agreed.push(engine.name().to_owned());
    }
    assert!(failures.is_empty(), "beyond {TOLERANCE:e}: {failures:?}");
    assert_eq!(agreed.len(), entries.len(), "only {agreed:?} imported");
    for name in CHAINED {
        assert!(
            agreed.iter().any(|a| a == name),
            "{name} did not import from {}",
            dir.display()
        );
    }
}

/// The worst relative error (scale: max(|reference|, 1)) of `engine` against fuzzylite's rows,
/// and how many rows had no rule fire; an error names the first row beyond [`TOLERANCE`] or
/// where one side fired and the other did not (fuzzylite writes NaN for an output no rule
/// reaches; `evaluate` says [`EvalError::NoRuleFired`]).
fn agreement(engine: &Engine<f64>, data: &Dataset) -> Result<(f64, usize), String> {
    let n_in = engine.inputs().len();
    let columns: Vec<usize> = engine
        .outputs()
        .iter()
        .map(|o| data.names.iter().position(|n| *n == o.name))
        .collect::<Option<_>>()
        .ok_or("an output has no column")?;
    let mut scratch = engine.scratch();
    let (mut worst, mut silent) = (0.0_f64, 0);
    for row in &data.rows {
        match engine.evaluate(&mut scratch, &row[..n_in]) {
            Ok(out) => {
                for (k, &col) in columns.iter().enumerate() {
                    let err = (out[k] - row[col]).abs() / row[col].abs().max(1.0);
                    // NaN (one side silent) is beyond it too.
                    if err.is_nan() || err > TOLERANCE {
                        return Err(format!("{row:?}: output {k} gave {}", out[k]));
                    }
                    worst = worst.max(err);
                }
            }
            Err(EvalError::NoRuleFired { output }) if row[columns[output]].is_nan() => silent += 1,
            Err(e) => return Err(format!("{row:?}: {e}")),
        }
    }
    Ok((worst, silent))
}
