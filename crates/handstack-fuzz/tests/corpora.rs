//! `cargo xtask test` replays every fuzz target's committed inputs: its seeds
//! (`fuzz/seeds/TARGET/`), the corpus fuzzing grew from them (`fuzz/corpus/TARGET/`, minimised)
//! and its regressions (`fuzz/regressions/TARGET/`, one file per finding, kept after the fix).
//! Deterministic, no fuzzing: a panic here is a finding that came back.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out: Vec<PathBuf> = entries
        .map(|e| e.expect("a readable corpus entry").path())
        .filter(|p| p.is_file())
        .collect();
    out.sort();
    out
}

#[test]
fn every_corpus_replays_without_a_finding() {
    let mut findings = Vec::new();
    for t in handstack_fuzz::TARGETS {
        let [seeds, corpus, regressions] = ["seeds", "corpus", "regressions"]
            .map(|d| files(&root().join("fuzz").join(d).join(t.name)));
        assert!(
            !seeds.is_empty(),
            "{}: no seeds (cargo xtask fuzz --seed)",
            t.name
        );
        for path in seeds.iter().chain(&corpus).chain(&regressions) {
            let bytes = std::fs::read(path).expect("a readable corpus file");
            if catch_unwind(AssertUnwindSafe(|| (t.run)(&bytes))).is_err() {
                findings.push(path.display().to_string());
            }
        }
        eprintln!(
            "{:<13} {:>3} seeds, {:>5} corpus files, {:>3} regressions",
            t.name,
            seeds.len(),
            corpus.len(),
            regressions.len()
        );
    }
    assert!(
        findings.is_empty(),
        "inputs that fail again:\n{}",
        findings.join("\n")
    );
}

#[test]
fn the_committed_seeds_are_the_generated_ones() {
    for t in handstack_fuzz::TARGETS {
        let seeds = handstack_fuzz::seeds::seeds(&root(), t.name).expect("the fixtures read");
        assert!(!seeds.is_empty(), "{}: no seeds", t.name);
        for (name, bytes) in seeds {
            let path = root().join("fuzz/seeds").join(t.name).join(&name);
            let committed = std::fs::read(&path)
                .unwrap_or_else(|e| panic!("{}: {e} (cargo xtask fuzz --seed)", path.display()));
            assert!(
                committed == bytes,
                "{} differs from its generator (cargo xtask fuzz --seed)",
                path.display()
            );
        }
    }
}
