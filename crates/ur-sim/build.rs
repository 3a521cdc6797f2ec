//! The tests drive the simulator with `UrArm` (ur-bridge's `rtde-client`, a dev-dependency),
//! which embeds Python: when that feature is on, ur-bridge hands over the libpython directory
//! (`DEP_UR_BRIDGE_PYTHON_LIB_DIR`) and the test binaries get it as an rpath. A plain build
//! (`cargo install ur-sim`) sees no such directory and links nothing of Python.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=DEP_UR_BRIDGE_PYTHON_LIB_DIR");
    if let Some(dir) = std::env::var_os("DEP_UR_BRIDGE_PYTHON_LIB_DIR") {
        let dir = dir.to_string_lossy();
        println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    }
}
