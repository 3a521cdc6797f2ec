//! The fast inference form of a trained dfdx dense stack: plain fixed-size `f32` arrays, no
//! tensors, no device, no allocation per call — and, without the `std` feature, the whole of
//! inference on a microcontroller: [`StaticDense`] reads its weights from `'static` arrays
//! (flash), so a frozen stack of them needs neither a heap nor RAM for its weights.
//!
//! dfdx pays ~10 µs of bookkeeping per forward call (tensor allocation, shape checks, device
//! dispatch) whatever the model's size; a 3 → 16 → 16 → 1 network needs well under a
//! microsecond of arithmetic. [`Freeze::freeze`] copies the parameters of any trained stack of
//! [`Linear`](dfdx::nn::modules::Linear) layers and activations ([`ReLU`], [`Sigmoid`], [`Tanh`]; [`Dropout`] becomes the
//! identity, as at inference) into the matching frozen layers, nested tuples as in dfdx. The
//! frozen stack implements [`Layer`] on `[f32; I]` → `[f32; O]`: the widths are checked by the
//! compiler, and a call only touches the stack and the weights.
//!
//! ```
//! # #[cfg(feature = "train")] {
//! use dfdx::prelude::*;
//! use tactile_nets::frozen::{Freeze, Layer};
//!
//! let dev = Cpu::seed_from_u64(0);
//! let net = dev.build_module::<((Linear<3, 8>, Sigmoid), (Linear<8, 4>, ReLU), Linear<4, 2>), f32>();
//! let fast = net.freeze()?;
//! let x = [0.5f32, -1.0, 2.0];
//! let (slow, quick) = (net.forward(dev.tensor(x)).array(), fast.forward(x));
//! assert!(slow.iter().zip(quick).all(|(a, b)| (a - b).abs() < 1e-6));
//! # }
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```

use crate::activations::sigmoid;
#[cfg(feature = "std")]
use crate::error::NetError;
use crate::error::{RunError, check_input};
#[cfg(feature = "train")]
use dfdx::prelude::{Cpu, Dropout, ReLU, Sigmoid, Tanh};

/// One inference step on a value of type `X` (an `[f32; N]` array for every layer here).
pub trait Layer<X> {
    /// What the layer returns.
    type Output;
    /// Runs the layer.
    fn forward(&self, x: X) -> Self::Output;
}

/// A trained dfdx module that has a frozen inference form.
#[cfg(feature = "train")]
pub trait Freeze {
    /// The frozen form.
    type Frozen;
    /// Copies the module's parameters into its frozen form.
    ///
    /// Errors: [`NetError::TensorMismatch`] if a parameter tensor does not hold its shape's
    /// values (cannot happen for a module dfdx built).
    fn freeze(&self) -> Result<Self::Frozen, NetError>;
}

/// A dense layer `y = W x + b`, `W` row-major `O × I` as dfdx stores it.
///
/// The weights are boxed (a 576 → 320 layer is 720 KiB, too big for a thread's stack); the
/// box is made once, at freezing.
#[cfg(feature = "std")]
#[derive(Debug, Clone, PartialEq)]
pub struct Dense<const I: usize, const O: usize> {
    weight: Box<[[f32; I]; O]>,
    bias: Box<[f32; O]>,
}

#[cfg(feature = "std")]
impl<const I: usize, const O: usize> Dense<I, O> {
    /// A layer from row-major `weight` (`O × I` values) and `bias` (`O` values).
    ///
    /// Errors: [`NetError::TensorMismatch`] when a length is wrong.
    pub fn new(weight: &[f32], bias: &[f32]) -> Result<Self, NetError> {
        let mismatch = |name: &str, got: usize, want: &str| NetError::TensorMismatch {
            name: name.to_owned(),
            stored: format!("{got} values"),
            expected: want.to_owned(),
        };
        if weight.len() != I * O {
            return Err(mismatch("weight", weight.len(), &format!("[{O}, {I}]")));
        }
        let rows: Vec<[f32; I]> = weight
            .chunks_exact(I.max(1))
            .take(O)
            .map(|r| core::array::from_fn(|i| r[i]))
            .collect();
        let weight: Box<[[f32; I]; O]> = rows
            .into_boxed_slice()
            .try_into()
            .map_err(|_| mismatch("weight", weight.len(), &format!("[{O}, {I}]")))?;
        let bias: Box<[f32; O]> = bias
            .to_vec()
            .into_boxed_slice()
            .try_into()
            .map_err(|b: Box<[f32]>| mismatch("bias", b.len(), &format!("[{O}]")))?;
        Ok(Self { weight, bias })
    }

    /// The weights in row-major `O × I` order (as a weights file stores them).
    pub fn weight_rows(&self) -> &[f32] {
        self.weight.as_flattened()
    }

    /// The bias.
    pub fn bias(&self) -> &[f32; O] {
        &self.bias
    }
}

#[cfg(feature = "std")]
impl<const I: usize, const O: usize> Layer<[f32; I]> for Dense<I, O> {
    type Output = [f32; O];

    #[inline]
    fn forward(&self, x: [f32; I]) -> [f32; O] {
        dense(&self.weight, &self.bias, &x)
    }
}

/// A dense layer `y = W x + b` for inputs that are mostly zero (those after a ReLU), stored
/// input-major: the forward pass adds `x_j · W[:, j]` for the non-zero `x_j` only, so it
/// reads and multiplies only the weights that matter.
///
/// Same arithmetic as [`Dense`] up to the order of the additions (results agree to f32
/// rounding); how much it saves is the share of zero inputs. The outputs are accumulated in
/// blocks of [`BLOCK`] (one block of `O` when `O < BLOCK`), each block's weights contiguous and
/// input-major, so a block's partial sums stay in registers while its weights stream through
/// in order.
#[cfg(feature = "std")]
#[derive(Debug, Clone, PartialEq)]
pub struct SparseDense<const I: usize, const O: usize> {
    // `weights[(b · I + j) · W + k]` = W[b · W + k][j] with `W = Self::WIDTH`; the last block
    // is zero-padded.
    weights: Box<[f32]>,
    bias: Box<[f32; O]>,
}

/// Outputs accumulated together in [`SparseDense`]: 32 `f32` are 8 SSE (or 4 AVX) registers.
pub const BLOCK: usize = 32;

#[cfg(feature = "std")]
impl<const I: usize, const O: usize> SparseDense<I, O> {
    /// The stored width of a block: a narrow layer (`O < BLOCK`, e.g. a 9-class head) is one
    /// block of `O`, so the forward pass reads no padding (padded to a block, the paper CNN's
    /// 320 → 9 layer would stream 40 KB of which 29 KB are zeros).
    const WIDTH: usize = if O < BLOCK { O } else { BLOCK };

    /// The input-major copy of `dense`.
    pub fn from_dense(dense: &Dense<I, O>) -> Self {
        const {
            assert!(
                I <= u16::MAX as usize,
                "SparseDense indexes its inputs with u16"
            )
        };
        let width = Self::WIDTH;
        let mut weights = vec![0.0f32; O.div_ceil(width) * I * width].into_boxed_slice();
        for (o, row) in dense.weight.iter().enumerate() {
            for (j, &w) in row.iter().enumerate() {
                weights[Self::at(o, j)] = w;
            }
        }
        SparseDense {
            weights,
            bias: dense.bias.clone(),
        }
    }

    /// The weights back in row-major `O × I` order (as a weights file stores them).
    pub fn weight_rows(&self) -> Vec<f32> {
        (0..O * I)
            .map(|k| self.weights[Self::at(k / I, k % I)])
            .collect()
    }

    /// Where `W[o][j]` is stored (see the field's comment).
    fn at(o: usize, j: usize) -> usize {
        let width = Self::WIDTH;
        ((o / width) * I + j) * width + o % width
    }

    /// The bias.
    pub fn bias(&self) -> &[f32; O] {
        &self.bias
    }
}

#[cfg(feature = "std")]
impl<const I: usize, const O: usize> SparseDense<I, O> {
    /// `forward(Relu.forward(x))` in one pass: the ReLU's zeros are the inputs the layer
    /// skips, so the activation costs no pass and no copy of its own (same bits: a NaN, which
    /// the ReLU makes 0, is skipped as well).
    pub fn forward_relu(&self, x: &[f32; I]) -> [f32; O] {
        self.accumulate_kept(x, |v| v > 0.0)
    }

    /// `b + Σ x_j · W[:, j]` over the inputs `keep` keeps; the others count as zero.
    #[inline(always)]
    fn accumulate_kept(&self, x: &[f32; I], keep: impl Fn(f32) -> bool) -> [f32; O] {
        // The kept inputs, compacted without a branch (a slot is written, then overwritten).
        let mut index = [0u16; I];
        let mut value = [0.0f32; I];
        let mut n = 0;
        for (j, &v) in x.iter().enumerate() {
            index[n] = j as u16;
            value[n] = v;
            n += usize::from(keep(v));
        }
        let (index, value) = (&index[..n], &value[..n]);
        let mut y = *self.bias;
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the one requirement of a `target_feature` function is that the CPU has
            // the feature, checked just above. Why: the same lane-wise mul and add on 8 lanes
            // instead of SSE2's 4 (bit-identical results: each output's sum keeps its order),
            // measured 3.61 → 2.70 µs per paper-CNN call on an AMD EPYC.
            #[allow(unsafe_code)]
            unsafe {
                accumulate_avx::<I, O>(&self.weights, index, value, &mut y);
            }
            return y;
        }
        accumulate::<I, O, 1>(&self.weights, index, value, &mut y);
        y
    }
}

#[cfg(feature = "std")]
impl<const I: usize, const O: usize> Layer<[f32; I]> for SparseDense<I, O> {
    type Output = [f32; O];

    fn forward(&self, x: [f32; I]) -> [f32; O] {
        // A NaN is kept, so it reaches every output as in `Dense`.
        self.accumulate_kept(&x, |v| v != 0.0)
    }
}

/// `y += W x` over the non-zero inputs (`index`, `value`) of [`SparseDense`]'s blocks, `P`
/// blocks per pass over the inputs. Each output's sum runs over the inputs in order whatever
/// `P` is, so every `P` gives the same bits; a larger `P` gives the adds of one input more
/// independent chains (one chain per register waits ~3 cycles per add), at the cost of
/// registers: 2 with AVX's 16 × 8 lanes, 1 with SSE2's 16 × 4.
#[cfg(feature = "std")]
#[inline(always)]
fn accumulate<const I: usize, const O: usize, const P: usize>(
    weights: &[f32],
    index: &[u16],
    value: &[f32],
    y: &mut [f32; O],
) {
    // A constant once monomorphised, so the lane loops below have fixed trip counts.
    let width = SparseDense::<I, O>::WIDTH;
    fn lanes(block: &[f32], j: u16, width: usize) -> &[f32] {
        let at = usize::from(j) * width;
        &block[at..at + width]
    }
    for (group, out) in weights.chunks(P * I * width).zip(y.chunks_mut(P * width)) {
        let mut acc = [[0.0f32; BLOCK]; P];
        if group.len() == P * I * width {
            for (&j, &v) in index.iter().zip(value) {
                for (p, acc) in acc.iter_mut().enumerate() {
                    let block = &group[p * I * width..(p + 1) * I * width];
                    for (a, w) in acc.iter_mut().zip(lanes(block, j, width)) {
                        *a += v * w;
                    }
                }
            }
        } else {
            // The last, shorter group: its blocks one at a time.
            for (block, acc) in group.chunks_exact(I * width).zip(acc.iter_mut()) {
                for (&j, &v) in index.iter().zip(value) {
                    for (a, w) in acc.iter_mut().zip(lanes(block, j, width)) {
                        *a += v * w;
                    }
                }
            }
        }
        // Block by block, so the adds vectorise (one flattened iterator over the blocks did not).
        for (out, acc) in out.chunks_mut(width).zip(&acc) {
            for (o, a) in out.iter_mut().zip(acc) {
                *o += a;
            }
        }
    }
}

/// [`accumulate`] compiled for AVX (8-lane `f32`), two blocks per pass, chosen at run time.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx")]
fn accumulate_avx<const I: usize, const O: usize>(
    weights: &[f32],
    index: &[u16],
    value: &[f32],
    y: &mut [f32; O],
) {
    accumulate::<I, O, 2>(weights, index, value, y);
}

/// A dense layer `y = W x + b` over `'static` weights (flash on a microcontroller): the
/// inference form of the models built into the crate ([`crate::pretrained`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticDense<const I: usize, const O: usize> {
    weight: &'static [[f32; I]; O],
    bias: &'static [f32; O],
}

