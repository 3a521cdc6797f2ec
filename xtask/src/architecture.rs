//! The crate graph held to `docs/architecture.md`: the document's rules table says what kind
//! each workspace crate is and which workspace crates it may use; [`check`] compares that with
//! the dependencies `cargo metadata` declares (every kind — normal, build, dev — and every
//! optional one, so no feature can bring a forbidden edge back).
//!
//! The rules, whatever the table's rows say:
//! - a product crate (kind `product` or `driver`) never depends on a `reproduction` crate;
//! - nothing depends on the `composition` root;
//! - a driver's normal and build dependencies are `hand-traits` among ours and only the
//!   third-party crates its row lists; a tool's third-party ones are those its row lists (xtask
//!   stays thin);
//! - every edge between workspace crates is one the table allows;
//! - reproduction and tool crates are `publish = false`; product crates are publishable, and
//!   docs.rs documents all their features (as the doc step of `cargo xtask test` does);
//! - a product crate's `src/` names no repository path (`"fixtures/…"`, `"docs/…"` literals).

use anyhow::{Context, Result, bail};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};

/// The heading of the rules table in `docs/architecture.md`.
pub const TABLE_HEADING: &str = "## Dependency rules";

/// What a crate is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Published, useful alone.
    Product,
    /// A published chip driver: embedded-hal and `hand-traits` only.
    Driver,
    /// `publish = false`: the papers' datasets, protocols and reports.
    Reproduction,
    /// The composition root: nothing depends on it.
    Composition,
    /// `publish = false` developer tooling.
    Tool,
}

impl Kind {
    fn parse(s: &str) -> Option<Kind> {
        Some(match s {
            "product" => Kind::Product,
            "driver" => Kind::Driver,
            "reproduction" => Kind::Reproduction,
            "composition" => Kind::Composition,
            "tool" => Kind::Tool,
            _ => return None,
        })
    }

    /// Published to crates.io (product crates and drivers).
    pub fn is_product(self) -> bool {
        matches!(self, Kind::Product | Kind::Driver)
    }
}

/// One row of the rules table.
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    /// The crate's kind.
    pub kind: Kind,
    /// Workspace crates it may use; `None` = any (the general rules still apply).
    pub may_use: Option<BTreeSet<String>>,
    /// Third-party crates a driver or a tool may use (normal and build); `None` = any.
    pub third_party: Option<BTreeSet<String>>,
}

/// A declared dependency of a workspace crate.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    /// The dependency's package name.
    pub to: String,
    /// `normal`, `dev` or `build`.
    pub kind: &'static str,
    /// Declared `optional` (behind a feature).
    pub optional: bool,
}

/// A workspace crate as `cargo metadata` declares it.
#[derive(Debug, Clone, PartialEq)]
pub struct Package {
    /// Package name.
    pub name: String,
    /// `publish = false`.
    pub unpublished: bool,
    /// The directory holding its `Cargo.toml`.
    pub dir: PathBuf,
    /// Its declared dependencies.
    pub deps: Vec<Edge>,
    /// `[package.metadata.docs.rs] all-features = true`: docs.rs documents what our doc step
    /// documents.
    pub docs_rs_all_features: bool,
    /// Its declared `rust-version`, if any.
    pub rust_version: Option<String>,
}

/// One broken rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation(pub String);

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Parses the rules table below [`TABLE_HEADING`]: `| crate | kind | may use | third-party |`,
/// names in backticks, `any` for no limit, `—` for none.
pub fn parse_rules(doc: &str) -> Result<BTreeMap<String, Rule>> {
    let start = doc
        .find(TABLE_HEADING)
        .with_context(|| format!("no `{TABLE_HEADING}` section"))?;
    let names = |cell: &str| -> Option<BTreeSet<String>> {
        (cell.trim() != "any").then(|| {
            cell.split('`')
                .skip(1)
                .step_by(2)
                .map(str::to_string)
                .collect()
        })
    };
    let mut rules = BTreeMap::new();
    for line in doc[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2)
    {
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        let [name, kind, may_use, third_party] = cells[..] else {
            bail!("rules row `{line}`: expected 4 cells");
        };
        let name = name.trim_matches('`').to_string();
        let kind = Kind::parse(kind).with_context(|| format!("rules row `{line}`: kind"))?;
        let rule = Rule {
            kind,
            may_use: names(may_use),
            third_party: names(third_party),
        };
        if rules.insert(name.clone(), rule).is_some() {
            bail!("rules table lists `{name}` twice");
        }
    }
    if rules.is_empty() {
        bail!("the `{TABLE_HEADING}` table has no rows");
    }
    Ok(rules)
}

