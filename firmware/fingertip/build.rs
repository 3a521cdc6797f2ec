//! Puts the board's `memory.x` where cortex-m-rt's `link.x` finds it: the STM32F103RE's for
//! the Cortex-M3 target, the STM32F411CE's for the Cortex-M4F one; nothing for the host.

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let target = std::env::var("TARGET")?;
    let memory = match target.as_str() {
        "thumbv7m-none-eabi" => "memory/stm32f103re.x",
        "thumbv7em-none-eabihf" => "memory/stm32f411ce.x",
        _ => return Ok(()),
    };
    let out = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::copy(memory, out.join("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={memory}");
    println!("cargo:rerun-if-changed=build.rs");
    Ok(())
}
