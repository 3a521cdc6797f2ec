//! Training the contact CNN (feature `train`): the dfdx graph of [`crate::cnn_layers`], fitted
//! with the crate's Adam loop and frozen into a [`ContactCnn`]; and [`DfdxCnn`], dfdx's forward
//! of a model, the reference the plain-array path is checked against.

use super::model::Fast;
use super::{
    CHANNELS, ContactCnn, PATCH, POOLED, REGIONS, Variant, WINDOW, WINDOW_VALUES, standardise,
};
use crate::cnn_frozen::FrozenCnn;
use crate::cnn_layers::{Im2Col, PoolFlatten};
use crate::error::{NetError, check_output};
use crate::frozen::Freeze;
use crate::io::TensorFile;
use crate::train::{Loss, Samples, TrainConfig, TrainLog, fit};
use dfdx::prelude::*;

type Arch<const F: usize, const FLAT: usize, const H: usize> = (
    (Im2Col, Linear<PATCH, F>, ReLU, PoolFlatten<F, FLAT>),
    (Linear<FLAT, H>, ReLU, Linear<H, REGIONS>),
);
type Net<const F: usize, const FLAT: usize, const H: usize> =
    <Arch<F, FLAT, H> as BuildOnDevice<Cpu, f32>>::Built;

enum Body {
    Paper(Net<8, { 8 * POOLED }, 320>),
    Small(Net<4, { 4 * POOLED }, 32>),
    Wide(Net<16, { 16 * POOLED }, 64>),
}

/// Runs `$e` with `$n` bound to the concrete network inside a [`Body`].
macro_rules! with_net {
    ($body:expr, $n:ident => $e:expr) => {
        match $body {
            Body::Paper($n) => $e,
            Body::Small($n) => $e,
            Body::Wide($n) => $e,
        }
    };
}

fn build(variant: Variant, dev: &Cpu) -> Body {
    match variant {
        Variant::Paper => Body::Paper(dev.build_module::<Arch<8, { 8 * POOLED }, 320>, f32>()),
        Variant::Small => Body::Small(dev.build_module::<Arch<4, { 4 * POOLED }, 32>, f32>()),
        Variant::Wide => Body::Wide(dev.build_module::<Arch<16, { 16 * POOLED }, 64>, f32>()),
    }
}

/// The plain-array copy of a trained network.
fn frozen<const F: usize, const FLAT: usize, const H: usize>(
    net: &Net<F, FLAT, H>,
) -> Result<FrozenCnn<F, FLAT, H>, NetError> {
    let conv = &net.0.1;
    let (hidden, _, out) = net.1.freeze()?;
    FrozenCnn::from_rows(&conv.weight.as_vec(), &conv.bias.as_vec(), &hidden, &out)
}

impl Body {
    fn freeze(&self) -> Result<Fast, NetError> {
        Ok(match self {
            Body::Paper(n) => Fast::Paper(frozen(n)?),
            Body::Small(n) => Fast::Small(frozen(n)?),
            Body::Wide(n) => Fast::Wide(frozen(n)?),
        })
    }
}

/// Per-channel mean and spread of `windows` (spread 1 for a constant channel).
fn channel_stats(windows: &[[f32; WINDOW_VALUES]]) -> ([f32; CHANNELS], [f32; CHANNELS]) {
    let mut mean = [0.0f32; CHANNELS];
    let mut scale = [1.0f32; CHANNELS];
    let n = (windows.len() * WINDOW).max(1) as f64;
    for c in 0..CHANNELS {
        let vals = || {
            windows
                .iter()
                .flat_map(|w| &w[c * WINDOW..(c + 1) * WINDOW])
        };
        let m = vals().map(|&v| f64::from(v)).sum::<f64>() / n;
        let var = vals().map(|&v| (f64::from(v) - m).powi(2)).sum::<f64>() / n;
        mean[c] = m as f32;
        if var.sqrt() > 1e-6 {
            scale[c] = var.sqrt() as f32;
        }
    }
    (mean, scale)
}

