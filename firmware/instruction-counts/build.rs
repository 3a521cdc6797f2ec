//! The QEMU machine's `memory.x` where cortex-m-rt's `link.x` finds it: lm3s6965evb for the
//! Cortex-M3 target, mps2-an386 for the Cortex-M4F one; nothing for the host.

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let memory = match std::env::var("TARGET")?.as_str() {
        "thumbv7m-none-eabi" => "memory/lm3s6965.x",
        "thumbv7em-none-eabihf" => "memory/mps2-an386.x",
        _ => return Ok(()),
    };
    let out = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::copy(memory, out.join("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={memory}");
    println!("cargo:rerun-if-changed=build.rs");
    Ok(())
}
