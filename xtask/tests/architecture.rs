//! The workspace's crate graph obeys `docs/architecture.md`'s rules table (read from
//! `cargo metadata`), and the checker catches each kind of forbidden edge on a stand-in graph.

use std::collections::BTreeMap;
use std::path::PathBuf;
use xtask::architecture::{
    Edge, Kind, Package, Rule, check, parse_rules, repository_paths, workspace_packages,
};

fn rules() -> BTreeMap<String, Rule> {
    let doc = std::fs::read_to_string(xtask::workspace_root().join("docs/architecture.md"))
        .expect("docs/architecture.md");
    parse_rules(&doc).expect("the rules table parses")
}

#[test]
fn the_workspace_graph_is_the_documented_one() {
    let rules = rules();
    let packages = workspace_packages(&xtask::workspace_root()).expect("cargo metadata");
    assert!(packages.len() >= 14, "{} workspace crates", packages.len());
    let mut bad = check(&rules, &packages);
    bad.extend(repository_paths(&rules, &packages));
    let report: Vec<String> = bad.iter().map(ToString::to_string).collect();
    assert!(report.is_empty(), "\n{}", report.join("\n"));
    // The eight product crates of issue 19, and the kinds the rules rest on.
    for name in [
        "hand-traits",
        "baro-drivers",
        "imu-icm20789",
        "aot-locate",
        "fuzzy-mamdani",
        "tactile-nets",
        "hand-control",
        "ur-bridge",
    ] {
        assert!(rules[name].kind.is_product(), "{name}");
    }
    for name in ["hand-sim", "paper-experiments", "paper-fixtures"] {
        assert_eq!(rules[name].kind, Kind::Reproduction, "{name}");
    }
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
            .map(|&(to, kind, optional)| Edge {
                to: to.into(),
                kind,
                optional,
            })
            .collect(),
    }
}

/// A graph that obeys the real table: each product crate with its allowed edges.
fn lawful() -> Vec<Package> {
    vec![
        package("hand-traits", false, &[]),
        package(
            "baro-drivers",
            false,
            &[("embedded-hal", "normal", false), ("rand", "normal", true)],
        ),
        package("imu-icm20789", false, &[("embedded-hal", "normal", false)]),
        package("aot-locate", false, &[("hand-traits", "normal", false)]),
        package("fuzzy-mamdani", false, &[("hand-traits", "normal", false)]),
        package("tactile-nets", false, &[("aot-locate", "normal", false)]),
        package("hand-control", false, &[("fuzzy-mamdani", "dev", false)]),
        package("ur-bridge", false, &[("ur-bridge", "dev", false)]),
        package("hand-zenoh", false, &[("hand-traits", "normal", false)]),
        package("hand-sim", true, &[("baro-drivers", "normal", false)]),
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
    p.deps.push(Edge {
        to: to.into(),
        kind,
        optional,
    });
}

#[test]
fn the_lawful_stand_in_graph_passes() {
    assert_eq!(after(|_| {}), Vec::<String>::new());
}

#[test]
fn a_product_crate_on_the_simulator_fails_under_any_feature_or_kind() {
    for (from, to, kind, optional) in [
        ("hand-control", "hand-sim", "normal", true),
        ("ur-bridge", "hand-sim", "dev", false),
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
fn the_packaged_crates_are_the_tables_product_crates() {
    let crates = xtask::package::product_crates(&xtask::workspace_root()).expect("the table");
    assert_eq!(
        crates,
        [
            "aot-locate",
            "baro-drivers",
            "fuzzy-mamdani",
            "hand-control",
            "hand-traits",
            "hand-zenoh",
            "handstack",
            "imu-icm20789",
            "tactile-nets",
            "ur-bridge",
        ]
    );
}
