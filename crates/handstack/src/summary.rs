//! The summary table `handstack run` prints after the runs: figure, value, paper, target, met.

use crate::Outcome;
use std::fmt::Write as _;

/// A figure's number as every output of a run shows it (this table, the HTML report): 4
/// significant digits without trailing zeros, and powers of ten beyond 10⁻⁴…10⁸.
///
/// ```
/// use handstack::summary::number;
/// assert_eq!(number(94.91666), "94.92");
/// assert_eq!(number(0.25), "0.25");
/// assert_eq!(number(0.0029751), "0.002975");
/// assert_eq!(number(20.0), "20");
/// assert_eq!(number(2.5e-7), "2.500e-7");
/// ```
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if !(-4..=7).contains(&magnitude) {
        return format!("{v:.3e}");
    }
    let digits = (3 - magnitude).clamp(0, 6) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// Prints `outcome` on stdout: as JSON, or as its table and then its notes.
pub fn print(outcome: &Outcome, json: bool) {
    if json {
        match serde_json::to_string_pretty(outcome) {
            Ok(s) => println!("{s}"),
            Err(e) => eprintln!("error: cannot write JSON: {e}"),
        }
    } else {
        println!("{}", table(outcome));
        for note in &outcome.notes {
            println!("  {note}");
        }
    }
}

