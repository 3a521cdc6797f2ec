//! `cargo xtask fixtures --check` passes on the committed tree and fails, naming the file, when a
//! generated fixture is edited, removed or joined by a stray file, or when its source changes.
//!
//! The mechanism is exercised with the `paper-derived` generator alone: it is pure Rust over
//! `fixtures/`, so a scratch copy of that folder is a complete workspace for it. Every generator
//! (the Python-backed ones and the datasets included) is checked on the real tree by
//! `cargo xtask test`, which ends with `fixtures --check` (and runs the numpy one again with its
//! widest SIMD kernels off).
//!
//! The value comparison of `fixtures/fuzzy/*.fld` is exercised with stand-in generators that
//! play "another CPU": they return the committed files with every number moved by rounding
//! noise, or with one real change.

use std::path::{Path, PathBuf};
use xtask::fixtures::{
    Compare, Ctx, Difference, Files, GENERATORS, Generator, Mode, regenerate, values::Drift,
};

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
        regenerate(&Ctx::new(&self.0), derived(), Mode::Check).unwrap()
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
    let ctx = Ctx::new(&s.0);
    assert_eq!(regenerate(&ctx, derived(), Mode::Write).unwrap().len(), 1);
    assert_eq!(s.check(), []);
}

// ---- value-compared files: the fuzzy references ------------------------------------------------

/// The committed `fixtures/fuzzy/` files, as the fuzzy generator would return them.
fn committed_fuzzy() -> Files {
    let dir = xtask::workspace_root().join(FUZZY_DIR);
    let mut files = Files::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        files.insert(name, std::fs::read(&path).unwrap());
    }
    files
}

const FUZZY_DIR: &str = "fixtures/fuzzy";

/// The real fuzzy generator's comparison, with `generate` standing in for the Python run.
fn fuzzy_with(generate: fn(&Ctx) -> anyhow::Result<Files>) -> Generator {
    let real = GENERATORS
        .iter()
        .find(|g| g.name == "fuzzy-reference")
        .expect("registered");
    assert!(matches!(
        real.compare,
        Compare::Values {
            extension: ".fld",
            ..
        }
    ));
    Generator { generate, ..*real }
}

/// Applies `edit` to the text of every `.fld` file.
fn edit_fld(edit: impl Fn(&str, &str) -> String) -> Files {
    let mut files = committed_fuzzy();
    for (name, bytes) in files.iter_mut().filter(|(n, _)| n.ends_with(".fld")) {
        *bytes = edit(name, std::str::from_utf8(bytes).unwrap()).into_bytes();
    }
    files
}

/// Every float of every data row moved by 1…16 ulp, alternately up and down (numpy's SIMD
/// kernels differ by up to 16 ulp between CPUs), and printed by Rust (`{:?}`), not Python.
fn rounding_noise(_: &Ctx) -> anyhow::Result<Files> {
    Ok(edit_fld(|_, text| {
        let mut k = 0u64;
        let mut out = String::new();
        for (i, line) in text.lines().enumerate() {
            let row: Vec<String> = line
                .split(' ')
                .map(|field| match field.parse::<f64>() {
                    // Zero has no ulp below it in this bit arithmetic: it stays as written.
                    Ok(v) if i >= 2 && v.is_finite() && v != 0.0 && field.contains('.') => {
                        k += 1;
                        let ulps = 1 + k % 16;
                        let bits = if k % 2 == 0 {
                            v.to_bits() + ulps
                        } else {
                            v.to_bits() - ulps
                        };
                        format!("{:?}", f64::from_bits(bits))
                    }
                    _ => field.to_string(),
                })
                .collect();
            out += &row.join(" ");
            out.push('\n');
        }
        out
    }))
}

/// tipper's first row, `tip_centroid` (10.32…, third column), drifted by 1e-9 relative.
fn one_real_drift(_: &Ctx) -> anyhow::Result<Files> {
    Ok(edit_fld(|name, text| {
        if name != "tipper.fld" {
            return text.to_string();
        }
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        let mut row: Vec<String> = lines[2].split(' ').map(String::from).collect();
        let v: f64 = row[2].parse().unwrap();
        assert!(
            v.abs() >= 1.0,
            "the drift is relative to the value itself here"
        );
        row[2] = format!("{:?}", v * (1.0 + 1e-9));
        lines[2] = row.join(" ");
        lines.join("\n") + "\n"
    }))
}