impl<const I: usize, const O: usize> StaticDense<I, O> {
    /// A layer over row-major `weight` (`O` rows of `I`) and `bias`.
    pub const fn new(weight: &'static [[f32; I]; O], bias: &'static [f32; O]) -> Self {
        Self { weight, bias }
    }
}

impl<const I: usize, const O: usize> Layer<[f32; I]> for StaticDense<I, O> {
    type Output = [f32; O];

    #[inline]
    fn forward(&self, x: [f32; I]) -> [f32; O] {
        dense(self.weight, self.bias, &x)
    }
}

/// `W x + b`: the one kernel of both dense forms.
#[inline]
fn dense<const I: usize, const O: usize>(
    weight: &[[f32; I]; O],
    bias: &[f32; O],
    x: &[f32; I],
) -> [f32; O] {
    let mut y = [0.0f32; O];
    for ((y, row), b) in y.iter_mut().zip(weight.iter()).zip(bias.iter()) {
        *y = dot(row, x) + b;
    }
    y
}

/// Lanes of independent partial sums in [`dot`].
const LANES: usize = 8;

/// `w · x` over [`LANES`] independent partial sums: one running sum would chain every add on
/// the previous one (~4 cycles each); eight chains let the adds overlap and vectorise.
#[inline]
fn dot(w: &[f32], x: &[f32]) -> f32 {
    let mut acc = [0.0f32; LANES];
    let (wc, xc) = (w.chunks_exact(LANES), x.chunks_exact(LANES));
    let tail: f32 = wc
        .remainder()
        .iter()
        .zip(xc.remainder())
        .map(|(a, b)| a * b)
        .sum();
    for (w8, x8) in wc.zip(xc) {
        for k in 0..LANES {
            acc[k] += w8[k] * x8[k];
        }
    }
    acc.iter().sum::<f32>() + tail
}

