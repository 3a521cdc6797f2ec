//! `papers docs MODEL`: a trained model's plots and report section, drawn from its committed
//! weights and metrics (what `papers train MODEL` writes). `cargo xtask train MODEL` runs it
//! after training, or alone with `--docs-only`.

mod contact_cnn;
mod contact_location;
mod contact_mlp;
mod force_dnn;
mod plot;
mod section;
mod softness;

use anyhow::{Result, bail};
use std::collections::BTreeMap;
use std::path::Path;

/// Criterion means a section quotes, by benchmark id, already in readable units (`8.34 µs`).
/// xtask reads criterion's output and hands them over, so this binary has no second reader.
pub(crate) type Timings = BTreeMap<String, String>;

/// Draws the plots and writes the docs of `model` below the workspace root `root`; only the
/// contact CNN's section quotes `timings` (a missing id reads "not measured").
pub(crate) fn write(root: &Path, model: &str, timings: &Timings) -> Result<()> {
    match model {
        "contact-mlp" => contact_mlp::write(root).and_then(|()| contact_location::write(root)),
        "force-dnn" => force_dnn::write(root),
        "softness" => softness::write(root),
        "contact-cnn" => contact_cnn::write(root, timings),
        _ => bail!(
            "unknown model `{model}`: expected contact-mlp, force-dnn, softness or contact-cnn"
        ),
    }
}
