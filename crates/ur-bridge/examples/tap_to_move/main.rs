//! Runs the tap-to-move experiment on the simulated UR3 and writes its report (the path given,
//! else stdout). `cargo xtask demo tap-to-move` runs it into `docs/arm-tap-to-move.md`.

mod run;

fn main() -> Result<(), String> {
    let rows = run::run(31)?;
    let md = run::markdown(&rows);
    match std::env::args().nth(1) {
        Some(path) => std::fs::write(&path, md).map_err(|e| format!("{path}: {e}")),
        None => {
            print!("{md}");
            Ok(())
        }
    }
}
