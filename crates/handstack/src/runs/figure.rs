//! Building [`Figure`]s: a measured value, the paper's beside it, a target and whether it is met.

use crate::Figure;

/// A target a figure is checked against.
#[derive(Debug, Clone, Copy)]
pub enum Target {
    /// value ≤ bound.
    AtMost(f64),
    /// value ≥ bound.
    AtLeast(f64),
    /// lo ≤ value ≤ hi.
    Between(f64, f64),
    /// |value − centre| ≤ tol.
    Within(f64, f64),
}

impl Target {
    fn text(self, unit: &str) -> String {
        let u = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        match self {
            Target::AtMost(b) => format!("≤ {b}{u}"),
            Target::AtLeast(b) => format!("≥ {b}{u}"),
            Target::Between(lo, hi) => format!("{lo}…{hi}{u}"),
            Target::Within(c, t) => format!("{c} ± {t}{u}"),
        }
    }

    fn met(self, v: f64) -> bool {
        match self {
            Target::AtMost(b) => v <= b,
            Target::AtLeast(b) => v >= b,
            Target::Between(lo, hi) => (lo..=hi).contains(&v),
            Target::Within(c, t) => (v - c).abs() <= t,
        }
    }
}

/// A figure without paper value or target.
pub fn measured(name: &str, label: &str, value: f64, unit: &str) -> Figure {
    Figure {
        name: name.to_owned(),
        label: label.to_owned(),
        value,
        unit: unit.to_owned(),
        paper: None,
        source: None,
        target: None,
        met: None,
        finding: None,
    }
}

/// Adds the paper's value and its source.
pub fn paper(mut f: Figure, value: f64, source: &str) -> Figure {
    f.paper = Some(value);
    f.source = Some(source.to_owned());
    f
}

/// Adds a target and whether the value meets it.
pub fn target(mut f: Figure, t: Target) -> Figure {
    f.target = Some(t.text(&f.unit));
    f.met = Some(t.met(f.value));
    f
}

/// Marks a figure whose target is missed for a known reason of the method it measures (see
/// [`Figure::finding`]); a met target stays met.
pub fn finding(mut f: Figure, why: &str) -> Figure {
    if f.met == Some(false) {
        f.finding = Some(why.to_owned());
    }
    f
}

/// `hits` of `n` as a percentage; NaN when `n` is 0 (a grid plot's cell with no samples).
pub fn percent(hits: u32, n: u32) -> f64 {
    if n == 0 {
        f64::NAN
    } else {
        100.0 * f64::from(hits) / f64::from(n)
    }
}
