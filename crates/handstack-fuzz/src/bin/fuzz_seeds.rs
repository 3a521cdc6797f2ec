//! Writes every target's seed corpus to `fuzz/seeds/TARGET/NAME` (`cargo xtask fuzz
//! --seed`): usage `fuzz-seeds REPOSITORY_ROOT`.

use std::path::PathBuf;
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
    ExitCode::SUCCESS
}