/// tipper's first two data rows swapped.
fn two_rows_swapped(_: &Ctx) -> anyhow::Result<Files> {
    Ok(edit_fld(|name, text| {
        let mut lines: Vec<&str> = text.lines().collect();
        if name == "tipper.fld" {
            lines.swap(2, 3);
        }
        lines.join("\n") + "\n"
    }))
}

/// tipper's header with one column renamed.
fn header_edited(_: &Ctx) -> anyhow::Result<Files> {
    Ok(edit_fld(|name, text| {
        if name == "tipper.fld" {
            text.replacen("tip_mom", "tip_lom", 1)
        } else {
            text.to_string()
        }
    }))
}

fn unchanged(_: &Ctx) -> anyhow::Result<Files> {
    Ok(committed_fuzzy())
}

fn check_fuzzy(s: &Scratch, generate: fn(&Ctx) -> anyhow::Result<Files>) -> Vec<Difference> {
    regenerate(&Ctx::new(&s.0), &[fuzzy_with(generate)], Mode::Check).unwrap()
}

fn tipper(s: &Scratch) -> PathBuf {
    s.0.join(FUZZY_DIR).join("tipper.fld")
}

/// The drifted lines of tipper.fld, asserting that it is the only file the check reports.
fn tipper_drifts(s: &Scratch, generate: fn(&Ctx) -> anyhow::Result<Files>) -> Vec<Drift> {
    match check_fuzzy(s, generate).as_slice() {
        [Difference::Drifted(file, drifts)] if *file == tipper(s) => drifts.clone(),
        other => panic!("expected tipper.fld alone to drift: {other:?}"),
    }
}

#[test]
fn last_digit_noise_in_every_float_passes_where_a_byte_check_would_not() {
    let s = Scratch::new("noise");
    assert_eq!(check_fuzzy(&s, rounding_noise), []);
    let bytes = Generator {
        compare: Compare::Bytes,
        ..fuzzy_with(rounding_noise)
    };
    let changed = regenerate(&Ctx::new(&s.0), &[bytes], Mode::Check).unwrap();
    let flds = std::fs::read_dir(s.0.join(FUZZY_DIR))
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "fld"))
        .count();
    assert!(flds >= 8, "{flds} .fld files");
    assert_eq!(
        changed.len(),
        flds,
        "every .fld differs in bytes: {changed:?}"
    );
    assert!(changed.iter().all(|d| matches!(d, Difference::Changed(_))));
}

#[test]
fn writing_noise_keeps_the_committed_bytes() {
    let s = Scratch::new("noise-write");
    let before = std::fs::read(tipper(&s)).unwrap();
    let found = regenerate(&Ctx::new(&s.0), &[fuzzy_with(rounding_noise)], Mode::Write).unwrap();
    assert_eq!(found, []);
    assert_eq!(std::fs::read(tipper(&s)).unwrap(), before);
}

#[test]
fn a_one_in_a_billion_drift_of_one_value_fails_naming_file_row_values_and_tolerance() {
    let s = Scratch::new("drift");
    let drifts = tipper_drifts(&s, one_real_drift);
    let [Drift { line: 3, detail }] = drifts.as_slice() else {
        panic!("{drifts:?}");
    };
    let committed = std::fs::read_to_string(tipper(&s)).unwrap();
    let value = committed.lines().nth(2).unwrap().split(' ').nth(2).unwrap();
    for part in [value, "`tip_centroid`", "1e-10"] {
        assert!(detail.contains(part), "{part} not in {detail}");
    }
    let shown = Difference::Drifted(tipper(&s), drifts).to_string();
    assert!(
        shown.contains("tipper.fld") && shown.contains("line 3"),
        "{shown}"
    );
}

#[test]
fn a_reordered_row_or_an_edited_header_fails() {
    let s = Scratch::new("reorder");
    let drifts = tipper_drifts(&s, two_rows_swapped);
    assert_eq!(drifts.iter().map(|d| d.line).collect::<Vec<_>>(), [3, 4]);

    let drifts = tipper_drifts(&s, header_edited);
    assert_eq!(drifts.len(), 1);
    assert_eq!(drifts[0].line, 2);
    assert!(drifts[0].detail.contains("text must match"), "{drifts:?}");
}

#[test]
fn a_stray_or_missing_value_compared_file_fails() {
    let s = Scratch::new("fuzzy-stray");
    let stray = s.0.join(FUZZY_DIR).join("stray.fld");
    std::fs::write(&stray, "x\n1.0\n").unwrap();
    std::fs::remove_file(tipper(&s)).unwrap();
    assert_eq!(
        check_fuzzy(&s, unchanged),
        [Difference::Missing(tipper(&s)), Difference::Extra(stray)]
    );
}
