//! Weights files: named `f32` tensors in the safetensors format, written and read with the
//! `safetensors` crate, no ML framework. With the `train` feature a file also takes and fills
//! any dfdx module (dfdx's own `safetensors` feature pins an older copy of that crate and
//! memory-maps files with `unsafe`; this module walks the module with its visitor instead).
//!
//! A [`TensorFile`] holds a model's parameters (under a prefix, e.g. `net.0.0.weight`), any
//! extra tensors a model needs (input normalisation, label catalogues) and one metadata entry,
//! `handstack`, a JSON string. Tensors are written in name order, so the same file is always
//! the same bytes.

use crate::error::NetError;
use safetensors::{Dtype, SafeTensors};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// The metadata key a [`TensorFile`] stores its JSON description under.
pub const METADATA_KEY: &str = "handstack";

/// One stored tensor: its shape and its values in row-major order.
#[derive(Debug, Clone, PartialEq)]
pub struct StoredTensor {
    /// Dimensions, outermost first; empty for a scalar.
    pub shape: Vec<usize>,
    /// `shape.iter().product()` values.
    pub data: Vec<f32>,
}

/// A set of named `f32` tensors plus a JSON metadata string: one `.safetensors` file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TensorFile {
    tensors: BTreeMap<String, StoredTensor>,
    metadata: String,
}

impl TensorFile {
    /// An empty file.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces) a tensor; fails when `data` does not fill `shape`.
    pub fn insert(&mut self, name: &str, shape: &[usize], data: &[f32]) -> Result<(), NetError> {
        let n: usize = shape.iter().product();
        if n != data.len() {
            return Err(NetError::TensorMismatch {
                name: name.to_owned(),
                stored: format!("{} values", data.len()),
                expected: format!("{shape:?}"),
            });
        }
        self.tensors.insert(
            name.to_owned(),
            StoredTensor {
                shape: shape.to_vec(),
                data: data.to_vec(),
            },
        );
        Ok(())
    }

    /// The values of tensor `name`, which must have exactly `shape`.
    pub fn get(&self, name: &str, shape: &[usize]) -> Result<&[f32], NetError> {
        let t = self
            .tensors
            .get(name)
            .ok_or_else(|| NetError::MissingTensor(name.to_owned()))?;
        if t.shape != shape {
            return Err(NetError::TensorMismatch {
                name: name.to_owned(),
                stored: format!("{:?}", t.shape),
                expected: format!("{shape:?}"),
            });
        }
        Ok(&t.data)
    }

    /// The tensor `name` whatever its shape.
    pub fn tensor(&self, name: &str) -> Option<&StoredTensor> {
        self.tensors.get(name)
    }

    /// Tensor names, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.tensors.keys().map(String::as_str)
    }

    /// The metadata JSON string (empty when none was set).
    pub fn metadata(&self) -> &str {
        &self.metadata
    }

    /// The metadata parsed as JSON ([`NetError::SafeTensors`] when it does not parse).
    pub fn metadata_json(&self) -> Result<serde_json::Value, NetError> {
        serde_json::from_str(&self.metadata)
            .map_err(|e| NetError::SafeTensors(format!("metadata: {e}")))
    }

    /// Sets the metadata JSON string.
    pub fn set_metadata(&mut self, json: String) {
        self.metadata = json;
    }

    /// The safetensors bytes (little-endian `F32` tensors, name order).
    pub fn to_bytes(&self) -> Result<Vec<u8>, NetError> {
        let bytes: Vec<(String, Vec<usize>, Vec<u8>)> = self
            .tensors
            .iter()
            .map(|(name, t)| {
                let raw = t.data.iter().flat_map(|v| v.to_le_bytes()).collect();
                (name.clone(), t.shape.clone(), raw)
            })
            .collect();
        let views = bytes
            .iter()
            .map(|(name, shape, raw)| {
                safetensors::tensor::TensorView::new(Dtype::F32, shape.clone(), raw)
                    .map(|v| (name.as_str(), v))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let metadata = (!self.metadata.is_empty())
            .then(|| HashMap::from([(METADATA_KEY.to_owned(), self.metadata.clone())]));
        Ok(safetensors::serialize(views, metadata)?)
    }

    /// Parses safetensors bytes; every tensor must be `F32`.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, NetError> {
        let st = SafeTensors::deserialize(bytes)?;
        let mut file = TensorFile::new();
        for name in st.names() {
            let view = st.tensor(name)?;
            if view.dtype() != Dtype::F32 {
                return Err(NetError::TensorMismatch {
                    name: name.to_owned(),
                    stored: format!("{:?}", view.dtype()),
                    expected: "F32".to_owned(),
                });
            }
            let data: Vec<f32> = view
                .data()
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect();
            // No model stores a NaN or infinity: one is a damaged file, not a weight.
            if let Some(index) = data.iter().position(|v| !v.is_finite()) {
                return Err(NetError::NonFiniteWeight {
                    tensor: name.to_owned(),
                    index,
                });
            }
            file.insert(name, view.shape(), &data)?;
        }
        let (_, header) = SafeTensors::read_metadata(bytes)?;
        if let Some(json) = header.metadata().as_ref().and_then(|m| m.get(METADATA_KEY)) {
            file.metadata = json.clone();
        }
        Ok(file)
    }

    /// Writes the file to `path`.
    pub fn save(&self, path: &Path) -> Result<(), NetError> {
        std::fs::write(path, self.to_bytes()?)?;
        Ok(())
    }

    /// Reads the file at `path`.
    pub fn load(path: &Path) -> Result<Self, NetError> {
        Self::from_bytes(&std::fs::read(path)?)
    }

    /// A model read from `path` by `parse`; any error (unreadable, truncated, a missing or
    /// misshapen tensor, a NaN) names the file ([`NetError::InFile`]).
    pub fn load_with<T>(
        path: &Path,
        parse: impl FnOnce(&TensorFile) -> Result<T, NetError>,
    ) -> Result<T, NetError> {
        let name = path.display().to_string();
        match std::fs::read(path) {
            Ok(bytes) => Self::parse_with(&name, &bytes, parse),
            Err(e) => Err(NetError::from(e).in_file(name)),
        }
    }

    /// A model parsed by `parse` from the safetensors `bytes` of the file `name`; any error
    /// names it ([`NetError::InFile`]).
    pub fn parse_with<T>(
        name: &str,
        bytes: &[u8],
        parse: impl FnOnce(&TensorFile) -> Result<T, NetError>,
    ) -> Result<T, NetError> {
        Self::from_bytes(bytes)
            .and_then(|f| parse(&f))
            .map_err(|e| e.in_file(name))
    }
}

