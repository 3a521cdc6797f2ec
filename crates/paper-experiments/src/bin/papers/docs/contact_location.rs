//! The generated sections of `docs/contact-location.md`: the targets under border-aware labels
//! and the jittered held-out set, from one [`ContactLocation`] evaluation of the committed
//! datasets and models (`papers docs contact-mlp` writes them after the MLP's table and plot).

use anyhow::Result;
use paper_experiments::contact_location::{
    ContactLocation, DOC, JITTERED_HEADING, TARGETS_HEADING, jittered_section, targets_section,
};
use std::path::Path;

/// Evaluates everything and rewrites both sections.
pub(crate) fn write(root: &Path) -> Result<()> {
    let cl = ContactLocation::evaluate(root, &[])?;
    let path = root.join(DOC);
    super::section::write(&path, TARGETS_HEADING, &targets_section(&cl))?;
    super::section::write(&path, JITTERED_HEADING, &jittered_section(&cl))?;
    println!("wrote {DOC}: {TARGETS_HEADING}, {JITTERED_HEADING}");
    Ok(())
}
