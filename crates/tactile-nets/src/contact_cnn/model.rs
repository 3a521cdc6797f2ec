//! The contact CNN as a weights file holds it (feature `std`): plain arrays, no ML framework.

use super::{
    CHANNELS, PAPER, POOLED, Prediction, REGIONS, SMALL, Variant, WIDE, WINDOW, WINDOW_VALUES,
    argmax, standardise,
};
use crate::cnn_frozen::{FrozenCnn, Tensor};
use crate::error::{NetError, check_output};
use crate::io::TensorFile;
use hand_traits::{Contact, ContactLocator};
use std::path::Path;

/// The plain-array network of each [`Variant`].
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Fast {
    Paper(FrozenCnn<{ PAPER.0 }, { PAPER.0 * POOLED }, { PAPER.1 }>),
    Small(FrozenCnn<{ SMALL.0 }, { SMALL.0 * POOLED }, { SMALL.1 }>),
    Wide(FrozenCnn<{ WIDE.0 }, { WIDE.0 * POOLED }, { WIDE.1 }>),
}

impl Fast {
    fn from_file(variant: Variant, file: &TensorFile) -> Result<Fast, NetError> {
        Ok(match variant {
            Variant::Paper => Fast::Paper(FrozenCnn::from_file(file)?),
            Variant::Small => Fast::Small(FrozenCnn::from_file(file)?),
            Variant::Wide => Fast::Wide(FrozenCnn::from_file(file)?),
        })
    }

    fn to_file(&self, file: &mut TensorFile) -> Result<(), NetError> {
        match self {
            Fast::Paper(f) => f.to_file(file),
            Fast::Small(f) => f.to_file(file),
            Fast::Wide(f) => f.to_file(file),
        }
    }

    fn tensors(&self) -> [Tensor; 6] {
        match self {
            Fast::Paper(f) => f.tensors(),
            Fast::Small(f) => f.tensors(),
            Fast::Wide(f) => f.tensors(),
        }
    }

    fn logits(&self, z: &[f32; WINDOW_VALUES]) -> [f32; REGIONS] {
        match self {
            Fast::Paper(f) => f.logits(z),
            Fast::Small(f) => f.logits(z),
            Fast::Wide(f) => f.logits(z),
        }
    }
}

/// A trained contact CNN: its weights in plain arrays, the input standardisation and, when its
/// training windows said so, where a window sits relative to the tap's pressure trigger.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactCnn {
    pub(super) variant: Variant,
    pub(super) mean: [f32; CHANNELS],
    pub(super) scale: [f32; CHANNELS],
    pub(super) frozen: Fast,
    pub(super) trigger_offset: Option<u8>,
}

/// The weights file's metadata key for [`ContactCnn::trigger_offset`].
const TRIGGER_OFFSET_KEY: &str = "window_centre_after_trigger_frames";

impl ContactCnn {
    /// Which network this is.
    pub fn variant(&self) -> Variant {
        self.variant
    }

    /// Frames from a tap's pressure trigger to the centre of the windows the network was
    /// trained on (sample [`WINDOW`]` / 2`): a window cut elsewhere around a tap is not what
    /// the network learned. `None` when the training data did not say.
    ///
    /// The built-in models: 16 (hand-sim's taps are cut around the middle of press, hold and
    /// release; centred on the trigger instead, the paper CNN located 10 of 90 taps).
    pub fn trigger_offset(&self) -> Option<usize> {
        self.trigger_offset.map(usize::from)
    }

    /// The model with its training windows' [`ContactCnn::trigger_offset`] (at most
    /// [`WINDOW`]` / 2`: a window starts at the trigger at the latest).
    ///
    /// Errors: [`NetError::Training`] for a larger offset.
    pub fn with_trigger_offset(mut self, frames: usize) -> Result<ContactCnn, NetError> {
        if frames > WINDOW / 2 {
            return Err(NetError::Training(format!(
                "a window centred {frames} frames after the trigger would start after it (at most {})",
                WINDOW / 2
            )));
        }
        self.trigger_offset = Some(frames as u8);
        Ok(self)
    }

    /// The per-channel input standardisation `(mean, spread)` of the training set.
    pub fn input_scale(&self) -> ([f32; CHANNELS], [f32; CHANNELS]) {
        (self.mean, self.scale)
    }

    /// The network's tensors as its weights file stores them (the conv kernel and bias, the
    /// hidden layer's weight and bias, the output layer's): what its fixed-point form is
    /// quantised from.
    pub(crate) fn tensors(&self) -> [Tensor; 6] {
        self.frozen.tensors()
    }

    /// Standardised window and whether it lies within [`Z_RANGE`](super::Z_RANGE); errors as
    /// [`ContactCnn::logits`].
    fn standardise(&self, window: &[f32]) -> Result<([f32; WINDOW_VALUES], bool), NetError> {
        Ok(standardise(window, &self.mean, &self.scale)?)
    }

