//! The force DNN as a weights file holds it (feature `std`): plain arrays, no ML framework.

use super::{HIDDEN, N_INPUTS, OUTPUT_SPAN, WIDTHS, decoded, estimate, standardised};
use crate::error::NetError;
use crate::frozen::{Dense, Layer, Logistic, Relu};
use crate::io::TensorFile;
use crate::stored::Stored;
use hand_traits::{ForceEstimate, ForceEstimator};
use std::path::Path;

/// The network of hidden width `H` in plain arrays (what dfdx's trained stack freezes to).
pub(super) type Frozen<const H: usize> = (
    (Dense<N_INPUTS, H>, Logistic),
    (Dense<H, H>, Relu),
    (Dense<H, H>, Logistic),
    (Dense<H, 1>, Logistic),
);

/// The network at one of the [`WIDTHS`].
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Fast {
    W4(Frozen<4>),
    W8(Frozen<8>),
    W16(Frozen<HIDDEN>),
    W32(Frozen<32>),
}

/// Runs `$e` with `$n` bound to the concrete network inside `$fast`.
macro_rules! with_width {
    ($fast:expr, $n:ident => $e:expr) => {
        match $fast {
            Fast::W4($n) => $e,
            Fast::W8($n) => $e,
            Fast::W16($n) => $e,
            Fast::W32($n) => $e,
        }
    };
}

/// The tensor-name prefix of the network's layers.
pub(super) const NET: &str = "net.";

impl Fast {
    fn hidden(&self) -> usize {
        match self {
            Fast::W4(_) => 4,
            Fast::W8(_) => 8,
            Fast::W16(_) => HIDDEN,
            Fast::W32(_) => 32,
        }
    }

    /// The network a file stores, at the width its first layer's shape names.
    fn read(file: &TensorFile) -> Result<Fast, NetError> {
        let first = format!("{NET}0.0.weight");
        let shape = &file
            .tensor(&first)
            .ok_or_else(|| NetError::MissingTensor(first.clone()))?
            .shape;
        let width = match shape[..] {
            [h, N_INPUTS] if WIDTHS.contains(&h) => h,
            _ => {
                return Err(NetError::TensorMismatch {
                    name: first,
                    stored: format!("{shape:?}"),
                    expected: format!("[H, {N_INPUTS}] with H one of {WIDTHS:?}"),
                });
            }
        };
        Ok(match width {
            4 => Fast::W4(Stored::read(file, NET)?),
            8 => Fast::W8(Stored::read(file, NET)?),
            32 => Fast::W32(Stored::read(file, NET)?),
            _ => Fast::W16(Stored::read(file, NET)?),
        })
    }
}

/// A force / weight DNN from a weights file (or trained, with the `train` feature): three
/// tared pressure rises in, the weight in gram-force out.
///
/// ```
/// use hand_traits::ForceEstimator;
/// use tactile_nets::force_dnn::ForceDnn;
/// use tactile_nets::pretrained::{self, ForceModel};
///
/// // A weights file as `ForceDnn::save` (or `cargo xtask train force-dnn`) writes it.
/// let path = std::env::temp_dir().join("force-dnn-doc.safetensors");
/// pretrained::force_dnn(ForceModel::Table1)?.save(&path)?;
/// let mut dnn = ForceDnn::load(&path)?;
/// let f = dnn.estimate_force(&[2.0, 3.0, 2.5])?;
/// assert!(f.in_range);
/// assert!(ForceDnn::load(std::path::Path::new("no-such.safetensors")).is_err());
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), tactile_nets::NetError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ForceDnn {
    pub(super) fast: Fast,
    pub(super) mean: [f32; N_INPUTS],
    pub(super) scale: [f32; N_INPUTS],
    pub(super) range_gf: [f32; 2],
}

impl ForceDnn {
    /// Units in each hidden layer.
    pub fn hidden(&self) -> usize {
        self.fast.hidden()
    }

    /// The rated range (lightest, heaviest weight), gf.
    pub fn range_gf(&self) -> [f32; 2] {
        self.range_gf
    }

