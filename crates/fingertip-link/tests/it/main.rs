//! The frame format against independent vectors, and the reader against a damaged stream.

mod frame;
mod reader;
