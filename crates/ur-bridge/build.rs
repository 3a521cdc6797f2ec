//! With `rtde-client` (pyo3): links this crate's tests and doctests against the libpython pyo3
//! was configured with, with an rpath so they find it, and hands its directory to dependents'
//! build scripts (`DEP_UR_BRIDGE_PYTHON_LIB_DIR`). Without it: nothing (`CARGO_FEATURE_RTDE_CLIENT`
//! unset), so the crate builds with no Python around.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "rtde-client")]
    {
        pyo3_build_config::add_libpython_rpath_link_args();
        if let Some(dir) = pyo3_build_config::get().lib_dir() {
            println!("cargo:python_lib_dir={dir}");
        }
    }
}
