//! Frozen dense stacks read from and written to weights files without an ML framework, under
//! the tensor names dfdx's module walk gives them (`net.0.0.weight`, `net.2.bias`, …), so a
//! file trained with the `train` feature and one written here are the same bytes.
//!
//! Names: a tuple's element `i` is under `i.`, a [`Dense`] layer's parameters are `weight`
//! (`O × I`, row-major) and `bias` (`O`); activations have no parameters (dfdx's `Dropout`
//! stores its rate, a scalar its model writes itself).

use crate::error::NetError;
use crate::frozen::{Dense, HyperbolicTangent, Identity, Logistic, Relu};
use crate::io::TensorFile;

/// A frozen layer (or stack of layers) that a weights file stores.
pub(crate) trait Stored: Sized {
    /// The layer from the tensors under `prefix`; each must exist with the layer's shape.
    fn read(file: &TensorFile, prefix: &str) -> Result<Self, NetError>;
    /// Adds the layer's tensors under `prefix`.
    fn write(&self, file: &mut TensorFile, prefix: &str) -> Result<(), NetError>;
}

impl<const I: usize, const O: usize> Stored for Dense<I, O> {
    fn read(file: &TensorFile, prefix: &str) -> Result<Self, NetError> {
        let weight = file.get(&format!("{prefix}weight"), &[O, I])?;
        let bias = file.get(&format!("{prefix}bias"), &[O])?;
        Dense::new(weight, bias)
    }

    fn write(&self, file: &mut TensorFile, prefix: &str) -> Result<(), NetError> {
        file.insert(&format!("{prefix}weight"), &[O, I], self.weight_rows())?;
        file.insert(&format!("{prefix}bias"), &[O], self.bias())
    }
}

/// Parameter-free layers: nothing to read or write.
macro_rules! parameter_free {
    ($($t:ty),+) => {$(
        impl Stored for $t {
            fn read(_: &TensorFile, _: &str) -> Result<Self, NetError> {
                Ok(Self)
            }

            fn write(&self, _: &mut TensorFile, _: &str) -> Result<(), NetError> {
                Ok(())
            }
        }
    )+};
}

parameter_free!(Relu, Logistic, HyperbolicTangent, Identity);

/// Tuples (dfdx's sequential containers): element `i` under `{prefix}i.`.
macro_rules! tuple {
    ($($t:ident . $i:tt),+) => {
        impl<$($t: Stored),+> Stored for ($($t,)+) {
            fn read(file: &TensorFile, prefix: &str) -> Result<Self, NetError> {
                Ok(($($t::read(file, &format!("{prefix}{}.", $i))?,)+))
            }

            fn write(&self, file: &mut TensorFile, prefix: &str) -> Result<(), NetError> {
                $(self.$i.write(file, &format!("{prefix}{}.", $i))?;)+
                Ok(())
            }
        }
    };
}

tuple!(A.0, B.1);
tuple!(A.0, B.1, C.2);
tuple!(A.0, B.1, C.2, D.3);
