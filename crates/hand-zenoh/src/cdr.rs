//! CDR, little-endian, as ROS 2 puts it on the wire (rmw_zenoh's payloads, rosbag2's records):
//! a 4-byte encapsulation header `00 01 00 00` (CDR_LE), then each primitive aligned to its own
//! size (at most 8) counted from the end of that header; strings are a `u32` length that
//! includes the terminating NUL, the bytes and the NUL; sequences a `u32` count and the
//! elements; fixed arrays the elements alone.
//!
//! ```
//! use hand_zenoh::cdr::{CdrReader, CdrWriter};
//!
//! let mut w = CdrWriter::new();
//! w.u8(7);
//! w.f64(1.5); // aligned to 8: seven bytes of padding after the u8
//! w.string("hi");
//! let bytes = w.finish();
//! assert_eq!(bytes.len(), 4 + 1 + 7 + 8 + 4 + 3);
//!
//! let mut r = CdrReader::new(&bytes)?;
//! assert_eq!((r.u8()?, r.f64()?, r.string()?), (7, 1.5, "hi".to_owned()));
//! r.finish()?;
//! # Ok::<(), hand_zenoh::cdr::CdrError>(())
//! ```

/// The CDR little-endian encapsulation header (representation identifier 0x0001, options 0).
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Why bytes are not a CDR message of the expected type.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CdrError {
    /// The payload is shorter than the 4-byte encapsulation header.
    #[error("payload of {0} bytes has no CDR encapsulation header")]
    NoHeader(usize),
    /// The encapsulation is not CDR little-endian (`00 01`).
    #[error("encapsulation {0:02x?} is not CDR little-endian (00 01)")]
    Encapsulation([u8; 2]),
    /// The payload ends inside a field.
    #[error("payload ends at byte {at}: {needed} more bytes needed for {what}")]
    Truncated {
        /// Offset (after the header) where the field starts.
        at: usize,
        /// Bytes the field needs beyond the end.
        needed: usize,
        /// The field's CDR kind.
        what: &'static str,
    },
    /// A sequence or string claims more elements than the rest of the payload can hold.
    #[error("{what} at byte {at} claims {count} elements, the payload holds at most {room}")]
    Length {
        /// Offset (after the header) of the count.
        at: usize,
        /// The claimed count.
        count: u32,
        /// How many could fit.
        room: usize,
        /// The field's CDR kind.
        what: &'static str,
    },
    /// A boolean that is neither 0 nor 1.
    #[error("boolean at byte {at} is {value}, not 0 or 1")]
    Bool {
        /// Offset (after the header).
        at: usize,
        /// The byte.
        value: u8,
    },
    /// A string that is not NUL-terminated UTF-8.
    #[error("string at byte {at} is not NUL-terminated UTF-8")]
    String {
        /// Offset (after the header) of its length.
        at: usize,
    },
    /// Bytes left over after the message (beyond the at most 3 bytes of final padding).
    #[error("{0} bytes left over after the message")]
    Trailing(usize),
}

/// Writes one CDR little-endian message, header included.
#[derive(Debug, Clone)]
pub struct CdrWriter {
    buf: Vec<u8>,
}

impl Default for CdrWriter {
    fn default() -> Self {
        Self::new()
    }
}

/// Invokes `$m!` with every CDR primitive: its doc line, its method name, its Rust type.
macro_rules! primitives {
    ($m:ident) => {
        $m! {
            /// An `int8`.
            i8: i8;
            /// A `uint8` (also `byte` and `char`).
            u8: u8;
            /// An `int16`.
            i16: i16;
            /// A `uint16`.
            u16: u16;
            /// An `int32`.
            i32: i32;
            /// A `uint32`.
            u32: u32;
            /// An `int64`.
            i64: i64;
            /// A `uint64`.
            u64: u64;
            /// A `float32`.
            f32: f32;
            /// A `float64`.
            f64: f64;
        }
    };
}

