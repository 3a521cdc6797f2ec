//! The contact CNN's inference on plain arrays: the same arithmetic as the dfdx graph
//! (valid 3 × 3 conv, ReLU, 2 × 2 max-pool, dense + ReLU, dense), without dfdx's per-call
//! tensor allocations — the single-sample path the 50 µs budget is measured on.
//!
//! Weights are read from a [`TensorFile`] with the dfdx module's names, so the two paths
//! share one stored form; the tests check them against each other to 1e-5.

use crate::cnn_layers::{CONV_ROWS, KERNEL, PATCH, POOLED};
use crate::data::imu_pad::{REGIONS, WINDOW, WINDOW_VALUES};
use crate::error::NetError;
use crate::io::TensorFile;

/// Largest filter count a frozen net holds (stack buffers are sized by it).
pub const MAX_FILTERS: usize = 32;
/// Largest dense width a frozen net holds.
pub const MAX_DENSE: usize = 320;

/// A dense layer `y = W x + b`, `W` row-major `(outputs, inputs)` as dfdx's `Linear` stores it.
#[derive(Debug, Clone, PartialEq)]
struct Dense {
    inputs: usize,
    weight: Vec<f32>,
    bias: Vec<f32>,
}

impl Dense {
    fn load(file: &TensorFile, name: &str, outputs: usize, inputs: usize) -> Result<Dense, NetError> {
        Ok(Dense {
            inputs,
            weight: file.get(&format!("{name}.weight"), &[outputs, inputs])?.to_vec(),
            bias: file.get(&format!("{name}.bias"), &[outputs])?.to_vec(),
        })
    }

    /// `out[i] = b[i] + W[i] · x`, then ReLU when `relu`.
    fn apply(&self, x: &[f32], out: &mut [f32], relu: bool) {
        for ((o, row), b) in out
            .iter_mut()
            .zip(self.weight.chunks_exact(self.inputs))
            .zip(&self.bias)
        {
            let s = b + row.iter().zip(x).map(|(w, v)| w * v).sum::<f32>();
            *o = if relu { s.max(0.0) } else { s };
        }
    }
}

/// A contact CNN's weights as plain arrays.
#[derive(Debug, Clone, PartialEq)]
pub struct FrozenCnn {
    filters: usize,
    conv: Dense,
    hidden: Dense,
    output: Dense,
}

impl FrozenCnn {
    /// Reads the weights stored under `prefix` by [`TensorFile::add_module`] for a net of
    /// `(filters, dense)` sizes.
    pub fn from_file(
        file: &TensorFile,
        prefix: &str,
        (filters, dense): (usize, usize),
    ) -> Result<FrozenCnn, NetError> {
        if filters > MAX_FILTERS || dense > MAX_DENSE {
            return Err(NetError::TensorMismatch {
                name: format!("{prefix}*"),
                stored: format!("{filters} filters, dense {dense}"),
                expected: format!("at most {MAX_FILTERS} filters, dense {MAX_DENSE}"),
            });
        }
        Ok(FrozenCnn {
            filters,
            conv: Dense::load(file, &format!("{prefix}0.1"), filters, PATCH)?,
            hidden: Dense::load(file, &format!("{prefix}1.0"), dense, POOLED * filters)?,
            output: Dense::load(file, &format!("{prefix}1.2"), REGIONS, dense)?,
        })
    }

    /// Logits of a standardised window (channel-major 4 × 38).
    pub fn logits(&self, z: &[f32; WINDOW_VALUES]) -> [f32; REGIONS] {
        let f = self.filters;
        // Pooled map, `[column][filter]` as dfdx flattens it. ReLU commutes with max, so the
        // pool takes the max of the raw conv values and ReLU follows.
        let mut pooled = [f32::NEG_INFINITY; POOLED * MAX_FILTERS];
        let mut patch = [0.0f32; PATCH];
        let mut conv = [0.0f32; MAX_FILTERS];
        for r in 0..CONV_ROWS {
            for c in 0..2 * POOLED {
                for (k, p) in patch.iter_mut().enumerate() {
                    *p = z[(r + k / KERNEL) * WINDOW + c + k % KERNEL];
                }
                self.conv.apply(&patch, &mut conv[..f], false);
                let cell = &mut pooled[(c / 2) * f..(c / 2 + 1) * f];
                for (m, &v) in cell.iter_mut().zip(&conv[..f]) {
                    *m = m.max(v);
                }
            }
        }
        for v in &mut pooled[..POOLED * f] {
            *v = v.max(0.0);
        }
        let mut hidden = [0.0f32; MAX_DENSE];
        let h = self.output.inputs;
        self.hidden.apply(&pooled[..POOLED * f], &mut hidden[..h], true);
        let mut out = [0.0f32; REGIONS];
        self.output.apply(&hidden[..h], &mut out, false);
        out
    }
}
