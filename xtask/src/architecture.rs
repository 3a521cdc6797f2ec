//! The crate graph held to `docs/architecture.md`, and drawn into it.
//!
//! [`graph`] draws the workspace's dependency graph from `cargo metadata` (each crate's normal
//! and dev-dependencies on other members, with the features each edge turns on), grouped into
//! product crates, simulators (both published), reproduction crates and tools; `cargo xtask
//! architecture` writes it between the document's generated-part markers ([`BEGIN`], [`END`])
//! and `--check` (and xtask's tests) fail when the drawn graph is not the declared one.
//!
//! The document's rules table says what kind each workspace crate is and which workspace crates
//! it may use; [`check`] compares that with the dependencies `cargo metadata` declares (every
//! kind — normal, build, dev — and every optional one, so no feature can bring a forbidden edge
//! back).
//!
//! The rules, whatever the table's rows say:
//! - a product crate (kind `product` or `driver`) never depends on a `simulator` or
//!   `reproduction` crate, under any feature and as no kind of dependency; a simulator never
//!   depends on a `reproduction` crate;
//! - nothing depends on the `composition` root;
//! - a driver's normal and build dependencies are the workspace crates its row lists and only the
//!   third-party crates its row lists; a tool's third-party ones are those its row lists (xtask
//!   stays thin);
//! - every edge between workspace crates is one the table allows;
//! - reproduction and tool crates are `publish = false`; product crates and simulators are
//!   publishable, and docs.rs documents all their features (as the doc step of `cargo xtask
//!   test` does);
//! - a published crate's `src/` names no repository path (`"fixtures/…"`, `"docs/…"` literals);
//! - no product crate has a binary target but `handstack`'s `handstack` ([`product_bins`]; a
//!   simulator's program is its own);
//! - no published crate's `src/` names a paper seed (`seed 000`…`seed 002`, `seed000`…:
//!   [`seed_mentions`]).
//!
//! The last two take lists of known exceptions, [`KNOWN_PRODUCT_BINS`] and
//! [`KNOWN_SEED_MENTIONS`], both empty: a new violation fails, and so does a listed exception
//! that is gone, with the line of the list to delete or change.

use anyhow::{Context, Result, bail};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The heading of the rules table in `docs/architecture.md`.
pub const TABLE_HEADING: &str = "## Dependency rules";

/// What a crate is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Published, useful alone.
    Product,
    /// A published chip driver: embedded-hal and the workspace crates its row lists only.
    Driver,
    /// Published: a program a user runs beside their own code (`cargo install ur-sim`), answering
    /// a real protocol on a real transport; it may use the product crate owning that protocol.
    Simulator,
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
            "simulator" => Kind::Simulator,
            "reproduction" => Kind::Reproduction,
            "composition" => Kind::Composition,
            "tool" => Kind::Tool,
            _ => return None,
        })
    }

    /// A product crate (product crates and drivers): published, useful alone, and never on a
    /// simulator or reproduction crate.
    pub fn is_product(self) -> bool {
        matches!(self, Kind::Product | Kind::Driver)
    }

    /// Published to crates.io: product crates, drivers and simulators.
    pub fn is_published(self) -> bool {
        self.is_product() || self == Kind::Simulator
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
    /// The dependency's features the declaration turns on.
    pub features: Vec<String>,
    /// The dependency's default features are on (`default-features` not false).
    pub default_features: bool,
    /// The `cfg(…)` or target triple the declaration is limited to, if any.
    pub target: Option<String>,
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
    /// Its binary targets (`[[bin]]` and `src/bin/`, `src/main.rs`), by name.
    pub bins: Vec<String>,
    /// Its features: each name and what it turns on (`dep:x`, `x/f`, `x?/f`, own features).
    pub features: BTreeMap<String, Vec<String>>,
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
                    features: strings(&d["features"]),
                    default_features: d["uses_default_features"].as_bool().unwrap_or(true),
                    target: d["target"].as_str().map(str::to_owned),
                })
                .collect();
            let mut bins: Vec<String> = p["targets"]
                .as_array()
                .context("targets")?
                .iter()
                .filter(|t| strings(&t["kind"]).iter().any(|k| k == "bin"))
                .filter_map(|t| t["name"].as_str().map(str::to_owned))
                .collect();
            bins.sort();
            let features = p["features"]
                .as_object()
                .context("features")?
                .iter()
                .map(|(name, on)| (name.clone(), strings(on)))
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
                bins,
                features,
            })
        })
        .collect()
}