    /// The 9 logits for a raw window (152 values, channel-major: acc x, acc y in mm/s², gyro
    /// x, gyro y in mrad/s), through the plain-array path (no allocation).
    ///
    /// Errors: [`NetError::Shape`] unless `window` has 152 values, [`NetError::NonFinite`] for
    /// a NaN or infinite value, [`NetError::NonFiniteOutput`] when a finite input far outside
    /// the training range overflows the network.
    pub fn logits(&self, window: &[f32]) -> Result<[f32; REGIONS], NetError> {
        let (z, _) = self.standardise(window)?;
        let out = self.frozen.logits(&z);
        check_output(&out)?;
        Ok(out)
    }

    /// Region of highest probability for each of many raw windows (the evaluation path).
    pub fn classify_batch(&self, windows: &[[f32; WINDOW_VALUES]]) -> Result<Vec<u8>, NetError> {
        windows
            .iter()
            .map(|w| self.logits(w).map(|l| argmax(&l)))
            .collect()
    }

    /// Locates a contact from a raw window (see [`ContactCnn::logits`] for the errors),
    /// flagged out of range beyond [`Z_RANGE`](super::Z_RANGE).
    pub fn predict(&self, window: &[f32]) -> Result<Prediction, NetError> {
        let (z, in_range) = self.standardise(window)?;
        let logits = self.frozen.logits(&z);
        Ok(Prediction::of(&logits, in_range)?)
    }

    /// Weights and input scaling as a [`TensorFile`].
    pub fn to_file(&self) -> Result<TensorFile, NetError> {
        let mut f = TensorFile::new();
        self.frozen.to_file(&mut f)?;
        f.insert("input.mean", &[CHANNELS], &self.mean)?;
        f.insert("input.scale", &[CHANNELS], &self.scale)?;
        let (filters, dense) = self.variant.sizes();
        let mut meta = serde_json::json!({
            "model": "contact_cnn",
            "variant": self.variant.name(),
            "input": "4 x 38 window, channel-major: acc x, acc y (mm/s^2), gyro x, gyro y (mrad/s)",
            "filters": filters,
            "dense": dense,
            "regions": REGIONS,
        });
        if let (Some(frames), Some(m)) = (self.trigger_offset, meta.as_object_mut()) {
            m.insert(TRIGGER_OFFSET_KEY.to_owned(), frames.into());
        }
        f.set_metadata(meta.to_string());
        Ok(f)
    }

    /// A model from [`ContactCnn::to_file`]'s output.
    ///
    /// Errors: [`NetError::SafeTensors`] when the metadata names no variant or a trigger
    /// offset that is not a frame count, [`NetError::Training`] for an offset past
    /// [`WINDOW`]` / 2`, a tensor error
    /// for a missing or misshapen tensor, [`NetError::TensorMismatch`] for a spread that is
    /// not finite and positive.
    pub fn from_file(file: &TensorFile) -> Result<ContactCnn, NetError> {
        let meta: serde_json::Value = serde_json::from_str(file.metadata())
            .map_err(|e| NetError::SafeTensors(format!("metadata: {e}")))?;
        let variant = meta
            .get("variant")
            .and_then(|v| v.as_str())
            .and_then(Variant::from_name)
            .ok_or_else(|| NetError::SafeTensors("metadata names no contact-CNN variant".into()))?;
        let vec4 = |name: &str| -> Result<[f32; CHANNELS], NetError> {
            let v = file.get(name, &[CHANNELS])?;
            Ok(core::array::from_fn(|j| v[j]))
        };
        let (mean, scale) = (vec4("input.mean")?, vec4("input.scale")?);
        if let Some(i) = scale.iter().position(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(NetError::TensorMismatch {
                name: "input.scale".into(),
                stored: format!("{}", scale[i]),
                expected: "finite positive spreads".into(),
            });
        }
        let model = ContactCnn {
            variant,
            mean,
            scale,
            frozen: Fast::from_file(variant, file)?,
            trigger_offset: None,
        };
        match meta.get(TRIGGER_OFFSET_KEY) {
            None => Ok(model),
            Some(v) => match v.as_u64().and_then(|f| usize::try_from(f).ok()) {
                Some(frames) => model.with_trigger_offset(frames),
                None => Err(NetError::SafeTensors(format!(
                    "metadata `{TRIGGER_OFFSET_KEY}` is {v}, not a frame count"
                ))),
            },
        }
    }

    /// Writes the model as a `.safetensors` file.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        self.to_file()?.save(path)
    }

    /// Reads a model written by [`ContactCnn::save`]; an error names the file.
    pub fn load(path: &Path) -> Result<ContactCnn, NetError> {
        TensorFile::load_with(path, Self::from_file)
    }

    /// A model from the bytes of a weights file (one embedded with `include_bytes!`, or
    /// received); errors name it as `name`.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<ContactCnn, NetError> {
        TensorFile::parse_with(name, bytes, Self::from_file)
    }
}

/// Input: one raw 4 × 38 window (152 values, see [`ContactCnn::logits`]); regions: the 9 of
/// §IV-A, `3 · row group + column`.
impl ContactLocator for ContactCnn {
    type Input = [f32];
    type Error = NetError;

    fn locate(&mut self, input: &[f32]) -> Result<Contact, NetError> {
        Ok(self.predict(input)?.into())
    }
}
