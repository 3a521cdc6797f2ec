//! With `arm` (ur-bridge embeds Python): links binaries against the libpython pyo3 was
//! configured with, with an rpath so the tests and examples find it.

fn main() {
    if std::env::var_os("CARGO_FEATURE_ARM").is_some() {
        pyo3_build_config::add_libpython_rpath_link_args();
    }
}
