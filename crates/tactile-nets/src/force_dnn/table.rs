//! Table 1's form of weight data: rows of a weight and three pressures, tared to rises.

use super::WeightSample;
use crate::error::NetError;

/// Tares `(weight_gf, pressures_hpa)` rows against the row whose weight is 0 (Table 1's form).
///
/// Errors: [`NetError::Data`] when no row has weight 0 or a value is not finite.
pub fn tared_table(rows: &[(f64, [f64; 3])]) -> Result<Vec<WeightSample>, NetError> {
    let (_, tare) = rows
        .iter()
        .find(|(w, _)| *w == 0.0)
        .ok_or_else(|| NetError::Data {
            line: 0,
            reason: "no 0 gf row to tare against".into(),
        })?;
    rows.iter()
        .enumerate()
        .map(|(i, (w, p))| {
            let s = WeightSample {
                rise_hpa: core::array::from_fn(|k| (p[k] - tare[k]) as f32),
                weight_gf: *w as f32,
            };
            finite(&s, i + 1)
        })
        .collect()
}

fn finite(s: &WeightSample, line: usize) -> Result<WeightSample, NetError> {
    if s.rise_hpa
        .iter()
        .chain([&s.weight_gf])
        .all(|v| v.is_finite())
    {
        Ok(*s)
    } else {
        Err(NetError::Data {
            line,
            reason: "non-finite value".into(),
        })
    }
}
