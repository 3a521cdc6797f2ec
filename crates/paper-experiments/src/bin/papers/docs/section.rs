//! Rewriting one `## ` section of a markdown document, leaving the rest byte for byte.

use anyhow::{Context, Result, bail};
use std::path::Path;

/// `doc` with the body of the section whose heading line starts with `heading` replaced by
/// `body`: everything after the heading line up to the next `## ` heading (or the end).
pub(crate) fn replace(doc: &str, heading: &str, body: &str) -> Result<String> {
    let mut lines = doc.split_inclusive('\n');
    let mut out = String::with_capacity(doc.len() + body.len());
    let mut found = false;
    for line in lines.by_ref() {
        out.push_str(line);
        if line.starts_with(heading) {
            found = true;
            break;
        }
    }
    if !found {
        bail!("no section `{heading}`");
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out.push('\n');
    out.push_str(body.trim_end());
    out.push_str("\n\n");
    let mut rest = lines.skip_while(|l| !l.starts_with("## ")).peekable();
    if rest.peek().is_none() {
        out.truncate(out.trim_end().len());
        out.push('\n');
    }
    out.extend(rest);
    Ok(out)
}

/// Rewrites the section `heading` of the markdown file at `path` (see [`replace`]).
pub(crate) fn write(path: &Path, heading: &str, body: &str) -> Result<()> {
    let doc =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    std::fs::write(path, replace(&doc, heading, body)?)
        .with_context(|| format!("writing {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_only_the_named_section() -> Result<()> {
        let doc = "# T\n\nintro\n\n## 1. A\n\nold a\n\n## 2. B\n\nkeep b\n";
        let new = replace(doc, "## 1. A", "new a\n")?;
        assert_eq!(
            new,
            "# T\n\nintro\n\n## 1. A\n\nnew a\n\n## 2. B\n\nkeep b\n"
        );
        assert_eq!(replace(&new, "## 1. A", "new a")?, new, "idempotent");
        let last = replace(doc, "## 2. B", "b2")?;
        assert_eq!(last, "# T\n\nintro\n\n## 1. A\n\nold a\n\n## 2. B\n\nb2\n");
        assert!(replace(doc, "## 3.", "x").is_err());
        Ok(())
    }
}