/// A JSON array of strings (anything else: empty).
fn strings(v: &Value) -> Vec<String> {
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(|s| s.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default()
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
        let what = if rule.kind == Kind::Simulator {
            "a simulator"
        } else {
            "a product crate"
        };
        match rule.kind {
            Kind::Reproduction | Kind::Composition | Kind::Tool if published => say(format!(
                "`{}` ({:?}) must be publish = false",
                p.name, rule.kind
            )),
            k if k.is_published() && !published => {
                say(format!("`{}` is {what} but publish = false", p.name));
            }
            k if k.is_published() && !p.docs_rs_all_features => say(format!(
                "`{}` is {what} without `[package.metadata.docs.rs] all-features = true`",
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
            if rule.kind.is_product() && matches!(target.kind, Kind::Reproduction | Kind::Simulator)
            {
                say(format!(
                    "{edge}: a product crate never depends on a simulator or reproduction crate"
                ));
            }
            if rule.kind == Kind::Simulator && target.kind == Kind::Reproduction {
                say(format!(
                    "{edge}: a simulator is published and never depends on a reproduction crate"
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

/// Repository paths named in string literals under `src/` of each published crate (product
/// crates and simulators): `(file, line number, line)`.
pub fn repository_paths(rules: &BTreeMap<String, Rule>, packages: &[Package]) -> Vec<Violation> {
    let mut bad = Vec::new();
    for p in packages {
        if !rules.get(&p.name).is_some_and(|r| r.kind.is_published()) {
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
                        "{}:{}: a published crate names a repository path: {}",
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

// ---- rules with known exceptions: binaries and paper seeds in product crates -----------------

/// The one binary a product crate ships: the installable stack's command line.
pub const STACK_BIN: (&str, &str) = ("handstack", "handstack");

/// Binaries product crates ship besides [`STACK_BIN`], as `(crate, binary)`: known exceptions
/// to "no product crate has a binary but `handstack`", each a simulator run as a process of its
/// own. [`product_bins`] fails on a binary missing here, and on a line here whose binary is
/// gone: delete the line when its simulator moves out of the product crate.
pub const KNOWN_PRODUCT_BINS: &[(&str, &str)] = &[];

/// Files of product crates' `src/` that name a paper seed, with how many times: known exceptions
/// to "no product crate's `src/` names a paper seed" (`seed 000`, `seed001`, …, any case), as
/// `(path from the workspace root, mentions)`. [`seed_mentions`] fails on a file not listed or
/// over its count, and on a count that is now too high or a file that no longer names one,
/// printing the line to change or delete: the list shrinks with every file rewritten in the
/// code's own terms.
pub const KNOWN_SEED_MENTIONS: &[(&str, usize)] = &[];

/// Where the known exceptions live, for the messages.
const LISTS: &str = "xtask/src/architecture.rs";

/// Binary targets of product crates (kinds `product` and `driver` in `rules`; a simulator's
/// program is its own) against [`STACK_BIN`] and `known` ([`KNOWN_PRODUCT_BINS`] in the real
/// check).
pub fn product_bins(
    rules: &BTreeMap<String, Rule>,
    packages: &[Package],
    known: &[(&str, &str)],
) -> Vec<Violation> {
    let mut bad = Vec::new();
    let shipped: BTreeSet<(&str, &str)> = packages
        .iter()
        .filter(|p| rules.get(&p.name).is_some_and(|r| r.kind.is_product()))
        .flat_map(|p| p.bins.iter().map(|b| (p.name.as_str(), b.as_str())))
        .collect();
    for &(krate, bin) in &shipped {
        if (krate, bin) != STACK_BIN && !known.contains(&(krate, bin)) {
            bad.push(Violation(format!(
                "`{krate}` has a binary `{bin}`: no product crate but `handstack` ships one \
                 (a simulator's program belongs in a simulator crate, a tool's in a tool crate)"
            )));
        }
    }
    for &(krate, bin) in known {
        if !shipped.contains(&(krate, bin)) {
            bad.push(Violation(format!(
                "product crate `{krate}` has no binary `{bin}` any more: delete its known \
                 exception from KNOWN_PRODUCT_BINS in {LISTS}: `(\"{krate}\", \"{bin}\"),`"
            )));
        }
    }
    bad
}

/// The 1-based line of each paper-seed mention in `text` (`seed 000`, `seed001`, … `seed 002`,
/// any case; one entry per mention).
pub fn seed_mention_lines(text: &str) -> Vec<usize> {
    let mut lines = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let lower = line.to_ascii_lowercase();
        for (at, _) in lower.match_indices("seed") {
            let rest = &lower.as_bytes()[at + 4..];
            let rest = rest.strip_prefix(b" ").unwrap_or(rest);
            if let [b'0', b'0', b'0'..=b'2', ..] = rest {
                lines.push(i + 1);
            }
        }
    }
    lines
}

/// Paper-seed mentions in the `.rs` files under each published crate's `src/` (product crates
/// and simulators, by `cargo metadata`), against `known` ([`KNOWN_SEED_MENTIONS`] in the real check); paths are
/// relative to `root`.
pub fn seed_mentions(root: &Path, packages: &[Package], known: &[(&str, usize)]) -> Vec<Violation> {
    let mut found: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for p in packages.iter().filter(|p| !p.unpublished) {
        let mut files = Vec::new();
        collect_rs(&p.dir.join("src"), &mut files);
        for file in files {
            let Ok(text) = std::fs::read_to_string(&file) else {
                continue;
            };
            let lines = seed_mention_lines(&text);
            if lines.is_empty() {
                continue;
            }
            let path = file.strip_prefix(root).unwrap_or(&file);
            let path = path
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            found.insert(path, lines);
        }
    }
    let allowed: BTreeMap<&str, usize> = known.iter().copied().collect();
    let mut bad = Vec::new();
    for (path, lines) in &found {
        let n = lines.len();
        let allowed = allowed.get(path.as_str()).copied().unwrap_or(0);
        if n > allowed {
            let at: Vec<String> = lines.iter().map(ToString::to_string).collect();
            bad.push(Violation(format!(
                "{path}: names a paper seed {n} times (lines {}), {allowed} known: a product \
                 crate says what its code does, not which paper seed it reproduces",
                at.join(", ")
            )));
        }
    }
    for (&path, &allowed) in &allowed {
        let n = found.get(path).map_or(0, Vec::len);
        if n < allowed {
            let fix = if n == 0 {
                format!("delete its line `(\"{path}\", {allowed}),`")
            } else {
                format!("change its line `(\"{path}\", {allowed}),` to `(\"{path}\", {n}),`")
            };
            bad.push(Violation(format!(
                "{path}: names a paper seed {n} times, {allowed} known: in KNOWN_SEED_MENTIONS \
                 of {LISTS}, {fix}"
            )));
        }
    }
    bad
}

// ---- the drawn graph --------------------------------------------------------------------------

/// The document the graph is drawn into, from the workspace root.
pub const DOC: &str = "docs/architecture.md";
/// The line before the generated part.
pub const BEGIN: &str = "<!-- generated by `cargo xtask architecture`: do not edit below -->";
/// The line after the generated part.
pub const END: &str = "<!-- end of generated part -->";

/// A group of the drawn graph, in the order drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Group {
    /// Published (`publish` not false), but simulators.
    Product,
    /// Kind `simulator` (published).
    Simulator,
    /// Kinds `reproduction` and `composition`.
    Reproduction,
    /// Kind `tool`.
    Tool,
}

impl Group {
    /// The group of `p`: a simulator by its kind in the rules table, else product if
    /// published, else by its kind.
    pub fn of(p: &Package, rules: &BTreeMap<String, Rule>) -> Result<Group> {
        if rules
            .get(&p.name)
            .is_some_and(|r| r.kind == Kind::Simulator)
        {
            return Ok(Group::Simulator);
        }
        if !p.unpublished {
            return Ok(Group::Product);
        }
        let rule = rules.get(&p.name).with_context(|| {
            format!(
                "`{}` is not in {DOC}'s rules table: add its row, then draw the graph",
                p.name
            )
        })?;
        Ok(match rule.kind {
            Kind::Reproduction | Kind::Composition => Group::Reproduction,
            Kind::Simulator => Group::Simulator,
            Kind::Tool => Group::Tool,
            Kind::Product | Kind::Driver => bail!(
                "`{}` is a product crate in {DOC}'s rules table but publish = false",
                p.name
            ),
        })
    }

    fn heading(self) -> &'static str {
        match self {
            Group::Product => "Product crates (published)",
            Group::Reproduction => "Reproduction crates (publish = false)",
            Group::Simulator => "Simulators (published)",
            Group::Tool => "Tools (publish = false)",
        }
    }
}

/// One drawn edge: `` `to[features]` `` and what turns it or its features on.
fn label(p: &Package, e: &Edge) -> String {
    let mut features = e.features.clone();
    features.sort();
    let mut s = if features.is_empty() {
        format!("`{}`", e.to)
    } else {
        format!("`{}[{}]`", e.to, features.join(", "))
    };
    let mut notes = Vec::new();
    if !e.default_features {
        notes.push("no default features".to_string());
    }
    if e.kind != "dev" {
        let dep = format!("dep:{}", e.to);
        let strong = format!("{}/", e.to);
        let weak = format!("{}?/", e.to);
        let defaults = p.features.get("default");
        if e.optional {
            let by: Vec<String> = p
                .features
                .iter()
                .filter(|(_, on)| {
                    on.iter()
                        .any(|x| *x == dep || *x == e.to || x.starts_with(&strong))
                })
                .map(|(f, _)| {
                    let default = defaults.is_some_and(|d| d.contains(f));
                    if default {
                        format!("default feature `{f}`")
                    } else {
                        format!("`{f}`")
                    }
                })
                .collect();
            notes.push(format!("optional: {}", by.join(", ")));
        }
        for (f, on) in &p.features {
            let adds: Vec<&str> = on
                .iter()
                .filter_map(|x| x.strip_prefix(&strong).or_else(|| x.strip_prefix(&weak)))
                .collect();
            if !adds.is_empty() {
                notes.push(format!("`{f}` → `[{}]`", adds.join(", ")));
            }
        }
    }
    if e.kind == "build" {
        notes.push("build".to_string());
    }
    if let Some(target) = &e.target {
        notes.push(format!("on `{target}` only"));
    }
    if !notes.is_empty() {
        let _ = write!(s, " ({})", notes.join("; "));
    }
    s
}

/// The graph between workspace crates as drawn into [`DOC`]: one Markdown table per [`Group`],
/// a row per crate (sorted by name), its normal (and build) dependencies on other members in one
/// column and its dev-dependencies in the other (sorted); a crate's dev-dependency on itself
/// (its tests turning on its own features) is left out.
pub fn graph(rules: &BTreeMap<String, Rule>, packages: &[Package]) -> Result<String> {
    let ours: BTreeSet<&str> = packages.iter().map(|p| p.name.as_str()).collect();
    let mut groups: BTreeMap<Group, Vec<&Package>> = BTreeMap::new();
    for p in packages {
        groups.entry(Group::of(p, rules)?).or_default().push(p);
    }
    let (mut uses, mut dev) = (0, 0);
    let mut tables = String::new();
    for (group, mut members) in groups {
        members.sort_by(|a, b| a.name.cmp(&b.name));
        let _ = write!(
            tables,
            "\n**{}**\n\n| crate | uses | tests, examples and benches also use |\n|---|---|---|\n",
            group.heading()
        );
        for p in members {
            let mut edges: Vec<&Edge> = p
                .deps
                .iter()
                .filter(|e| e.to != p.name && ours.contains(e.to.as_str()))
                .collect();
            edges.sort_by(|a, b| (&a.to, a.kind, &a.target).cmp(&(&b.to, b.kind, &b.target)));
            let (d, n): (Vec<&Edge>, Vec<&Edge>) = edges.into_iter().partition(|e| e.kind == "dev");
            uses += n.len();
            dev += d.len();
            let cell = |edges: &[&Edge]| {
                if edges.is_empty() {
                    "—".to_string()
                } else {
                    let labels: Vec<String> = edges.iter().map(|e| label(p, e)).collect();
                    labels.join(", ")
                }
            };
            let _ = writeln!(tables, "| `{}` | {} | {} |", p.name, cell(&n), cell(&d));
        }
    }
    Ok(format!(
        "{} workspace crates; {uses} edges between them, and {dev} more in tests, examples and \
         benches (`cargo metadata`).\n{tables}",
        packages.len()
    ))
}

/// Where the generated part of `doc` begins (after [`BEGIN`]) and ends (at [`END`]).
fn markers(doc: &str) -> Result<(usize, usize)> {
    let (Some(a), Some(b)) = (doc.find(BEGIN), doc.find(END)) else {
        bail!("{DOC} lacks the generated part's markers ({BEGIN} … {END})");
    };
    if b < a {
        bail!("{DOC}: the generated part ends before it begins");
    }
    Ok((a + BEGIN.len(), b))
}

/// The generated part of `doc` (between [`BEGIN`] and [`END`], blank lines trimmed).
pub fn drawn(doc: &str) -> Result<&str> {
    let (a, b) = markers(doc)?;
    Ok(doc[a..b].trim_matches('\n'))
}

/// `doc` with `generated` between its markers.
pub fn splice(doc: &str, generated: &str) -> Result<String> {
    let (a, b) = markers(doc)?;
    Ok(format!(
        "{}\n\n{}\n\n{}",
        &doc[..a],
        generated.trim_matches('\n'),
        &doc[b..]
    ))
}

/// Every rule of this module broken by the workspace at `root`: the rules table's, the
/// repository paths, and the known exceptions' (binaries, paper seeds).
pub fn violations(
    root: &Path,
    rules: &BTreeMap<String, Rule>,
    packages: &[Package],
) -> Vec<Violation> {
    let mut bad = check(rules, packages);
    bad.extend(repository_paths(rules, packages));
    bad.extend(product_bins(rules, packages, KNOWN_PRODUCT_BINS));
    bad.extend(seed_mentions(root, packages, KNOWN_SEED_MENTIONS));
    bad
}

/// `cargo xtask architecture [--check]`: draws the graph into [`DOC`] (`--check`: fails if the
/// drawn one differs instead), then fails on any broken rule.
pub fn run(root: &Path, check_only: bool) -> Result<()> {
    let path = root.join(DOC);
    let doc = std::fs::read_to_string(&path).with_context(|| DOC.to_string())?;
    let rules = parse_rules(&doc)?;
    let packages = workspace_packages(root)?;
    let generated = graph(&rules, &packages)?;
    if check_only {
        if drawn(&doc)? != generated.trim_matches('\n') {
            bail!(
                "{DOC}'s crate graph is not the one cargo metadata declares: run `cargo xtask architecture`"
            );
        }
        println!("{DOC}: the crate graph matches cargo metadata");
    } else {
        let new = splice(&doc, &generated)?;
        if new == doc {
            println!("{DOC}: the crate graph is up to date");
        } else {
            std::fs::write(&path, new).with_context(|| DOC.to_string())?;
            println!("{DOC}: crate graph rewritten");
        }
    }
    let bad = violations(root, &rules, &packages);
    if !bad.is_empty() {
        let list: Vec<String> = bad.iter().map(ToString::to_string).collect();
        bail!("architecture rules broken:\n{}", list.join("\n"));
    }
    Ok(())
}