    /// The weight, gf, for the three tared rises `rise_hpa` (hPa).
    ///
    /// Errors: [`NetError::Shape`] unless `rise_hpa` has 3 values, [`NetError::NonFinite`] for
    /// a NaN or infinite value, [`NetError::NonFiniteOutput`] when a finite input overflows.
    pub fn estimate_gf(&self, rise_hpa: &[f32]) -> Result<f32, NetError> {
        let z = standardised(rise_hpa, &self.mean, &self.scale)?;
        Ok(decoded(
            with_width!(&self.fast, n => n.forward(z)[0]),
            self.range_gf,
        )?)
    }

    /// Weights, input standardisation and output range as a [`TensorFile`].
    pub fn to_file(&self) -> Result<TensorFile, NetError> {
        let mut f = TensorFile::new();
        with_width!(&self.fast, n => n.write(&mut f, NET)?);
        let h = self.hidden();
        f.insert("input.mean", &[N_INPUTS], &self.mean)?;
        f.insert("input.scale", &[N_INPUTS], &self.scale)?;
        f.insert("output.range_gf", &[2], &self.range_gf)?;
        let meta = serde_json::json!({
            "model": "force_dnn",
            "inputs": ["rise1_hpa", "rise2_hpa", "rise3_hpa"],
            "layers": [
                format!("linear 3->{h}, sigmoid"),
                format!("linear {h}->{h}, relu"),
                format!("linear {h}->{h}, sigmoid"),
                format!("linear {h}->1, sigmoid"),
            ],
            "output_span": OUTPUT_SPAN,
        });
        f.set_metadata(meta.to_string());
        Ok(f)
    }

    /// A model from [`ForceDnn::to_file`]'s output.
    ///
    /// Errors: [`NetError::SafeTensors`] when the metadata names no force DNN, a
    /// non-positive input spread or an empty rated range; [`NetError::MissingTensor`] /
    /// [`NetError::TensorMismatch`] for a missing or misshapen tensor.
    pub fn from_file(file: &TensorFile) -> Result<ForceDnn, NetError> {
        let meta = file.metadata_json()?;
        if meta.get("model").and_then(|m| m.as_str()) != Some("force_dnn") {
            return Err(NetError::SafeTensors("metadata names no force DNN".into()));
        }
        let vec3 = |name: &str| -> Result<[f32; N_INPUTS], NetError> {
            let v = file.get(name, &[N_INPUTS])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        let scale = vec3("input.scale")?;
        if scale.iter().any(|s| *s <= 0.0) {
            return Err(NetError::SafeTensors(format!(
                "input spreads {scale:?} are not all positive"
            )));
        }
        let range = file.get("output.range_gf", &[2])?;
        if range[1] <= range[0] {
            return Err(NetError::SafeTensors(format!(
                "rated range {}..{} gf is empty",
                range[0], range[1]
            )));
        }
        Ok(ForceDnn {
            fast: Fast::read(file)?,
            mean: vec3("input.mean")?,
            scale,
            range_gf: [range[0], range[1]],
        })
    }

    /// Writes the model as a `.safetensors` file.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        self.to_file()?.save(path)
    }

    /// Reads a model written by [`ForceDnn::save`]; an error names the file.
    pub fn load(path: &Path) -> Result<ForceDnn, NetError> {
        TensorFile::load_with(path, Self::from_file)
    }

    /// A model from the bytes of a weights file (one embedded with `include_bytes!`, or
    /// received); errors name it as `name`.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<ForceDnn, NetError> {
        TensorFile::parse_with(name, bytes, Self::from_file)
    }
}

/// Input: the three tared rises, hPa ([`super::tared_table`]).
impl ForceEstimator for ForceDnn {
    type Input = [f32];
    type Error = NetError;

    /// The estimate, flagged out of range as [`super::StaticForceDnn`]'s is.
    fn estimate_force(&mut self, input: &[f32]) -> Result<ForceEstimate, NetError> {
        Ok(estimate(self.estimate_gf(input)?, self.range_gf()))
    }
}