impl ContactCnn {
    /// Trains `variant` on `windows` (raw, channel-major) labelled with `regions` (0…8),
    /// using `config` (its seed also seeds the initial weights).
    pub fn train(
        windows: &[[f32; WINDOW_VALUES]],
        regions: &[u8],
        variant: Variant,
        config: &TrainConfig,
    ) -> Result<(ContactCnn, TrainLog), NetError> {
        if windows.is_empty() || windows.len() != regions.len() {
            return Err(NetError::Training(format!(
                "{} windows and {} labels",
                windows.len(),
                regions.len()
            )));
        }
        if let Some(&r) = regions.iter().find(|&&r| usize::from(r) >= REGIONS) {
            return Err(NetError::Training(format!("region {r} is not 0…8")));
        }
        let (mean, scale) = channel_stats(windows);
        let mut samples = Samples {
            inputs: Vec::with_capacity(windows.len() * WINDOW_VALUES),
            targets: Vec::with_capacity(windows.len() * REGIONS),
        };
        for (w, &r) in windows.iter().zip(regions) {
            samples
                .inputs
                .extend((0..WINDOW_VALUES).map(|i| (w[i] - mean[i / WINDOW]) / scale[i / WINDOW]));
            samples
                .targets
                .extend((0..REGIONS).map(|k| f32::from(u8::from(k == usize::from(r)))));
        }
        let dev = Cpu::seed_from_u64(config.seed);
        let mut body = build(variant, &dev);
        let loss = Loss::SoftmaxCrossEntropy;
        let log = with_net!(&mut body, net => {
            fit::<_, WINDOW_VALUES, REGIONS>(&dev, net, &samples, loss, config)?
        });
        let model = ContactCnn {
            variant,
            mean,
            scale,
            frozen: body.freeze()?,
            trigger_offset: None,
        };
        Ok((model, log))
    }
}

/// `copies` copies of `window` (raw, channel-major) with white noise added at `snr_db`: each
/// channel's noise has the power of that channel's signal over the window divided by
/// `10^(snr_db / 10)` — the paper's augmentation (Al & Martinez-Hernandez, §IV-A: "noise with
/// different signal-to-noise ratio"), drawn from `rng`.
///
/// ```
/// use rand::SeedableRng;
/// use tactile_nets::contact_cnn::{WINDOW_VALUES, noisy_copies};
/// let w = [100.0f32; WINDOW_VALUES];
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
/// let copies = noisy_copies(&w, 3, 30.0, &mut rng);
/// assert_eq!(copies.len(), 3);
/// // At 30 dB the noise is ~1/31.6 of the signal's amplitude.
/// let rms = (copies[0].iter().map(|v| (v - 100.0).powi(2)).sum::<f32>() / WINDOW_VALUES as f32).sqrt();
/// assert!((1.5..5.0).contains(&rms), "{rms}");
/// ```
pub fn noisy_copies<R: rand::Rng>(
    window: &[f32; WINDOW_VALUES],
    copies: usize,
    snr_db: f32,
    rng: &mut R,
) -> Vec<[f32; WINDOW_VALUES]> {
    let ratio = 10f32.powf(snr_db / 10.0);
    let sigma: [f32; CHANNELS] = core::array::from_fn(|c| {
        let s = &window[c * WINDOW..(c + 1) * WINDOW];
        (s.iter().map(|v| v * v).sum::<f32>() / WINDOW as f32 / ratio).sqrt()
    });
    (0..copies)
        .map(|_| {
            core::array::from_fn(|i| {
                let n: f32 = rng.sample(rand_distr::StandardNormal);
                window[i] + sigma[i / WINDOW] * n
            })
        })
        .collect()
}

/// A contact CNN as a dfdx graph: the forward pass it was trained with, kept as the reference
/// the plain-array path of [`ContactCnn`] is tested and benchmarked against.
pub struct DfdxCnn {
    body: Body,
    mean: [f32; CHANNELS],
    scale: [f32; CHANNELS],
    dev: Cpu,
}

impl DfdxCnn {
    /// The dfdx graph of `model`, loaded from its weights file form.
    pub fn of(model: &ContactCnn) -> Result<DfdxCnn, NetError> {
        let file: TensorFile = model.to_file()?;
        let dev = Cpu::seed_from_u64(0);
        let mut body = build(model.variant(), &dev);
        with_net!(&mut body, net => file.load_module("net.", net)?);
        let (mean, scale) = model.input_scale();
        Ok(DfdxCnn {
            body,
            mean,
            scale,
            dev,
        })
    }

    /// The 9 logits of a raw window through dfdx's forward (errors as
    /// [`ContactCnn::logits`]).
    pub fn logits(&self, window: &[f32]) -> Result<[f32; REGIONS], NetError> {
        let (z, _) = standardise(window, &self.mean, &self.scale)?;
        let x = self
            .dev
            .try_tensor_from_vec(z.to_vec(), (1, Const::<WINDOW_VALUES>))?;
        let out = with_net!(&self.body, net => net.try_forward(x)?.as_vec());
        check_output(&out)?;
        let mut l = [0.0f32; REGIONS];
        l.copy_from_slice(&out);
        Ok(l)
    }
}
