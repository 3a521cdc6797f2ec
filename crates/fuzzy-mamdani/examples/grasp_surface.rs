//! Writes the grasp preset's control surface for the docs:
//! `cargo run -p fuzzy-mamdani --features plot --example grasp_surface -- docs/`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "docs".into()));
    std::fs::create_dir_all(&dir)?;
    let engine = fuzzy_mamdani::grasp_engine::<f64>();
    let csv = std::fs::File::create(dir.join("fuzzy-grasp-surface.csv"))?;
    fuzzy_mamdani::write_surface_csv(&engine, 41, std::io::BufWriter::new(csv))?;
    #[cfg(feature = "plot")]
    fuzzy_mamdani::plot_surface(&engine, 81, &dir.join("fuzzy-grasp-surface.svg"))?;
    Ok(())
}
