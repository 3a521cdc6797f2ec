//! Puts the package's `memory/TARGET.x` where cortex-m-rt's `link.x` finds it as `memory.x`
//! (`memory/stm32f103c8.x` with the feature `stm32f103c8`); nothing for a target without one
//! (the host). The fingertip's files are its boards (STM32F103RE, STM32F103C8, STM32F411CE);
//! `firmware/instruction-counts` builds with this script too, its files QEMU's machines.

use std::path::{Path, PathBuf};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let target = std::env::var("TARGET")?;
    let c8 = std::env::var_os("CARGO_FEATURE_STM32F103C8").is_some();
    let memory = if c8 && target == "thumbv7m-none-eabi" {
        "memory/stm32f103c8.x".to_owned()
    } else {
        format!("memory/{target}.x")
    };
    println!("cargo:rerun-if-changed={memory}");
    if !Path::new(&memory).is_file() {
        return Ok(());
    }
    let out = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::copy(&memory, out.join("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    Ok(())
}
