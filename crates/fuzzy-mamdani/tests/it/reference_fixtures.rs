//! Replays the scikit-fuzzy / pyfuzzylite rows of `fixtures/fuzzy/` (written by
//! `python/fixtures/fuzzy_reference.py`) on the exact path.
#![cfg(feature = "std")]

use std::path::{Path, PathBuf};

use fuzzy_mamdani::{Activation, Engine, EngineBuilder, Resolution, from_fis, from_fll};

/// Relative tolerance of the exact path against the references (scale: max(|reference|, 1)).
pub(crate) const TOLERANCE: f64 = 1e-6;

/// scikit-fuzzy's mean of maximum is the mean of its *grid points* at the maximum, so it is
/// only as exact as its output grid (step 0.005): the exact path must agree within one step,
/// on every row. Two clipped terms that share the maximum level up to rounding (e.g. tipping's
/// 7.517 / 7.483, both at 0.5034) are a tie in the references too: the generator settles
/// rounding-level differences before scikit-fuzzy's exact `==` (fixtures/README.md).
const MOM_GRID_STEP: f64 = 0.005;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/fuzzy")
}

pub(crate) struct Dataset {
    pub(crate) names: Vec<String>,
    pub(crate) rows: Vec<Vec<f64>>,
}

pub(crate) fn read_fld(path: &Path) -> Dataset {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let names = lines
        .next()
        .unwrap_or_default()
        .split_whitespace()
        .map(String::from)
        .collect();
    let rows = lines
        .map(|l| {
            l.split_whitespace()
                .map(|v| v.parse::<f64>().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    Dataset { names, rows }
}

/// The worst relative error per output column of `engine` on the dataset; `grid_mom` judges a
/// `_mom` column in steps of scikit-fuzzy's grid ([`MOM_GRID_STEP`]).
pub(crate) fn replay(engine: &Engine<f64>, data: &Dataset, grid_mom: bool) -> Vec<(String, f64)> {
    let n_in = engine.inputs().len();
    let mut scratch = engine.scratch();
    let mut worst: Vec<(String, f64)> = engine
        .outputs()
        .iter()
        .map(|o| (o.name.clone(), 0.0))
        .collect();
    let columns: Vec<usize> = engine
        .outputs()
        .iter()
        .map(|o| {
            data.names
                .iter()
                .position(|n| *n == o.name)
                .unwrap_or_else(|| panic!("no column {}", o.name))
        })
        .collect();
    for row in &data.rows {
        let out = engine
            .evaluate(&mut scratch, &row[..n_in])
            .unwrap_or_else(|e| panic!("{row:?}: {e}"));
        for (k, &col) in columns.iter().enumerate() {
            let want = row[col];
            let mut err = (out[k] - want).abs() / want.abs().max(1.0);
            assert!(err.is_finite(), "{row:?}: {} gave {}", worst[k].0, out[k]);
            if grid_mom && worst[k].0.ends_with("_mom") {
                // Judged in grid steps: TOLERANCE means one step of the reference's grid.
                err = (out[k] - want).abs() / MOM_GRID_STEP * TOLERANCE;
            }
            worst[k].1 = worst[k].1.max(err);
        }
    }
    worst
}

#[test]
fn every_fixture_engine_agrees_on_the_exact_path() {
    let (mut engines, mut failures) = (0, Vec::new());
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir())
        .expect("fixtures/fuzzy exists")
        .flatten()
        .map(|e| e.path())
        .collect();
    entries.sort();
    for fld in entries
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "fld") && !fuzzylite_semantics(p))
    {
        let data = read_fld(fld);
        assert!(
            data.rows.len() >= 1000,
            "{}: {} rows",
            fld.display(),
            data.rows.len()
        );
        let fll =
            std::fs::read_to_string(fld.with_extension("fll")).expect("an .fll beside each .fld");
        let engine = from_fll::<f64>(&fll).and_then(|e| Ok(e.with_resolution(Resolution::Exact)?));
        let engine = engine.unwrap_or_else(|e| panic!("{}: {e}", fld.display()));
        for (name, err) in replay(&engine, &data, true) {
            println!(
                "{:<22} {name:<14} worst relative error {err:.2e}",
                engine.name()
            );
            if err > TOLERANCE {
                failures.push(format!("{} {name}: {err:e}", engine.name()));
            }
        }
        engines += 1;
    }
    assert!(engines >= 5, "only {engines} fixture engines");
    assert!(failures.is_empty(), "beyond {TOLERANCE:e}: {failures:?}");
}