/// The summary of `outcome` as an aligned text table.
///
/// ```
/// use handstack::{Figure, Outcome};
/// let o = Outcome { scene: "s".into(), title: "t".into(), plots: vec![], notes: vec![], wall_s: 0.5,
///     figures: vec![Figure { name: "err".into(), label: "max error".into(), value: 0.25,
///         unit: "gf".into(), paper: Some(1.17), source: None, target: Some("≤ 0.5 gf".into()),
///         met: Some(true), finding: None }] };
/// let table = handstack::summary::table(&o);
/// assert!(table.contains("max error") && table.contains("0.25 gf") && table.contains("yes"));
/// ```
pub fn table(outcome: &Outcome) -> String {
    let mut rows = vec![[
        "figure".to_owned(),
        "value".to_owned(),
        "paper".to_owned(),
        "target".to_owned(),
        "met".to_owned(),
    ]];
    for f in &outcome.figures {
        let unit = if f.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", f.unit)
        };
        rows.push([
            f.label.clone(),
            format!("{}{unit}", number(f.value)),
            f.paper
                .map_or_else(|| "—".to_owned(), |p| format!("{}{unit}", number(p))),
            f.target.clone().unwrap_or_else(|| "—".to_owned()),
            match (f.met, &f.finding) {
                (Some(true), _) => "yes".to_owned(),
                (Some(false), Some(_)) => "no: finding".to_owned(),
                (Some(false), None) => "NO".to_owned(),
                (None, _) => "—".to_owned(),
            },
        ]);
    }
    let widths: Vec<usize> = (0..5)
        .map(|i| rows.iter().map(|r| r[i].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = format!(
        "{} — {} ({:.1} s)\n",
        outcome.scene, outcome.title, outcome.wall_s
    );
    for (n, r) in rows.iter().enumerate() {
        for (i, cell) in r.iter().enumerate() {
            let pad = widths[i] - cell.chars().count();
            if i == 0 {
                let _ = write!(out, "  {cell}{}", " ".repeat(pad));
            } else {
                let _ = write!(out, "  {}{cell}", " ".repeat(pad));
            }
        }
        out.push('\n');
        if n == 0 {
            let total: usize = widths.iter().sum::<usize>() + 2 * widths.len();
            let _ = writeln!(out, "  {}", "-".repeat(total - 2));
        }
    }
    for f in &outcome.figures {
        if let (Some(false), Some(why)) = (f.met, &f.finding) {
            let _ = writeln!(out, "  finding, {}: {why}", f.label);
        }
    }
    out
}

/// What a command line made of a list of scene files: the outcomes, and each failure as
/// (scene file, error).
#[derive(Debug, Default)]
pub struct Runs {
    /// The scenes that ran, in order.
    pub outcomes: Vec<Outcome>,
    /// The scenes that failed: file and error text.
    pub failures: Vec<(String, String)>,
    /// The exit status the first failure gives (0 when none failed).
    pub exit_code: u8,
}

/// An error that says which exit status it ends a program with.
pub trait ExitStatus {
    /// The status, 1…255.
    fn exit_code(&self) -> u8;
}

impl ExitStatus for crate::RunError {
    fn exit_code(&self) -> u8 {
        crate::RunError::exit_code(self)
    }
}

/// The line a failed run prints: the error, after its file unless the error names the file
/// already (a scene error says `a.toml:18:1: …`, as `check` prints it; a device error does not).
fn error_line(file: &str, error: &str) -> String {
    match error.strip_prefix(file) {
        Some(rest) if rest.starts_with(':') => format!("error: {error}"),
        _ => format!("error: {file}: {error}"),
    }
}

/// Runs each of `scenes` with `run`, showing progress on `bars`: a summary table per outcome on
/// stdout (unless `json`), followed by its notes (what the run left its devices doing), each
/// error on stderr; with `json`, the outcomes as JSON on stdout at the end. Once `stop` is set
/// (a signal), the scenes after the one it stopped are not run. The `handstack` binary and the
/// papers' `paper-scenes` both run their scenes so.
pub fn run_each<E: core::fmt::Display + ExitStatus>(
    scenes: &[std::path::PathBuf],
    json: bool,
    bars: &crate::progress::Bars,
    stop: &crate::stop::Stop,
    run: impl Fn(&std::path::Path) -> Result<Outcome, E>,
) -> Runs {
    let mut runs = Runs::default();
    for path in scenes {
        if stop.is_set() {
            break;
        }
        bars.prefix(path.display().to_string());
        match run(path) {
            Ok(o) => {
                if !json {
                    bars.suspend(|| {
                        println!("{}", table(&o));
                        for note in &o.notes {
                            println!("  {note}");
                        }
                    });
                }
                runs.outcomes.push(o);
            }
            Err(e) => {
                let file = path.display().to_string();
                let text = e.to_string();
                bars.suspend(|| eprintln!("{}", error_line(&file, &text)));
                if runs.failures.is_empty() {
                    runs.exit_code = e.exit_code();
                }
                runs.failures.push((file, text));
            }
        }
    }
    if let Some(reason) = stop.reason() {
        // A signal's status says so, whatever the stopped run returned; a run that returned
        // its figures when stopped (a cell's taps so far) has not said it was stopped.
        runs.exit_code = reason.exit_code();
        if runs.failures.is_empty() {
            bars.suspend(|| {
                eprintln!("stopped by {reason}: the figures above cover the run up to then")
            });
        }
    }
    bars.finish();
    if json {
        match serde_json::to_string_pretty(&runs.outcomes) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("error: cannot write JSON: {e}");
                runs.failures.push(("(all)".into(), e.to_string()));
                runs.exit_code = runs.exit_code.max(crate::error::EXIT_NOT_STARTED);
            }
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::{error_line, table};
    use crate::runs::figure::{Target, finding, measured, target};
    use crate::{Figure, Outcome};

    /// A missed target with a known reason reads as a finding, with its reason under the
    /// table; a plain miss stays `NO`.
    #[test]
    fn a_finding_is_told_apart_from_a_miss() {
        let f = |name: &str| target(measured(name, name, 20.0, "%"), Target::AtLeast(90.0));
        let figures: Vec<Figure> = vec![f("ours"), finding(f("eq3"), "the formula as written")];
        let o = Outcome {
            scene: "s".into(),
            title: "t".into(),
            figures,
            plots: vec![],
            notes: vec![],
            wall_s: 1.0,
        };
        let text = table(&o);
        assert!(
            text.lines()
                .any(|l| l.contains("ours") && l.ends_with("NO")),
            "{text}"
        );
        assert!(
            text.lines()
                .any(|l| l.contains("eq3") && l.ends_with("no: finding")),
            "{text}"
        );
        assert!(
            text.contains("  finding, eq3: the formula as written\n"),
            "{text}"
        );
        // A met target is never a finding.
        let met = finding(
            target(measured("m", "m", 95.0, "%"), Target::AtLeast(90.0)),
            "x",
        );
        assert_eq!(met.finding, None);
    }

    /// A scene error names its file once, not `error: a.toml: a.toml:18:1: …`.
    #[test]
    fn an_error_line_names_the_file_once() {
        assert_eq!(
            error_line("a.toml", "a.toml:18:1: unclosed table, expected `]`"),
            "error: a.toml:18:1: unclosed table, expected `]`"
        );
        assert_eq!(
            error_line(
                "a.toml",
                "a.toml: cannot read: No such file or directory (os error 2)"
            ),
            "error: a.toml: cannot read: No such file or directory (os error 2)"
        );
        assert_eq!(
            error_line("a.toml", "cannot open hand at /dev/ttyUSB0: not found"),
            "error: a.toml: cannot open hand at /dev/ttyUSB0: not found"
        );
        // Another file's name at the start is not this file's.
        assert_eq!(
            error_line("a.toml", "a.toml.bak:1:1: x"),
            "error: a.toml: a.toml.bak:1:1: x"
        );
    }
}
