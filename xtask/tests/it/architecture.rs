//! The workspace's crate graph obeys `docs/architecture.md`'s rules table (read from
//! `cargo metadata`), the graph drawn in that document is the one `cargo metadata` declares,
//! and the checkers catch each kind of forbidden edge, binary and paper-seed mention on
//! stand-ins.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use xtask::architecture::{
    BEGIN, DOC, END, Edge, Group, KNOWN_PRODUCT_BINS, KNOWN_SEED_MENTIONS, Kind, Package, Rule,
    check, drawn, graph, parse_rules, product_bins, repository_paths, seed_mention_lines,
    seed_mentions, splice, violations, workspace_packages,
};

fn rules() -> BTreeMap<String, Rule> {
    let doc = std::fs::read_to_string(xtask::workspace_root().join("docs/architecture.md"))
        .expect("docs/architecture.md");
    parse_rules(&doc).expect("the rules table parses")
}

#[test]
fn the_workspace_graph_is_the_documented_one() {
    let rules = rules();
    let root = xtask::workspace_root();
    let packages = workspace_packages(&root).expect("cargo metadata");
    assert!(packages.len() >= 14, "{} workspace crates", packages.len());
    let mut bad = check(&rules, &packages);
    bad.extend(repository_paths(&rules, &packages));
    let report: Vec<String> = bad.iter().map(ToString::to_string).collect();
    assert!(report.is_empty(), "\n{}", report.join("\n"));
    // And the rules with known exceptions (binaries, paper seeds), as `cargo xtask
    // architecture` checks them all.
    let report: Vec<String> = violations(&root, &rules, &packages)
        .iter()
        .map(ToString::to_string)
        .collect();
    assert!(report.is_empty(), "\n{}", report.join("\n"));
    // The product crates, and the kinds the rules rest on.
    for name in [
        "hand-traits",
        "baro-drivers",
        "imu-icm20789",
        "aot-locate",
        "fuzzy-mamdani",
        "tactile-nets",
        "hand-control",
        "ur-bridge",
        "sim-clock",
    ] {
        assert!(rules[name].kind.is_product(), "{name}");
    }
    for name in ["paper-experiments", "paper-fixtures", "hand-sim"] {
        assert_eq!(rules[name].kind, Kind::Reproduction, "{name}");
    }
    // The UR controller simulator is a published program of its own, above the product crate
    // whose protocol it answers and below none.
    assert_eq!(rules["ur-sim"].kind, Kind::Simulator);
    assert!(rules["ur-sim"].kind.is_published() && !rules["ur-sim"].kind.is_product());
    // The servo bus on a pty is a published simulator, above the crate whose protocol it speaks.
    assert_eq!(rules["dxl-sim"].kind, Kind::Simulator);
    assert!(rules["dxl-sim"].kind.is_published() && !rules["dxl-sim"].kind.is_product());
    // The installable stack is a product; the papers' scenes are the composition root above it.
    assert_eq!(rules["handstack"].kind, Kind::Product);
    assert_eq!(rules["paper-scenes"].kind, Kind::Composition);
}

