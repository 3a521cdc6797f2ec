//! `cargo xtask test` replays every fuzz target's committed inputs: its seeds
//! (`fuzz/seeds/TARGET/`), the corpus fuzzing grew from them (`fuzz/corpus/TARGET.tar.gz`, one
//! archive, minimised) and its regressions (`fuzz/regressions/TARGET/`, one file per finding,
//! kept after the fix). Deterministic, no fuzzing: a panic here is a finding that came back.

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

/// The targets `fuzz/runs.tsv` records a run of: each run leaves the target a corpus archive,
/// so a missing one is a lost corpus, not a target never fuzzed.
fn fuzzed() -> Vec<String> {
    let runs = std::fs::read_to_string(root().join("fuzz/runs.tsv")).unwrap_or_default();
    runs.lines()
        .skip(1)
        .filter_map(|l| l.split('\t').nth(2))
        .map(str::to_owned)
        .collect()
}

/// The entries of `fuzz/corpus/TARGET.tar.gz`, each named `ARCHIVE:ENTRY`.
fn corpus(target: &str, fuzzed: &[String]) -> Vec<(String, Vec<u8>)> {
    let archive = root().join("fuzz/corpus").join(format!("{target}.tar.gz"));
    if !archive.exists() {
        assert!(
            !fuzzed.iter().any(|f| f == target),
            "{target}: fuzz/runs.tsv records fuzzing it, but its corpus {} is missing",
            archive.display()
        );
        return Vec::new();
    }
    handstack_fuzz::corpus::read(&archive)
        .unwrap_or_else(|e| panic!("{target}: {e}"))
        .into_iter()
        .map(|(name, bytes)| (format!("{}:{name}", archive.display()), bytes))
        .collect()
}

#[test]
fn every_corpus_replays_without_a_finding() {
    let fuzzed = fuzzed();
    let mut findings = Vec::new();
    for t in handstack_fuzz::TARGETS {
        let [seeds, regressions] =
            ["seeds", "regressions"].map(|d| files(&root().join("fuzz").join(d).join(t.name)));
        assert!(
            !seeds.is_empty(),
            "{}: no seeds (cargo xtask fuzz --seed)",
            t.name
        );
        let corpus = corpus(t.name, &fuzzed);
        let entries = corpus.len();
        let read = |path: &PathBuf| {
            let bytes = std::fs::read(path).expect("a readable corpus file");
            (path.display().to_string(), bytes)
        };
        let inputs = seeds
            .iter()
            .map(read)
            .chain(corpus)
            .chain(regressions.iter().map(read));
        for (name, bytes) in inputs {
            if catch_unwind(AssertUnwindSafe(|| (t.run)(&bytes))).is_err() {
                findings.push(name);
            }
        }
        eprintln!(
            "{:<13} {:>3} seeds, {:>5} corpus entries, {:>3} regressions",
            t.name,
            seeds.len(),
            entries,
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

/// The cargo-fuzz project's targets are [`handstack_fuzz::TARGETS`]: each
/// `fuzz/fuzz_targets/NAME.rs` and the `[[bin]]` tables of `fuzz/Cargo.toml` are what
/// `cargo xtask fuzz --seed` writes from it, and no other target file is there.
#[test]
fn the_cargo_fuzz_project_is_written_from_the_targets() {
    use handstack_fuzz::{TARGETS, cargo_fuzz};
    let again = "differs from handstack_fuzz::TARGETS (cargo xtask fuzz --seed)";
    let manifest =
        std::fs::read_to_string(root().join("fuzz/Cargo.toml")).expect("fuzz/Cargo.toml");
    assert_eq!(
        cargo_fuzz::manifest(&manifest, &TARGETS).as_deref(),
        Some(manifest.as_str()),
        "fuzz/Cargo.toml {again}"
    );
    let mut names = Vec::new();
    for path in files(&root().join("fuzz/fuzz_targets")) {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let t = handstack_fuzz::target(&name).unwrap_or_else(|| {
            panic!(
                "{}: not a target of handstack_fuzz::TARGETS",
                path.display()
            )
        });
        let committed = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            committed,
            cargo_fuzz::target_source(t),
            "{} {again}",
            path.display()
        );
        names.push(name);
    }
    let mut want: Vec<&str> = TARGETS.iter().map(|t| t.name).collect();
    want.sort_unstable();
    assert_eq!(names, want, "fuzz/fuzz_targets/ {again}");
}
