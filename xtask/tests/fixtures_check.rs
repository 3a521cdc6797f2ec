//! `cargo xtask fixtures --check` passes on the committed tree and fails, naming the file, when a
//! generated fixture is edited, removed or joined by a stray file, or when its source changes.
//!
//! The mechanism is exercised with the `paper-derived` generator alone: it is pure Rust over
//! `fixtures/`, so a scratch copy of that folder is a complete workspace for it. Every generator
//! (the Python-backed ones and the datasets included) is checked on the real tree by
//! `cargo xtask test`, which ends with `fixtures --check`.

use std::path::{Path, PathBuf};
use xtask::fixtures::{Ctx, Difference, GENERATORS, Generator, Mode, regenerate};

/// The generator the mechanism is tested with.
fn derived() -> &'static [Generator] {
    let g = GENERATORS
        .iter()
        .find(|g| g.name == "paper-derived")
        .expect("registered");
    std::slice::from_ref(g)
}

/// A scratch copy of the workspace's `fixtures/` tree, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("handstack-fixtures-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        copy_tree(
            &xtask::workspace_root().join("fixtures"),
            &dir.join("fixtures"),
        );
        Scratch(dir)
    }

    fn check(&self) -> Vec<Difference> {
        regenerate(
            &Ctx {
                root: self.0.clone(),
            },
            derived(),
            Mode::Check,
        )
        .unwrap()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let dest = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_tree(&path, &dest);
        } else {
            std::fs::copy(&path, &dest).unwrap();
        }
    }
}

const RISE: &str = "fixtures/derived/seed000_table2_rise.csv";

#[test]
fn committed_fixtures_match_a_fresh_generation() {
    assert_eq!(Scratch::new("clean").check(), []);
}

#[test]
fn an_edited_generated_fixture_fails_the_check() {
    let s = Scratch::new("edited");
    let file = s.0.join(RISE);
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("16.13", "16.50");
    std::fs::write(&file, text).unwrap();
    assert_eq!(s.check(), [Difference::Changed(file)]);
}

#[test]
fn a_removed_or_stray_file_fails_the_check() {
    let s = Scratch::new("removed");
    std::fs::remove_file(s.0.join(RISE)).unwrap();
    let stray = s.0.join("fixtures/derived/stray.csv");
    std::fs::write(&stray, "# nothing makes me\n").unwrap();
    assert_eq!(
        s.check(),
        [
            Difference::Missing(s.0.join(RISE)),
            Difference::Extra(stray)
        ]
    );
}

#[test]
fn an_edited_source_table_changes_what_is_generated() {
    let s = Scratch::new("source");
    let table2 = s.0.join("fixtures/paper/seed000_table2_contact_area.csv");
    let text = std::fs::read_to_string(&table2)
        .unwrap()
        .replacen("1017.52", "1018.52", 1);
    std::fs::write(&table2, text).unwrap();
    assert_eq!(s.check(), [Difference::Changed(s.0.join(RISE))]);
}

#[test]
fn write_mode_repairs_what_check_reports() {
    let s = Scratch::new("write");
    std::fs::write(s.0.join(RISE), "tampered\n").unwrap();
    let ctx = Ctx { root: s.0.clone() };
    assert_eq!(regenerate(&ctx, derived(), Mode::Write).unwrap().len(), 1);
    assert_eq!(s.check(), []);
}
