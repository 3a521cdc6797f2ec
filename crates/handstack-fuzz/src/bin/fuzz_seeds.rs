//! Writes every target's seed corpus to `fuzz/seeds/TARGET/NAME`, and the cargo-fuzz project's
//! target files and `[[bin]]` tables (`handstack_fuzz::cargo_fuzz`) (`cargo xtask fuzz --seed`):
//! usage `fuzz-seeds REPOSITORY_ROOT`.

use handstack_fuzz::cargo_fuzz;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn main() -> ExitCode {
    let Some(root) = std::env::args_os().nth(1).map(PathBuf::from) else {
        eprintln!("usage: fuzz-seeds REPOSITORY_ROOT");
        return ExitCode::FAILURE;
    };
    for t in handstack_fuzz::TARGETS {
        let seeds = match handstack_fuzz::seeds::seeds(&root, t.name) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("fuzz-seeds: {}: {e}", t.name);
                return ExitCode::FAILURE;
            }
        };
        let dir = root.join("fuzz/seeds").join(t.name);
        let written = std::fs::create_dir_all(&dir).and_then(|()| {
            seeds
                .iter()
                .try_for_each(|(name, bytes)| std::fs::write(dir.join(name), bytes))
        });
        if let Err(e) = written {
            eprintln!("fuzz-seeds: {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
        println!("{:<13} {:>3} seeds", t.name, seeds.len());
    }
    match write_cargo_fuzz(&root) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fuzz-seeds: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Writes `fuzz/fuzz_targets/NAME.rs` for every target (removing other `.rs` files there) and
/// the `[[bin]]` part of `fuzz/Cargo.toml`.
fn write_cargo_fuzz(root: &Path) -> Result<(), String> {
    let dir = root.join("fuzz/fuzz_targets");
    let io = |what: &Path, e: std::io::Error| format!("{}: {e}", what.display());
    for entry in std::fs::read_dir(&dir).map_err(|e| io(&dir, e))? {
        let path = entry.map_err(|e| io(&dir, e))?.path();
        let ours = path
            .file_stem()
            .and_then(|s| s.to_str())
            .is_some_and(|s| handstack_fuzz::target(s).is_some());
        if path.extension().is_some_and(|x| x == "rs") && !ours {
            std::fs::remove_file(&path).map_err(|e| io(&path, e))?;
        }
    }
    for t in &handstack_fuzz::TARGETS {
        let path = dir.join(format!("{}.rs", t.name));
        std::fs::write(&path, cargo_fuzz::target_source(t)).map_err(|e| io(&path, e))?;
    }
    let path = root.join("fuzz/Cargo.toml");
    let old = std::fs::read_to_string(&path).map_err(|e| io(&path, e))?;
    let new = cargo_fuzz::manifest(&old, &handstack_fuzz::TARGETS)
        .ok_or_else(|| format!("{}: no line `{}`", path.display(), cargo_fuzz::BINS_MARKER))?;
    std::fs::write(&path, new).map_err(|e| io(&path, e))?;
    println!(
        "fuzz/fuzz_targets/ and fuzz/Cargo.toml: {} targets",
        handstack_fuzz::TARGETS.len()
    );
    Ok(())
}