macro_rules! put {
    ($($(#[$doc:meta])* $name:ident: $t:ty;)*) => {$(
        $(#[$doc])*
        pub fn $name(&mut self, v: $t) {
            self.align(core::mem::size_of::<$t>());
            self.buf.extend_from_slice(&v.to_le_bytes());
        }
    )*};
}

impl CdrWriter {
    /// A writer holding the encapsulation header.
    pub fn new() -> CdrWriter {
        CdrWriter::with_capacity(64)
    }

    /// A writer with room for `bytes` bytes of message (so a steady publisher need not grow it).
    pub fn with_capacity(bytes: usize) -> CdrWriter {
        let mut buf = Vec::with_capacity(bytes + 4);
        buf.extend_from_slice(&CDR_LE_HEADER);
        CdrWriter { buf }
    }

    /// Empties the writer back to the header, keeping its allocation.
    pub fn clear(&mut self) {
        self.buf.truncate(CDR_LE_HEADER.len());
    }

    fn align(&mut self, n: usize) {
        let pos = self.buf.len() - CDR_LE_HEADER.len();
        let pad = (n - pos % n) % n;
        self.buf.resize(self.buf.len() + pad, 0);
    }

    primitives!(put);

    /// A `bool` (one byte, 0 or 1).
    pub fn bool(&mut self, v: bool) {
        self.u8(u8::from(v));
    }

    /// A `string`: length with the NUL, bytes, NUL.
    pub fn string(&mut self, v: &str) {
        self.seq_len(v.len() + 1);
        self.buf.extend_from_slice(v.as_bytes());
        self.buf.push(0);
    }

    /// A sequence's element count.
    ///
    /// # Panics
    /// When `n` exceeds `u32::MAX` (CDR cannot say it; no message here comes near).
    pub fn seq_len(&mut self, n: usize) {
        self.u32(u32::try_from(n).expect("CDR sequence longer than u32::MAX"));
    }

    /// The message so far, header included.
    pub fn as_bytes(&self) -> &[u8] {
        &self.buf
    }

    /// The finished message, header included.
    pub fn finish(self) -> Vec<u8> {
        self.buf
    }
}

/// Reads one CDR little-endian message; every read checks the bounds.
#[derive(Debug, Clone)]
pub struct CdrReader<'a> {
    body: &'a [u8],
    pos: usize,
}

macro_rules! get {
    ($($(#[$doc:meta])* $name:ident: $t:ty;)*) => {$(
        $(#[$doc])*
        pub fn $name(&mut self) -> Result<$t, CdrError> {
            const N: usize = core::mem::size_of::<$t>();
            self.align(N, stringify!($t))?;
            let b = self.take(N, stringify!($t))?;
            let mut a = [0u8; N];
            a.copy_from_slice(b);
            Ok(<$t>::from_le_bytes(a))
        }
    )*};
}

impl<'a> CdrReader<'a> {
    /// A reader of `payload`, after checking its CDR_LE header.
    pub fn new(payload: &'a [u8]) -> Result<CdrReader<'a>, CdrError> {
        let Some((head, body)) = payload.split_first_chunk::<4>() else {
            return Err(CdrError::NoHeader(payload.len()));
        };
        if head[..2] != CDR_LE_HEADER[..2] {
            return Err(CdrError::Encapsulation([head[0], head[1]]));
        }
        Ok(CdrReader { body, pos: 0 })
    }

    fn remaining(&self) -> usize {
        self.body.len() - self.pos
    }

    fn take(&mut self, n: usize, what: &'static str) -> Result<&'a [u8], CdrError> {
        if n > self.remaining() {
            return Err(CdrError::Truncated {
                at: self.pos,
                needed: n - self.remaining(),
                what,
            });
        }
        let b = &self.body[self.pos..self.pos + n];
        self.pos += n;
        Ok(b)
    }

    fn align(&mut self, n: usize, what: &'static str) -> Result<(), CdrError> {
        let pad = (n - self.pos % n) % n;
        self.take(pad, what).map(|_| ())
    }

    primitives!(get);

    /// A `bool`; any byte but 0 or 1 is an error.
    pub fn bool(&mut self) -> Result<bool, CdrError> {
        let at = self.pos;
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            value => Err(CdrError::Bool { at, value }),
        }
    }

    /// A `string`.
    pub fn string(&mut self) -> Result<String, CdrError> {
        self.align(4, "string")?;
        let at = self.pos;
        let n = self.seq_len(1, "string")?;
        let bytes = self.take(n, "string")?;
        match bytes.split_last() {
            Some((0, text)) => core::str::from_utf8(text)
                .map(str::to_owned)
                .map_err(|_| CdrError::String { at }),
            _ => Err(CdrError::String { at }),
        }
    }

    /// A sequence's element count, checked against the room left when each element takes at
    /// least `min_size` bytes (so a corrupt count cannot make the caller allocate gigabytes).
    pub fn seq_len(&mut self, min_size: usize, what: &'static str) -> Result<usize, CdrError> {
        let at = self.pos;
        let count = self.u32()?;
        let room = self.remaining() / min_size.max(1);
        match usize::try_from(count) {
            Ok(n) if n <= room => Ok(n),
            _ => Err(CdrError::Length {
                at,
                count,
                room,
                what,
            }),
        }
    }

    /// Ends the message: at most 3 bytes of padding may follow it.
    pub fn finish(self) -> Result<(), CdrError> {
        match self.remaining() {
            0..=3 => Ok(()),
            n => Err(CdrError::Trailing(n)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reader(body: &[u8]) -> CdrReader<'_> {
        CdrReader { body, pos: 0 }
    }

    #[test]
    fn alignment_counts_from_after_the_header() {
        let mut w = CdrWriter::new();
        w.u8(1);
        w.u16(2);
        w.u32(3);
        w.u8(4);
        w.f64(5.0);
        assert_eq!(
            w.finish(),
            [
                0, 1, 0, 0, // header
                1, 0, 2, 0, 3, 0, 0, 0, 4, 0, 0, 0, 0, 0, 0, 0, // u8 pad u16 u32 u8 pad×7
                0, 0, 0, 0, 0, 0, 0x14, 0x40, // 5.0
            ]
        );
    }

    #[test]
    fn bad_bytes_are_typed_errors() {
        assert_eq!(CdrReader::new(&[0, 1]).unwrap_err(), CdrError::NoHeader(2));
        assert_eq!(
            CdrReader::new(&[0, 0, 0, 0]).unwrap_err(),
            CdrError::Encapsulation([0, 0])
        );
        assert!(matches!(
            reader(&[1, 0]).u32(),
            Err(CdrError::Truncated { needed: 2, .. })
        ));
        assert_eq!(reader(&[2]).bool(), Err(CdrError::Bool { at: 0, value: 2 }));
        // A string without its NUL, and one that is not UTF-8.
        assert_eq!(
            reader(&[2, 0, 0, 0, b'h', b'i']).string(),
            Err(CdrError::String { at: 0 })
        );
        assert_eq!(
            reader(&[2, 0, 0, 0, 0xff, 0]).string(),
            Err(CdrError::String { at: 0 })
        );
        // A count the payload cannot hold is refused before anything is allocated.
        assert!(matches!(
            reader(&[0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0]).seq_len(4, "sequence"),
            Err(CdrError::Length {
                count: u32::MAX,
                room: 1,
                ..
            })
        ));
        assert_eq!(reader(&[0; 4]).finish(), Err(CdrError::Trailing(4)));
        assert_eq!(reader(&[0; 3]).finish(), Ok(()));
    }
}
