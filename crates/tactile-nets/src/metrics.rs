//! The metrics file every trained model commits beside its weights, and its drift check.
//!
//! Format (JSON, keys in a fixed order, one file per model family):
//!
//! ```json
//! {
//!   "model": "contact_mlp",
//!   "description": "…",
//!   "split": "train: repeat 0; test: repeat 1",
//!   "seed": 7,
//!   "rows": [ { "label": "osr4096/cell_set", "values": { "area_accuracy": 0.97, … } } ]
//! }
//! ```
//!
//! A row is one trained model (or one configuration) evaluated on the held-out set; `values`
//! maps a metric name to its value. Counts are stored as numbers too, so a drift check compares
//! everything the same way.

use crate::error::NetError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The committed metrics of one model family.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MetricsFile {
    /// Model family name (`contact_mlp`).
    pub model: String,
    /// What the rows measure, in a sentence or two.
    pub description: String,
    /// How the data were split into training and held-out sets.
    pub split: String,
    /// The training seed.
    pub seed: u64,
    /// One row per trained model / configuration.
    pub rows: Vec<MetricsRow>,
}

/// One model's held-out metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MetricsRow {
    /// Which model (`osr4096/cell_set`).
    pub label: String,
    /// Metric name → value.
    pub values: BTreeMap<String, f64>,
}

impl MetricsFile {
    /// Pretty JSON with a trailing newline.
    pub fn to_json(&self) -> Result<String, NetError> {
        serde_json::to_string_pretty(self)
            .map(|s| s + "\n")
            .map_err(|e| NetError::Metrics(e.to_string()))
    }

    /// Parses [`MetricsFile::to_json`]'s output.
    pub fn from_json(text: &str) -> Result<Self, NetError> {
        serde_json::from_str(text).map_err(|e| NetError::Metrics(e.to_string()))
    }

    /// The row labelled `label`.
    pub fn row(&self, label: &str) -> Option<&MetricsRow> {
        self.rows.iter().find(|r| r.label == label)
    }

    /// Every way `fresh` differs from `self` (the committed file): rows or metrics missing on
    /// either side, or values further apart than `tolerance`. Empty when they agree.
    pub fn drift(&self, fresh: &MetricsFile, tolerance: f64) -> Vec<String> {
        let mut out = Vec::new();
        for row in &self.rows {
            let Some(other) = fresh.row(&row.label) else {
                out.push(format!("{}: not re-evaluated", row.label));
                continue;
            };
            for (key, &committed) in &row.values {
                match other.values.get(key) {
                    None => out.push(format!("{}/{key}: missing", row.label)),
                    Some(&v) if (v - committed).abs() > tolerance || v.is_nan() => out.push(
                        format!("{}/{key}: committed {committed}, now {v}", row.label),
                    ),
                    Some(_) => {}
                }
            }
            for key in other.values.keys().filter(|k| !row.values.contains_key(*k)) {
                out.push(format!("{}/{key}: not committed", row.label));
            }
        }
        for row in fresh.rows.iter().filter(|r| self.row(&r.label).is_none()) {
            out.push(format!("{}: not committed", row.label));
        }
        out
    }
}
