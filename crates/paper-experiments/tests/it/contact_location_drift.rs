//! Drift check: the generated sections of `docs/contact-location.md` (the targets under
//! the labels, the jittered set) are what a re-run of the evaluation over the committed
//! taps and models writes (`cargo xtask train contact-mlp --docs-only` on change). Counts and
//! percentages only: our code decides every character.

use paper_experiments::aot_eval::Rule;
use paper_experiments::contact_location::{
    ContactLocation, DOC, JITTERED_HEADING, Set, TARGETS_HEADING, jittered_section, targets_section,
};
use std::path::PathBuf;

/// The body of the section `heading` of `doc`, trimmed (what `section::replace` wrote).
fn section<'a>(doc: &'a str, heading: &str) -> &'a str {
    let start = doc.find(heading).expect("the section") + heading.len();
    let rest = &doc[start..];
    let end = rest.find("\n## ").unwrap_or(rest.len());
    rest[..end].trim()
}

#[test]
fn generated_sections_match_a_rerun() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let doc = std::fs::read_to_string(root.join(DOC)).unwrap();
    let cl = ContactLocation::evaluate(&root, &[]).unwrap();
    assert_eq!(section(&doc, TARGETS_HEADING), targets_section(&cl).trim());
    assert_eq!(
        section(&doc, JITTERED_HEADING),
        jittered_section(&cl).trim()
    );
    // The set sizes: ≥ 600 jittered taps per OSR, every one off a border.
    for osr in cl.osrs() {
        let t = cl.aot(Set::Jittered, Rule::Ranging, osr);
        assert!(t.n >= 600, "OSR {osr}: {} jittered taps", t.n);
        assert!(cl.jittered.border.get(&osr).is_none_or(|b| b.taps == 0));
        assert_eq!(cl.lattice.border[&osr].taps, 60);
    }
}
