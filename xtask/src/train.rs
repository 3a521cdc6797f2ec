//! `cargo xtask train MODEL [--docs-only]`: retrains a committed model and redraws its docs.
//!
//! Two binaries, both under the optimised `test` profile (dfdx at `opt-level = 0`, the xtask's
//! own profile, is several times slower): `papers train MODEL` trains and writes the weights
//! and metrics below `crates/tactile-nets/models/`; then `papers docs MODEL` draws the plots and rewrites
//! the model's section of the docs from those files (`--docs-only`: that step alone).
//!
//! - `contact-mlp` (`--docs-only`): `docs/contact-location/contact-mlp-osr.svg`, prints the
//!   MLP's markdown table, and rewrites the generated sections of `docs/contact-location.md`
//!   (the targets under border-aware labels, the jittered set);
//! - `force-dnn`: the training curve and section 1 of `docs/learning.md`;
//! - `softness` (`--docs-only`): confusion matrices, training curves and section 2;
//! - `contact-cnn` (`--docs-only`): Table I side by side, the confusion matrix and section 3,
//!   quoting the latest `cargo xtask bench contact_cnn` means from `target/criterion`.

use crate::run::PAPERS;
use anyhow::{Result, bail};
use std::path::Path;
use std::time::SystemTime;

const USAGE: &str = "usage: cargo xtask train contact-mlp [--docs-only] | force-dnn | softness [--docs-only] | contact-cnn [--docs-only]";

/// The models, and whether each takes `--docs-only`.
const MODELS: [(&str, bool); 4] = [
    ("contact-mlp", true),
    ("force-dnn", false),
    ("softness", true),
    ("contact-cnn", true),
];

/// The criterion ids (a prefix) whose means the contact CNN's section quotes.
const CNN_TIMINGS: &str = "contact_cnn";

/// Runs `cargo xtask train <model> [--docs-only]`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    let takes_docs_only = |model: &str| MODELS.iter().find(|(m, _)| *m == model).map(|m| m.1);
    let (model, docs_only) = match args {
        [model] if takes_docs_only(model).is_some() => (model.as_str(), false),
        [model, flag] if flag == "--docs-only" && takes_docs_only(model) == Some(true) => {
            (model.as_str(), true)
        }
        _ => bail!(USAGE),
    };
    if !docs_only {
        PAPERS.run(root, &format!("train ({model})"), &["train", model])?;
    }
    let mut docs = vec!["docs".to_owned(), model.to_owned()];
    if model == "contact-cnn" {
        for (id, mean) in timings(root, CNN_TIMINGS) {
            docs.push("--timing".to_owned());
            docs.push(format!("{id}={mean}"));
        }
    }
    PAPERS.run(root, &format!("docs ({model})"), &docs)
}

/// The latest criterion mean of every benchmark whose id starts with `prefix`, in readable
/// units; none when nothing was measured (the section then says "not measured").
fn timings(root: &Path, prefix: &str) -> Vec<(String, String)> {
    crate::bench::collect(&root.join("target/criterion"), SystemTime::UNIX_EPOCH)
        .unwrap_or_default()
        .into_iter()
        .filter(|m| m.id.starts_with(prefix))
        .map(|m| (m.id, crate::bench::human(m.mean_ns)))
        .collect()
}
