//! aot-locate's integration tests, one binary: eq. 4 labels of every placement of a set of
//! contact shapes, and properties of the scorer, the detector and the locator over arbitrary
//! input.

mod labels;
mod props;