/// The workspace crates and their declared dependencies (`cargo metadata --no-deps`).
pub fn workspace_packages(root: &Path) -> Result<Vec<Package>> {
    let out = crate::run::cargo(root)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .output()
        .context("running cargo metadata")?;
    if !out.status.success() {
        bail!(
            "cargo metadata failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let meta: Value = serde_json::from_slice(&out.stdout).context("cargo metadata's JSON")?;
    let packages = meta["packages"].as_array().context("no packages")?;
    packages
        .iter()
        .map(|p| {
            let name = p["name"].as_str().context("package name")?.to_string();
            let manifest = PathBuf::from(p["manifest_path"].as_str().context("manifest")?);
            let deps = p["dependencies"]
                .as_array()
                .context("dependencies")?
                .iter()
                .map(|d| Edge {
                    to: d["name"].as_str().unwrap_or_default().to_string(),
                    kind: match d["kind"].as_str() {
                        Some("dev") => "dev",
                        Some("build") => "build",
                        _ => "normal",
                    },
                    optional: d["optional"].as_bool().unwrap_or(false),
                })
                .collect();
            Ok(Package {
                name,
                // `publish = false` is an empty registry list.
                unpublished: p["publish"].as_array().is_some_and(Vec::is_empty),
                dir: manifest.parent().context("manifest dir")?.to_path_buf(),
                deps,
                docs_rs_all_features: p["metadata"]["docs"]["rs"]["all-features"]
                    .as_bool()
                    .unwrap_or(false),
                rust_version: p["rust_version"].as_str().map(str::to_owned),
            })
        })
        .collect()
}

/// Every rule `packages` break against `rules`.
pub fn check(rules: &BTreeMap<String, Rule>, packages: &[Package]) -> Vec<Violation> {
    let ours: BTreeSet<&str> = packages.iter().map(|p| p.name.as_str()).collect();
    let mut bad = Vec::new();
    let mut say = |s: String| bad.push(Violation(s));
    for name in rules.keys().filter(|n| !ours.contains(n.as_str())) {
        say(format!(
            "docs/architecture.md lists `{name}`, which is no workspace crate"
        ));
    }
    for p in packages {
        let Some(rule) = rules.get(&p.name) else {
            say(format!(
                "`{}` is not in docs/architecture.md's rules table",
                p.name
            ));
            continue;
        };
        let published = !p.unpublished;
        match rule.kind {
            Kind::Reproduction | Kind::Tool if published => say(format!(
                "`{}` ({:?}) must be publish = false",
                p.name, rule.kind
            )),
            Kind::Product | Kind::Driver if !published => say(format!(
                "`{}` is a product crate but publish = false",
                p.name
            )),
            Kind::Product | Kind::Driver if !p.docs_rs_all_features => say(format!(
                "`{}` is a product crate without `[package.metadata.docs.rs] all-features = true`",
                p.name
            )),
            _ => {}
        }
        for e in &p.deps {
            let feature = if e.optional { " (optional)" } else { "" };
            let edge = format!("`{}` → `{}` ({}{feature})", p.name, e.to, e.kind);
            if e.to == p.name {
                continue; // a crate's dev-dependency on itself with more features
            }
            let Some(target) = ours
                .contains(e.to.as_str())
                .then(|| rules.get(&e.to))
                .flatten()
            else {
                // third party
                let limited = matches!(rule.kind, Kind::Driver | Kind::Tool) && e.kind != "dev";
                let allowed = rule.third_party.as_ref().is_none_or(|t| t.contains(&e.to));
                if limited && !allowed {
                    say(match rule.kind {
                        Kind::Driver => {
                            format!("{edge}: a driver uses embedded-hal and its listed crates only")
                        }
                        _ => format!("{edge}: a tool uses its listed third-party crates only"),
                    });
                }
                continue;
            };
            if target.kind == Kind::Composition {
                say(format!("{edge}: nothing depends on the composition root"));
            }
            if rule.kind.is_product() && target.kind == Kind::Reproduction {
                say(format!(
                    "{edge}: a product crate never depends on a reproduction crate"
                ));
            }
            let allowed = rule.may_use.as_ref().is_none_or(|m| m.contains(&e.to));
            if !allowed {
                say(format!(
                    "{edge}: not in its row of docs/architecture.md's rules table"
                ));
            }
        }
    }
    bad
}

/// Repository paths named in string literals under `src/` of each product crate:
/// `(file, line number, line)`.
pub fn repository_paths(rules: &BTreeMap<String, Rule>, packages: &[Package]) -> Vec<Violation> {
    let mut bad = Vec::new();
    for p in packages {
        if !rules.get(&p.name).is_some_and(|r| r.kind.is_product()) {
            continue;
        }
        let mut files = Vec::new();
        collect_rs(&p.dir.join("src"), &mut files);
        for file in files {
            let Ok(text) = std::fs::read_to_string(&file) else {
                continue;
            };
            for (i, line) in text.lines().enumerate() {
                let code = line.trim_start();
                if code.starts_with("//") {
                    continue;
                }
                if ["\"fixtures/", "\"docs/", "\"../../"]
                    .iter()
                    .any(|s| code.contains(s))
                {
                    bad.push(Violation(format!(
                        "{}:{}: a product crate names a repository path: {}",
                        file.display(),
                        i + 1,
                        code
                    )));
                }
            }
        }
    }
    bad
}

fn collect_rs(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect_rs(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}