/// MATLAB's tipper as a `.fis` file gives the same rows as its `.fll` twin.
#[test]
fn tipper_fis_replays_like_its_fll_twin() {
    let fis = std::fs::read_to_string(dir().join("tipper.fis")).expect("tipper.fis");
    let engine = from_fis::<f64>(&fis)
        .and_then(|e| Ok(e.with_resolution(Resolution::Exact)?))
        .expect("imports");
    let worst = replay(&engine, &read_fld(&dir().join("tipper.fld")), true);
    assert!(worst[0].1 <= TOLERANCE, "{worst:?}");
}

/// The `fl_` engines are replayed as imported: fuzzylite's semantics (midpoint integration at
/// 100 cells, hedges in propositions and conclusions, `none` operators).
fn fuzzylite_semantics(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.starts_with("fl_"))
}

/// pyfuzzylite 8.0.6's rows of the `fl_` engines, replayed on the engines as `from_fll` reads
/// them (no resolution switched): every defuzzifier at 100 midpoints, every hedge.
#[test]
fn fuzzylite_semantics_replay_as_imported() {
    let mut names: Vec<String> = Vec::new();
    let (mut failures, mut activations, mut blocks) = (Vec::new(), Vec::new(), 0);
    let mut chained = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir())
        .expect("fixtures/fuzzy exists")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "fld") && fuzzylite_semantics(p))
        .collect();
    entries.sort();
    for fld in &entries {
        let data = read_fld(fld);
        assert!(data.rows.len() >= 1000, "{}", fld.display());
        let fll = std::fs::read_to_string(fld.with_extension("fll")).expect("an .fll beside");
        let engine = from_fll::<f64>(&fll).unwrap_or_else(|e| panic!("{}: {e}", fld.display()));
        assert!(
            engine
                .outputs()
                .iter()
                .all(|o| o.defuzzifier.resolution() == Some(Resolution::Midpoints(100))),
            "{} reads as fuzzylite's midpoints",
            fld.display()
        );
        activations.push(engine.activation().name());
        if engine.rules().iter().any(|r| r.antecedent.reads_outputs()) {
            chained.extend(engine.rule_blocks().iter().map(|b| b.activation.name()));
        }
        blocks = blocks.max(engine.rule_blocks().len());
        // What is read is what is written: the engine survives its own `.fll`.
        let again =
            from_fll::<f64>(&fuzzy_mamdani::to_fll(&engine).expect("writes")).expect("reads back");
        assert_eq!(again.rule_blocks(), engine.rule_blocks());
        assert_eq!(again.rules(), engine.rules());
        if engine.activation() != Activation::General {
            // The method decides the rows: the same engine under General does not give them.
            let general = EngineBuilder::from(&engine)
                .activation(Activation::General)
                .build()
                .expect("builds");
            let worst = replay(&general, &data, false)[0].1;
            assert!(
                worst > 1e-3,
                "{}: General gives its rows too",
                engine.name()
            );
        }
        for (name, err) in replay(&engine, &data, false) {
            println!(
                "{:<22} {name:<14} worst relative error {err:.2e}",
                engine.name()
            );
            if err > TOLERANCE {
                failures.push(format!("{} {name}: {err:e}", engine.name()));
            }
            names.push(name);
        }
    }
    for a in Activation::<f64>::NAMES {
        assert!(activations.contains(&a), "no engine under activation {a}");
    }
    assert!(blocks >= 2, "no engine with several rule blocks");
    // Chained engines under each way of visiting a block's rules: in order, from the end, and
    // all compared first.
    for a in ["General", "First", "Last", "Highest"] {
        assert!(chained.contains(&a), "no chained engine under {a}");
    }
    for d in ["centroid", "bisector", "mom", "som", "lom"] {
        assert!(
            names.iter().any(|n| n.ends_with(d)),
            "no {d} column replayed"
        );
    }
    assert!(failures.is_empty(), "beyond {TOLERANCE:e}: {failures:?}");
}