#[cfg(feature = "train")]
impl<const I: usize, const O: usize> Freeze for dfdx::nn::modules::Linear<I, O, f32, Cpu> {
    type Frozen = Dense<I, O>;

    fn freeze(&self) -> Result<Dense<I, O>, NetError> {
        Dense::new(&self.weight.as_vec(), &self.bias.as_vec())
    }
}

/// Declares a frozen element-wise activation and its dfdx counterpart(s).
macro_rules! activation {
    ($(#[$doc:meta])* $name:ident, |$v:ident| $f:expr, $($dfdx:ident),+) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
        pub struct $name;

        impl<const N: usize> Layer<[f32; N]> for $name {
            type Output = [f32; N];

            #[inline]
            fn forward(&self, mut x: [f32; N]) -> [f32; N] {
                for $v in x.iter_mut() {
                    *$v = $f;
                }
                x
            }
        }

        $(#[cfg(feature = "train")]
        impl Freeze for $dfdx {
            type Frozen = $name;

            fn freeze(&self) -> Result<$name, NetError> {
                Ok($name)
            }
        })+
    };
}

activation!(
    /// `max(x, 0)` (dfdx [`ReLU`]).
    Relu, |v| v.max(0.0), ReLU
);
activation!(
    /// The logistic function, overflow-free ([`crate::activations::sigmoid`]; dfdx [`Sigmoid`]).
    Logistic, |v| sigmoid(*v), Sigmoid
);
activation!(
    /// `tanh(x)` (dfdx [`Tanh`]).
    HyperbolicTangent, |v| num_traits::Float::tanh(*v), Tanh
);
activation!(
    /// The identity: dfdx [`Dropout`] at inference.
    Identity, |v| *v, Dropout
);

/// Freezing and chaining for tuples of layers (dfdx's sequential containers): each element
/// after the first is named with the one before it, whose output it reads.
macro_rules! tuple {
    ($first:ident . $fi:tt $(, $t:ident . $i:tt : $prev:ident)* ; $last:ident) => {
        #[cfg(feature = "train")]
        impl<$first: Freeze $(, $t: Freeze)*> Freeze for ($first, $($t,)*) {
            type Frozen = ($first::Frozen, $($t::Frozen,)*);

            fn freeze(&self) -> Result<Self::Frozen, NetError> {
                Ok((self.$fi.freeze()?, $(self.$i.freeze()?,)*))
            }
        }

        impl<X, $first $(, $t)*> Layer<X> for ($first, $($t,)*)
        where
            $first: Layer<X>,
            $($t: Layer<$prev::Output>,)*
        {
            type Output = $last::Output;

            #[inline]
            fn forward(&self, x: X) -> Self::Output {
                let x = self.$fi.forward(x);
                $(let x = self.$i.forward(x);)*
                x
            }
        }
    };
}

tuple!(A.0; A);
tuple!(A.0, B.1: A; B);
tuple!(A.0, B.1: A, C.2: B; C);
tuple!(A.0, B.1: A, C.2: B, D.3: C; D);
tuple!(A.0, B.1: A, C.2: B, D.3: C, E.4: D; E);
tuple!(A.0, B.1: A, C.2: B, D.3: C, E.4: D, F.5: E; F);

/// `input` as an array of `N` values, checked like every model input: [`NetError::Shape`]
/// unless it has `N` values, [`NetError::NonFinite`] for a NaN or infinite value.
pub fn input<const N: usize>(input: &[f32]) -> Result<[f32; N], RunError> {
    check_input(input, N)?;
    Ok(core::array::from_fn(|i| input[i]))
}

#[cfg(all(test, feature = "train"))]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn sparse_dense_equals_dense_and_its_paths_agree_bit_for_bit() -> Result<(), NetError> {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        // 70 outputs: two full blocks and a padded one; a 9-wide layer: one block of 9.
        let w: Vec<f32> = (0..40 * 70).map(|_| rng.random_range(-1.0..1.0)).collect();
        let b: Vec<f32> = (0..70).map(|_| rng.random_range(-1.0..1.0)).collect();
        let dense = Dense::<40, 70>::new(&w, &b)?;
        let sparse = SparseDense::from_dense(&dense);
        let narrow = Dense::<40, 9>::new(&w[..360], &b[..9])?;
        let narrow_sparse = SparseDense::from_dense(&narrow);
        for round in 0..50 {
            // ReLU-like inputs: about half zero, one round all zero, one all non-zero.
            let x: [f32; 40] = core::array::from_fn(|_| match round {
                0 => 0.0,
                1 => rng.random_range(0.1..2.0),
                _ => rng.random_range(-2.0f32..2.0).max(0.0),
            });
            let (want, got) = (dense.forward(x), sparse.forward(x));
            assert!(want.iter().zip(got).all(|(a, b)| (a - b).abs() <= 1e-5));
            let (want, got) = (narrow.forward(x), narrow_sparse.forward(x));
            assert!(want.iter().zip(got).all(|(a, b)| (a - b).abs() <= 1e-5));
            // The fused ReLU gives the bits of a ReLU and then the layer, negatives, -0.0 and
            // NaN among the inputs.
            let pre: [f32; 40] = core::array::from_fn(|j| match (round, j) {
                (_, 3) => -0.0,
                (2, 5) => f32::NAN,
                _ => rng.random_range(-2.0f32..2.0),
            });
            assert_eq!(
                sparse.forward_relu(&pre).map(f32::to_bits),
                got_bits(&sparse, Relu.forward(pre))
            );
            // The portable kernel gives the same bits as whichever `forward` chose.
            let index: Vec<u16> = (0..40u16).filter(|&j| x[usize::from(j)] != 0.0).collect();
            let value: Vec<f32> = index.iter().map(|&j| x[usize::from(j)]).collect();
            let mut y = *sparse.bias;
            accumulate::<40, 70, 1>(&sparse.weights, &index, &value, &mut y);
            assert_eq!(y.map(f32::to_bits), got_bits(&sparse, x));
            let mut y = *narrow_sparse.bias;
            accumulate::<40, 9, 1>(&narrow_sparse.weights, &index, &value, &mut y);
            assert_eq!(y, narrow_sparse.forward(x));
        }
        // A NaN input reaches every output, as in `Dense`.
        let mut x = [0.0f32; 40];
        x[7] = f32::NAN;
        assert!(sparse.forward(x).iter().all(|v| v.is_nan()));
        Ok(())
    }

    fn got_bits(layer: &SparseDense<40, 70>, x: [f32; 40]) -> [u32; 70] {
        layer.forward(x).map(f32::to_bits)
    }
}
