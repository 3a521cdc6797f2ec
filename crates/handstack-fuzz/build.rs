//! Links the replay test against the libpython pyo3 (in ur-bridge) was configured with, with an rpath so it finds it.

fn main() {
    pyo3_build_config::add_libpython_rpath_link_args();
}