/// Weights files and dfdx modules (feature `train`).
#[cfg(feature = "train")]
mod modules {
    use super::TensorFile;
    use crate::error::NetError;
    use dfdx::prelude::*;
    use num_traits::NumCast;

    impl TensorFile {
        /// Adds every tensor of a dfdx `module` under `prefix` (scalars such as a dropout rate
        /// become rank-0 tensors).
        pub fn add_module<M: TensorCollection<f32, Cpu>>(
            &mut self,
            prefix: &str,
            module: &M,
        ) -> Result<(), NetError> {
            let mut collect = Collect { file: self, prefix };
            M::iter_tensors(&mut RecursiveWalker {
                m: (module, String::new()),
                f: &mut collect,
            })?;
            Ok(())
        }

        /// Overwrites every tensor of a dfdx `module` with the tensors stored under `prefix`;
        /// each must exist with the module's shape.
        pub fn load_module<M: TensorCollection<f32, Cpu>>(
            &self,
            prefix: &str,
            module: &mut M,
        ) -> Result<(), NetError> {
            let mut fill = Fill { file: self, prefix };
            M::iter_tensors(&mut RecursiveWalker {
                m: (module, String::new()),
                f: &mut fill,
            })?;
            Ok(())
        }
    }

    /// Copies a module's tensors into a [`TensorFile`].
    struct Collect<'a> {
        file: &'a mut TensorFile,
        prefix: &'a str,
    }

    impl TensorVisitor<f32, Cpu> for Collect<'_> {
        type Viewer = (ViewTensorRef, ViewTensorName);
        type Err = NetError;
        type E2 = f32;
        type D2 = Cpu;

        fn visit<S: Shape>(
            &mut self,
            _: TensorOptions<S, f32, Cpu>,
            (t, name): (&Tensor<S, f32, Cpu>, String),
        ) -> Result<Option<Tensor<S, f32, Cpu>>, NetError> {
            let shape: Vec<usize> = t.shape().concrete().into_iter().collect();
            self.file
                .insert(&format!("{}{name}", self.prefix), &shape, &t.as_vec())?;
            Ok(None)
        }

        fn visit_scalar<N: NumCast>(
            &mut self,
            _: ScalarOptions<N>,
            (n, name): (&N, String),
        ) -> Result<Option<N>, NetError> {
            let v = n.to_f32().ok_or_else(|| NetError::TensorMismatch {
                name: name.clone(),
                stored: "scalar".to_owned(),
                expected: "a value representable as f32".to_owned(),
            })?;
            self.file
                .insert(&format!("{}{name}", self.prefix), &[], &[v])?;
            Ok(None)
        }
    }

    /// Copies a [`TensorFile`]'s tensors into a module.
    struct Fill<'a> {
        file: &'a TensorFile,
        prefix: &'a str,
    }

    impl TensorVisitor<f32, Cpu> for Fill<'_> {
        type Viewer = (ViewTensorMut, ViewTensorName);
        type Err = NetError;
        type E2 = f32;
        type D2 = Cpu;

        fn visit<S: Shape>(
            &mut self,
            _: TensorOptions<S, f32, Cpu>,
            (t, name): (&mut Tensor<S, f32, Cpu>, String),
        ) -> Result<Option<Tensor<S, f32, Cpu>>, NetError> {
            let shape: Vec<usize> = t.shape().concrete().into_iter().collect();
            let data = self.file.get(&format!("{}{name}", self.prefix), &shape)?;
            t.copy_from(data);
            Ok(None)
        }

        fn visit_scalar<N: NumCast>(
            &mut self,
            _: ScalarOptions<N>,
            (n, name): (&mut N, String),
        ) -> Result<Option<N>, NetError> {
            let full = format!("{}{name}", self.prefix);
            let v = self.file.get(&full, &[])?[0];
            *n = N::from(v).ok_or_else(|| NetError::TensorMismatch {
                name: full,
                stored: format!("{v}"),
                expected: "a value of the module's scalar type".to_owned(),
            })?;
            Ok(None)
        }
    }
}