fn package(name: &str, unpublished: bool, deps: &[(&str, &'static str, bool)]) -> Package {
    Package {
        name: name.into(),
        unpublished,
        docs_rs_all_features: !unpublished,
        rust_version: Some("1.85".into()),
        dir: PathBuf::from("/nonexistent").join(name),
        deps: deps
            .iter()
            .map(|&(to, kind, optional)| edge(to, kind, optional))
            .collect(),
        bins: Vec::new(),
        features: BTreeMap::new(),
    }
}

fn edge(to: &str, kind: &'static str, optional: bool) -> Edge {
    Edge {
        to: to.into(),
        kind,
        optional,
        features: Vec::new(),
        default_features: true,
        target: None,
    }
}

/// A graph that obeys the real table: each product crate with its allowed edges.
fn lawful() -> Vec<Package> {
    vec![
        package("hand-traits", false, &[]),
        package("sim-clock", false, &[("embedded-hal", "normal", false)]),
        package(
            "baro-drivers",
            false,
            &[
                ("embedded-hal", "normal", false),
                ("rand", "normal", true),
                ("sim-clock", "normal", true),
            ],
        ),
        package("imu-icm20789", false, &[("embedded-hal", "normal", false)]),
        package("aot-locate", false, &[("hand-traits", "normal", false)]),
        package("fuzzy-mamdani", false, &[("hand-traits", "normal", false)]),
        package("tactile-nets", false, &[("aot-locate", "normal", false)]),
        package("hand-control", false, &[("fuzzy-mamdani", "dev", false)]),
        package("ur-bridge", false, &[("ur-bridge", "dev", false)]),
        package("ur-sim", false, &[("ur-bridge", "normal", false)]),
        package("hand-zenoh", false, &[("hand-traits", "normal", false)]),
        package("firmata-host", false, &[]),
        package("fingertip-link", false, &[]),
        package(
            "underactuated-hand",
            false,
            &[
                ("hand-traits", "normal", false),
                ("firmata-host", "normal", true),
            ],
        ),
        package(
            "firmata-sim",
            false,
            &[
                ("firmata-host", "normal", false),
                ("baro-drivers", "normal", false),
            ],
        ),
        package(
            "dxl-sim",
            false,
            &[
                ("hand-control", "normal", false),
                ("fuzzy-mamdani", "dev", false),
            ],
        ),
        package(
            "hand-sim",
            true,
            &[
                ("baro-drivers", "normal", false),
                ("dxl-sim", "normal", false),
            ],
        ),
        package("paper-fixtures", true, &[]),
        package("paper-experiments", true, &[("hand-sim", "normal", false)]),
        package("handstack-benches", true, &[("hand-sim", "normal", false)]),
        package(
            "handstack-fuzz",
            true,
            &[
                ("handstack", "normal", false),
                ("paper-experiments", "normal", false),
            ],
        ),
        package(
            "handstack",
            false,
            &[
                ("hand-control", "normal", false),
                ("hand-zenoh", "normal", true),
            ],
        ),
        package(
            "paper-scenes",
            true,
            &[
                ("handstack", "normal", false),
                ("paper-experiments", "normal", false),
                // Seed 001's hand behind the simulated Arduino: a published simulator plugged
                // with hand-sim's physics where both may be used, never the other way round.
                ("firmata-sim", "normal", false),
                ("hand-sim", "normal", false),
            ],
        ),
        package(
            "xtask",
            true,
            &[
                ("paper-fixtures", "normal", false),
                ("anyhow", "normal", false),
            ],
        ),
    ]
}

/// The violations after `edit` changes the lawful graph.
fn after(edit: impl FnOnce(&mut Vec<Package>)) -> Vec<String> {
    let mut packages = lawful();
    edit(&mut packages);
    check(&rules(), &packages)
        .iter()
        .map(ToString::to_string)
        .collect()
}

fn add(packages: &mut [Package], from: &str, to: &str, kind: &'static str, optional: bool) {
    let p = packages.iter_mut().find(|p| p.name == from).expect(from);
    p.deps.push(edge(to, kind, optional));
}

#[test]
fn the_lawful_stand_in_graph_passes() {
    assert_eq!(after(|_| {}), Vec::<String>::new());
}

#[test]
fn a_product_crate_on_the_simulator_fails_under_any_feature_or_kind() {
    for (from, to, kind, optional) in [
        ("hand-control", "hand-sim", "normal", true),
        ("hand-control", "dxl-sim", "dev", false),
        ("baro-drivers", "dxl-sim", "normal", true),
        ("ur-bridge", "hand-sim", "dev", false),
        ("ur-bridge", "ur-sim", "dev", false),
        ("handstack", "ur-sim", "dev", false),
        ("tactile-nets", "paper-experiments", "normal", false),
        ("aot-locate", "paper-fixtures", "dev", false),
    ] {
        let bad = after(|p| add(p, from, to, kind, optional));
        assert!(
            bad.iter()
                .any(|b| b.contains(&format!("`{from}` → `{to}`")) && b.contains("reproduction")),
            "{from} → {to}: {bad:?}"
        );
    }
}

#[test]
fn a_simulator_uses_the_product_crate_of_its_protocol_never_the_reproduction() {
    let bad = after(|p| add(p, "ur-sim", "paper-experiments", "normal", false));
    assert!(
        bad.iter()
            .any(|b| b.contains("`ur-sim` → `paper-experiments`")
                && b.contains("never depends on a reproduction crate")),
        "{bad:?}"
    );
    // The underactuated hand's physics reaches the Arduino simulator from the composition
    // root (paper-scenes' hand board); the simulator never reaches for it.
    let bad = after(|p| add(p, "firmata-sim", "hand-sim", "normal", false));
    assert!(
        bad.iter().any(|b| b.contains("`firmata-sim` → `hand-sim`")
            && b.contains("never depends on a reproduction crate")),
        "{bad:?}"
    );
    // Nor a product crate other than the ones its row names.
    let bad = after(|p| add(p, "ur-sim", "handstack", "normal", false));
    assert!(
        bad.iter()
            .any(|b| b.contains("`ur-sim` → `handstack`") && b.contains("not in its row")),
        "{bad:?}"
    );
}

#[test]
fn nothing_may_depend_on_the_composition_root() {
    let bad = after(|p| add(p, "paper-experiments", "paper-scenes", "normal", false));
    assert!(
        bad.iter().any(|b| b.contains("composition root")),
        "{bad:?}"
    );
}

#[test]
fn the_installable_stack_stays_free_of_the_reproduction_and_under_no_product_crate() {
    for (from, to, kind) in [
        ("handstack", "hand-sim", "normal"),
        ("handstack", "paper-fixtures", "dev"),
        ("handstack", "paper-experiments", "build"),
    ] {
        let bad = after(|p| add(p, from, to, kind, false));
        assert!(
            bad.iter()
                .any(|b| b.contains(&format!("`{from}` → `{to}`")) && b.contains("reproduction")),
            "{from} → {to}: {bad:?}"
        );
    }
    // A product crate below the stack cannot reach up to it (its row does not name it).
    let bad = after(|p| add(p, "hand-control", "handstack", "normal", true));
    assert!(
        bad.iter()
            .any(|b| b.contains("`hand-control` → `handstack`") && b.contains("rules table")),
        "{bad:?}"
    );
    // And the stack is published.
    let bad = after(|p| {
        if let Some(h) = p.iter_mut().find(|p| p.name == "handstack") {
            h.unpublished = true;
        }
    });
    assert!(
        bad.iter()
            .any(|b| b.contains("`handstack` is a product crate but publish = false")),
        "{bad:?}"
    );
}

/// The crates `handstack` links with `features` (normal edges).
fn handstack_tree(features: &str) -> Vec<String> {
    let out = std::process::Command::new(env!("CARGO"))
        .current_dir(xtask::workspace_root())
        .args([
            "tree",
            "-p",
            "handstack",
            "--features",
            features,
            "-e",
            "normal",
        ])
        .args(["--prefix", "none", "--offline", "--locked"])
        .output()
        .expect("cargo tree");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.split(' ').next().map(str::to_owned))
        .collect()
}

/// The installable binary runs every learned model without an ML framework: tactile-nets'
/// `train` feature (dfdx; nalgebra's Levenberg–Marquardt) stays out of its dependency tree
/// with every feature but its own `train` (`handstack train`, the one build that trains).
#[test]
fn the_installable_stack_links_no_ml_framework_but_to_train() {
    let run = handstack_tree("cell");
    assert!(run.iter().any(|c| c == "tactile-nets"), "{run:?}");
    let train = handstack_tree("cell,train");
    for framework in ["dfdx", "levenberg-marquardt"] {
        assert!(
            !run.iter().any(|c| c == framework),
            "handstack links {framework}"
        );
        assert!(
            train.iter().any(|c| c == framework),
            "train lacks {framework}"
        );
    }
}

#[test]
fn a_driver_uses_embedded_hal_and_its_listed_crates_only() {
    let bad = after(|p| add(p, "baro-drivers", "serde", "normal", false));
    assert!(
        bad.iter().any(|b| b.contains("`baro-drivers` → `serde`")),
        "{bad:?}"
    );
    let bad = after(|p| add(p, "imu-icm20789", "aot-locate", "normal", false));
    assert!(bad.iter().any(|b| b.contains("not in its row")), "{bad:?}");
    // Dev-dependencies (tests against a mock bus) are free.
    assert_eq!(
        after(|p| add(p, "baro-drivers", "embedded-hal-mock", "dev", false)),
        Vec::<String>::new()
    );
}

#[test]
fn xtask_stays_thin() {
    for (to, what) in [
        ("hand-sim", "not in its row"),
        ("tactile-nets", "not in its row"),
        ("paper-experiments", "not in its row"),
        ("plotters", "a tool uses its listed third-party crates only"),
        ("dfdx", "a tool uses its listed third-party crates only"),
    ] {
        let bad = after(|p| add(p, "xtask", to, "normal", false));
        assert!(
            bad.iter()
                .any(|b| b.contains(&format!("`xtask` → `{to}`")) && b.contains(what)),
            "xtask → {to}: {bad:?}"
        );
    }
}

#[test]
fn an_edge_the_table_does_not_list_fails() {
    let bad = after(|p| add(p, "tactile-nets", "fuzzy-mamdani", "normal", false));
    assert!(
        bad.iter()
            .any(|b| b.contains("`tactile-nets` → `fuzzy-mamdani`") && b.contains("not in its row")),
        "{bad:?}"
    );
}

#[test]
fn publish_flags_follow_the_kind_and_every_crate_is_documented() {
    let bad = after(|p| p[0].unpublished = true);
    assert!(
        bad.iter()
            .any(|b| b.contains("`hand-traits` is a product crate")),
        "{bad:?}"
    );
    let bad = after(|p| {
        let sim = p
            .iter_mut()
            .find(|p| p.name == "hand-sim")
            .expect("hand-sim");
        sim.unpublished = false;
    });
    assert!(
        bad.iter()
            .any(|b| b.contains("`hand-sim`") && b.contains("publish = false"))
    );
    // A simulator is published, and documented as a product crate is.
    let bad = after(|p| {
        let dxl = p.iter_mut().find(|p| p.name == "dxl-sim").expect("dxl-sim");
        dxl.unpublished = true;
    });
    assert!(
        bad.iter()
            .any(|b| b.contains("`dxl-sim` is a simulator but publish = false")),
        "{bad:?}"
    );
    let bad = after(|p| {
        let dxl = p.iter_mut().find(|p| p.name == "dxl-sim").expect("dxl-sim");
        dxl.docs_rs_all_features = false;
    });
    assert!(
        bad.iter()
            .any(|b| b.contains("`dxl-sim` is a simulator without")),
        "{bad:?}"
    );
    let bad = after(|p| p.push(package("stray", false, &[])));
    assert!(
        bad.iter().any(|b| b.contains("`stray` is not in")),
        "{bad:?}"
    );
    let bad = after(|p| p.retain(|p| p.name != "xtask"));
    assert!(
        bad.iter()
            .any(|b| b.contains("`xtask`, which is no workspace crate"))
    );
}

#[test]
fn a_product_crate_naming_a_repository_path_fails() {
    let dir = std::env::temp_dir().join(format!("arch-paths-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("src/models")).expect("temp dir");
    std::fs::write(
        dir.join("src/models/mod.rs"),
        "// reads fixtures/models in the docs only\nconst M: &str = \"fixtures/models/x\";\n",
    )
    .expect("write");
    let mut p = package("tactile-nets", false, &[]);
    p.dir = dir.clone();
    let bad = repository_paths(&rules(), &[p]);
    std::fs::remove_dir_all(&dir).expect("cleanup");
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(bad[0].to_string().contains("mod.rs:2"), "{}", bad[0]);
}

#[test]
fn the_packaged_crates_are_the_tables_published_crates() {
    let crates = xtask::package::published_crates(&xtask::workspace_root()).expect("the table");
    assert_eq!(
        crates,
        [
            "aot-locate",
            "baro-drivers",
            "dxl-sim",
            "fingertip-link",
            "firmata-host",
            "firmata-sim",
            "fuzzy-mamdani",
            "hand-control",
            "hand-traits",
            "hand-zenoh",
            "handstack",
            "imu-icm20789",
            "sim-clock",
            "tactile-nets",
            "underactuated-hand",
            "ur-bridge",
            "ur-sim",
        ]
    );
}

#[test]
fn a_product_crate_on_the_simulator_is_named_as_such() {
    let bad = after(|p| add(p, "hand-control", "dxl-sim", "normal", false));
    assert!(
        bad.iter()
            .any(|b| b.contains("`hand-control` → `dxl-sim` (normal)")
                && b.contains("never depends on a simulator")),
        "{bad:?}"
    );
    // The published simulator too, even for tests only: spawn its binary instead.
    let bad = after(|p| add(p, "handstack", "ur-sim", "dev", false));
    assert!(
        bad.iter()
            .any(|b| b.contains("`handstack` → `ur-sim` (dev)")
                && b.contains("never depends on a simulator")),
        "{bad:?}"
    );
    // And a simulator is published (users install it), with docs.rs documenting all of it.
    let bad = after(|p| {
        let sim = p.iter_mut().find(|p| p.name == "ur-sim").expect("sim");
        sim.unpublished = true;
    });
    assert!(
        bad.iter()
            .any(|b| b.contains("`ur-sim` is a simulator but publish = false")),
        "{bad:?}"
    );
    let bad = after(|p| {
        let sim = p.iter_mut().find(|p| p.name == "ur-sim").expect("sim");
        sim.docs_rs_all_features = false;
    });
    assert!(
        bad.iter().any(|b| b.contains(
            "`ur-sim` is a simulator without `[package.metadata.docs.rs] all-features = true`"
        )),
        "{bad:?}"
    );
}

// ---- the drawn graph ----------------------------------------------------------------------------

fn doc() -> String {
    std::fs::read_to_string(xtask::workspace_root().join(DOC)).expect(DOC)
}

#[test]
fn the_drawn_graph_is_the_one_cargo_metadata_declares() {
    let doc = doc();
    let rules = parse_rules(&doc).expect("the rules table parses");
    let packages = workspace_packages(&xtask::workspace_root()).expect("cargo metadata");
    let generated = graph(&rules, &packages).expect("the graph draws");
    let in_doc = drawn(&doc).expect("the generated part's markers");
    if in_doc != generated.trim_matches('\n') {
        let diff: Vec<String> = generated
            .lines()
            .filter(|l| !in_doc.lines().any(|d| d == *l))
            .map(|l| format!("  + {l}"))
            .chain(
                in_doc
                    .lines()
                    .filter(|d| !generated.lines().any(|l| l == *d))
                    .map(|l| format!("  - {l}")),
            )
            .collect();
        panic!(
            "{DOC}'s crate graph is not the one cargo metadata declares; run \
             `cargo xtask architecture` to redraw it. Lines (+ metadata, - document):\n{}",
            diff.join("\n")
        );
    }
    // What the graph is known to hold, so the comparison cannot pass on an empty drawing.
    let row = |name: &str| {
        in_doc
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}` |")))
            .unwrap_or_else(|| panic!("no row for {name}"))
            .to_string()
    };
    assert_eq!(
        in_doc.lines().filter(|l| l.starts_with("| `")).count(),
        packages.len()
    );
    let experiments = row("paper-experiments");
    for edge in [
        "`baro-drivers`",
        "`sim-clock`",
        "`dxl-sim`",
        "`imu-icm20789[sim]`",
        "`hand-control[sim-clock]`",
        "`ur-bridge` (optional: default feature `arm`)",
        "`ur-sim` (optional: default feature `arm`)",
    ] {
        assert!(experiments.contains(edge), "{edge} not in {experiments}");
    }
    assert!(
        row("handstack").contains("`tactile-nets[std]` (no default features; `train` → `[train]`)")
    );
    assert!(row("handstack").contains("`hand-zenoh` (no default features; `cell` → `[node]`)"));
    for group in [
        "**Product crates (published)**",
        "**Reproduction crates (publish = false)**",
        "**Simulators (published)**",
        "**Tools (publish = false)**",
    ] {
        assert!(in_doc.contains(group), "{group}");
    }
}

#[test]
fn an_edited_drawing_differs_from_the_generated_one() {
    let doc = doc();
    let generated = drawn(&doc).expect("markers").to_string();
    let edited = splice(
        &doc,
        &generated.replace("`hand-control[sim-clock]`", "`hand-control`"),
    )
    .expect("splice");
    assert_ne!(drawn(&edited).expect("markers"), generated);
    // Splicing puts back exactly what it is given, and is idempotent.
    let again = splice(&edited, &generated).expect("splice");
    assert_eq!(drawn(&again).expect("markers"), generated);
    assert_eq!(splice(&again, &generated).expect("splice"), again);
    assert!(drawn("no markers here").is_err());
    assert!(drawn(&format!("{END}\n{BEGIN}\n")).is_err());
}

/// A small graph with every kind of edge the drawing distinguishes.
fn stand_in_graph() -> (BTreeMap<String, Rule>, Vec<Package>) {
    let rules = rules();
    let mut clock = package("sim-clock", false, &[("sim-clock", "dev", false)]);
    clock.features.insert("embedded-hal-async".into(), vec![]);
    let mut baro = package("baro-drivers", false, &[("sim-clock", "normal", true)]);
    baro.features.insert(
        "sim".into(),
        vec!["dep:rand".into(), "dep:sim-clock".into()],
    );
    baro.features
        .insert("async".into(), vec!["sim-clock?/embedded-hal-async".into()]);
    let mut sim = package(
        "hand-sim",
        true,
        &[
            ("baro-drivers", "normal", false),
            ("serde", "normal", false),
            ("paper-fixtures", "dev", false),
        ],
    );
    sim.deps[0].features = vec!["sim".into(), "async".into()];
    let mut stack = package("handstack", false, &[("baro-drivers", "normal", false)]);
    stack.deps[0].default_features = false;
    stack.deps[0].target = Some("cfg(unix)".into());
    let mut ur_sim = package(
        "ur-sim",
        false,
        &[("ur-bridge", "normal", false), ("ur-bridge", "dev", false)],
    );
    ur_sim.deps[0].default_features = false;
    ur_sim.deps[1].features = vec!["rtde-client".into()];
    let packages = vec![
        stack,
        ur_sim,
        sim,
        package("ur-bridge", false, &[]),
        package("dxl-sim", false, &[("hand-control", "normal", false)]),
        package("xtask", true, &[("paper-fixtures", "normal", false)]),
        package("paper-fixtures", true, &[]),
        baro,
        package("hand-control", false, &[]),
        clock,
    ];
    (rules, packages)
}

#[test]
fn the_drawing_is_grouped_sorted_and_names_features() {
    let (rules, packages) = stand_in_graph();
    let drawing = graph(&rules, &packages).expect("draws");
    let expected = "\
10 workspace crates; 6 edges between them, and 2 more in tests, examples and benches (`cargo metadata`).

**Product crates (published)**

| crate | uses | tests, examples and benches also use |
|---|---|---|
| `baro-drivers` | `sim-clock` (optional: `sim`; `async` → `[embedded-hal-async]`) | — |
| `hand-control` | — | — |
| `handstack` | `baro-drivers` (no default features; on `cfg(unix)` only) | — |
| `sim-clock` | — | — |
| `ur-bridge` | — | — |

**Simulators (published)**

| crate | uses | tests, examples and benches also use |
|---|---|---|
| `dxl-sim` | `hand-control` | — |
| `ur-sim` | `ur-bridge` (no default features) | `ur-bridge[rtde-client]` |

**Reproduction crates (publish = false)**

| crate | uses | tests, examples and benches also use |
|---|---|---|
| `hand-sim` | `baro-drivers[async, sim]` | `paper-fixtures` |
| `paper-fixtures` | — | — |

**Tools (publish = false)**

| crate | uses | tests, examples and benches also use |
|---|---|---|
| `xtask` | `paper-fixtures` | — |
";
    assert_eq!(drawing, expected);
    // The order cargo metadata lists crates in does not matter.
    let (_, mut reversed) = stand_in_graph();
    reversed.reverse();
    assert_eq!(graph(&rules, &reversed).expect("draws"), expected);
}

#[test]
fn a_crate_the_rules_table_does_not_know_cannot_be_drawn() {
    let (rules, mut packages) = stand_in_graph();
    packages.push(package("stray", true, &[]));
    let err = graph(&rules, &packages).expect_err("unknown crate");
    assert!(err.to_string().contains("`stray` is not in"), "{err}");
    // A published crate is a product crate whatever its row says, so it draws.
    let (rules, mut packages) = stand_in_graph();
    packages.push(package("stray", false, &[]));
    let drawing = graph(&rules, &packages).expect("draws");
    assert_eq!(
        Group::of(packages.last().expect("stray"), &rules).expect("group"),
        Group::Product
    );
    assert!(drawing.contains("| `stray` | — | — |"), "{drawing}");
}

// ---- binaries of product crates -----------------------------------------------------------------

fn with_bins(name: &str, unpublished: bool, bins: &[&str]) -> Package {
    let mut p = package(name, unpublished, &[]);
    p.bins = bins.iter().map(|b| b.to_string()).collect();
    p
}

#[test]
fn a_new_binary_in_a_product_crate_fails() {
    let known: &[(&str, &str)] = &[("hand-control", "dxl-sim")];
    let packages = vec![
        with_bins("handstack", false, &["handstack"]),
        with_bins("hand-control", false, &["dxl-sim"]),
        with_bins("paper-scenes", true, &["paper-scenes"]),
    ];
    assert_eq!(product_bins(&rules(), &packages, known), []);
    let mut more = packages.clone();
    more[1].bins.push("dxl-probe".into());
    more[0].bins.push("handstack-extra".into());
    let bad: Vec<String> = product_bins(&rules(), &more, known)
        .iter()
        .map(ToString::to_string)
        .collect();
    assert_eq!(bad.len(), 2, "{bad:?}");
    assert!(
        bad.iter()
            .any(|b| b.contains("`hand-control` has a binary `dxl-probe`"))
    );
    assert!(
        bad.iter()
            .any(|b| b.contains("`handstack` has a binary `handstack-extra`"))
    );
}

#[test]
fn a_known_binary_that_is_gone_fails_naming_the_line_to_delete() {
    let known: &[(&str, &str)] = &[("hand-control", "dxl-sim"), ("ur-bridge", "ur-sim")];
    let packages = vec![
        with_bins("hand-control", false, &["dxl-sim"]),
        with_bins("ur-bridge", false, &[]),
        // Moved to a simulator crate, published: a simulator's program is no product binary.
        with_bins("ur-sim", false, &["ur-sim"]),
    ];
    let bad = product_bins(&rules(), &packages, known);
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(
        bad[0]
            .to_string()
            .contains("`(\"ur-bridge\", \"ur-sim\"),`"),
        "{}",
        bad[0]
    );
}

// ---- paper seeds in product crates --------------------------------------------------------------

#[test]
fn seed_mentions_are_counted_like_the_pattern_says() {
    let text = "\
// Seed 000 §4 and seed002's loop
let x = 1; // SEED 001, seed 001 again
// seed 003, seed  000, seed_000, seedling 000, seeded 001: none of them
";
    assert_eq!(seed_mention_lines(text), [1, 1, 2, 2]);
    assert_eq!(seed_mention_lines("seed00"), Vec::<usize>::new());
}

/// A scratch product crate `name` under `root` with `files` (path under `src/`, text).
fn scratch_crate(root: &Path, name: &str, unpublished: bool, files: &[(&str, &str)]) -> Package {
    let dir = root.join("crates").join(name);
    for (path, text) in files {
        let file = dir.join("src").join(path);
        std::fs::create_dir_all(file.parent().expect("parent")).expect("dir");
        std::fs::write(file, text).expect("write");
    }
    let mut p = package(name, unpublished, &[]);
    p.dir = dir;
    p
}

struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> TempDir {
        let dir = std::env::temp_dir().join(format!("arch-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn seed_report(root: &Path, packages: &[Package], known: &[(&str, usize)]) -> Vec<String> {
    seed_mentions(root, packages, known)
        .iter()
        .map(ToString::to_string)
        .collect()
}

#[test]
fn a_new_paper_seed_mention_in_a_product_crate_fails() {
    let tmp = TempDir::new("seeds-new");
    let packages = vec![
        scratch_crate(
            &tmp.0,
            "aot-locate",
            false,
            &[
                ("lib.rs", "//! seed 000 eq. 3\n"),
                ("pad/cells.rs", "// cells\n"),
            ],
        ),
        // A reproduction crate may name the papers as it likes.
        scratch_crate(
            &tmp.0,
            "hand-sim",
            true,
            &[("lib.rs", "// seed 001 seed 002\n")],
        ),
    ];
    let known: &[(&str, usize)] = &[("crates/aot-locate/src/lib.rs", 1)];
    assert_eq!(seed_report(&tmp.0, &packages, known), Vec::<String>::new());

    // One more in a known file, and one in a new file.
    let packages = vec![
        scratch_crate(
            &tmp.0,
            "aot-locate",
            false,
            &[
                ("lib.rs", "//! seed 000 eq. 3\n//! and seed000 again\n"),
                ("pad/cells.rs", "// cells\n/// Seed 002's grid\n"),
            ],
        ),
        packages[1].clone(),
    ];
    let bad = seed_report(&tmp.0, &packages, known);
    assert_eq!(bad.len(), 2, "{bad:?}");
    assert!(
        bad.iter().any(|b| b.starts_with(
            "crates/aot-locate/src/lib.rs: names a paper seed 2 times (lines 1, 2), 1 known"
        )),
        "{bad:?}"
    );
    assert!(
        bad.iter().any(|b| b.starts_with(
            "crates/aot-locate/src/pad/cells.rs: names a paper seed 1 times (lines 2), 0 known"
        )),
        "{bad:?}"
    );
}

#[test]
fn a_known_seed_mention_that_is_gone_fails_naming_the_line_to_change_or_delete() {
    let tmp = TempDir::new("seeds-gone");
    let packages = vec![scratch_crate(
        &tmp.0,
        "tactile-nets",
        false,
        &[
            ("lib.rs", "//! the force DNN (seed 000 §2.2)\n"),
            ("softness.rs", "//! the softness network\n"),
        ],
    )];
    let known: &[(&str, usize)] = &[
        ("crates/tactile-nets/src/lib.rs", 3),
        ("crates/tactile-nets/src/softness.rs", 1),
        ("crates/tactile-nets/src/removed.rs", 2),
    ];
    let bad = seed_report(&tmp.0, &packages, known);
    assert_eq!(bad.len(), 3, "{bad:?}");
    for fix in [
        "change its line `(\"crates/tactile-nets/src/lib.rs\", 3),` to `(\"crates/tactile-nets/src/lib.rs\", 1),`",
        "delete its line `(\"crates/tactile-nets/src/softness.rs\", 1),`",
        "delete its line `(\"crates/tactile-nets/src/removed.rs\", 2),`",
    ] {
        assert!(bad.iter().any(|b| b.ends_with(fix)), "{fix}: {bad:?}");
    }
}

#[test]
fn the_known_exceptions_are_sorted_unique_and_real() {
    let mut sorted = KNOWN_SEED_MENTIONS.to_vec();
    sorted.sort();
    sorted.dedup_by_key(|(path, _)| *path);
    assert_eq!(
        sorted, KNOWN_SEED_MENTIONS,
        "sorted by path, one line per file"
    );
    assert!(KNOWN_SEED_MENTIONS.iter().all(|&(_, n)| n > 0));
    let mut bins = KNOWN_PRODUCT_BINS.to_vec();
    bins.sort();
    bins.dedup();
    assert_eq!(bins, KNOWN_PRODUCT_BINS);
    // Each names a product crate of the rules table.
    let rules = rules();
    for (krate, _) in KNOWN_PRODUCT_BINS {
        assert!(rules[*krate].kind.is_product(), "{krate}");
    }
    for (path, _) in KNOWN_SEED_MENTIONS {
        let krate = path
            .strip_prefix("crates/")
            .and_then(|p| p.split('/').next())
            .expect("crates/NAME/src/…");
        assert!(rules[krate].kind.is_product(), "{path}");
    }
}
