//! The attachment rmw_zenoh puts on every sample, query and reply: the writer's sequence
//! number, the source timestamp (ns since the Unix epoch) and its 16-byte GID.
//!
//! **The layout** is rmw_zenoh's `rmw_zenoh_cpp/src/detail/attachment_helpers.cpp` as ROS 2
//! ships it now — Rolling from rmw_zenoh 0.6.0 (PR #601), Jazzy from 0.2.4 (2025-04-20,
//! #605), Humble from 0.1.2 (2025-06-19, #606) — and rmw_zenoh's `docs/design.md`
//! ("Publishers", "Service Clients", "Service Servers"): zenoh-cpp's `ext::Serializer` writes
//! the sequence number and the timestamp as `int64` little-endian and the GID as a
//! `std::array<uint8_t, 16>`, which the Zenoh serialization format writes as a sequence (a
//! LEB128 element count, 16, then the bytes). 33 bytes:
//!
//! ```text
//! <sequence number: i64 LE> <source timestamp: i64 LE> 10 <GID: 16 bytes>
//! ```
//!
//! **The layout before** (rmw_zenoh ≤ 0.2.3 on Jazzy, ≤ 0.1.1 on Humble) named each field:
//! `"sequence_number"`, i64, `"source_timestamp"`, i64, `"source_gid"`, the GID as a sequence —
//! 77 bytes. [`Attachment::encode`] writes the current layout only (a current rmw_zenoh drops
//! a sample whose attachment it cannot read); [`Attachment::read`] reads both, saying which,
//! so a node still hears a peer on an older rmw_zenoh (or a bridge that writes the old layout)
//! and its counters show that the cell is mixed.
//!
//! ```
//! use hand_zenoh::attachment::{Attachment, Layout};
//!
//! let a = Attachment { sequence_number: 7, source_timestamp: 1_700_000_000_000_000_000, source_gid: [9; 16] };
//! let bytes = a.encode();
//! assert_eq!(bytes.len(), 33);
//! assert_eq!(Attachment::read(&bytes)?, (a, Layout::Current));
//! # Ok::<(), hand_zenoh::attachment::AttachmentError>(())
//! ```

/// One attachment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Attachment {
    /// The writer's sequence number (1 for its first sample; a gap is a lost sample).
    pub sequence_number: i64,
    /// When it was written (ns since the Unix epoch).
    pub source_timestamp: i64,
    /// The writer's GID.
    pub source_gid: [u8; 16],
}

/// Which layout an attachment was read in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// rmw_zenoh ≥ 0.2.4 (Jazzy), ≥ 0.1.2 (Humble), Rolling: 33 bytes.
    Current,
    /// rmw_zenoh ≤ 0.2.3 (Jazzy), ≤ 0.1.1 (Humble): the fields named, 77 bytes.
    Legacy,
}

/// Why bytes are not an rmw_zenoh attachment.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum AttachmentError {
    /// Neither layout's length.
    #[error(
        "an attachment of {0} bytes is neither rmw_zenoh's 33-byte layout nor its older 77-byte one"
    )]
    Length(usize),
    /// The GID's length prefix is not 16.
    #[error("the attachment's GID length is {0}, not 16")]
    GidLength(u8),
    /// A 77-byte attachment whose field names are not the older layout's.
    #[error("a 77-byte attachment without the older layout's field names")]
    Names,
}

/// The bytes of the current layout.
pub const LEN: usize = 33;
/// The bytes of the older layout.
pub const LEGACY_LEN: usize = 77;
/// The GID's length, as its LEB128 prefix (one byte: 16 < 128).
const GID_LEN: u8 = 16;
/// The older layout's field names, each preceded by its LEB128 length.
const NAMES: [&str; 3] = ["sequence_number", "source_timestamp", "source_gid"];

impl Attachment {
    /// Its bytes, in the current layout.
    pub fn encode(&self) -> [u8; LEN] {
        let mut out = [0u8; LEN];
        out[..8].copy_from_slice(&self.sequence_number.to_le_bytes());
        out[8..16].copy_from_slice(&self.source_timestamp.to_le_bytes());
        out[16] = GID_LEN;
        out[17..].copy_from_slice(&self.source_gid);
        out
    }

    /// Its bytes in the older layout (77 bytes), for tests of a reader that must take both.
    pub fn encode_legacy(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(LEGACY_LEN);
        let name = |out: &mut Vec<u8>, n: &str| {
            // Every name is shorter than 128 bytes: its LEB128 length is one byte.
            out.push(n.len() as u8);
            out.extend_from_slice(n.as_bytes());
        };
        name(&mut out, NAMES[0]);
        out.extend_from_slice(&self.sequence_number.to_le_bytes());
        name(&mut out, NAMES[1]);
        out.extend_from_slice(&self.source_timestamp.to_le_bytes());
        name(&mut out, NAMES[2]);
        out.push(GID_LEN);
        out.extend_from_slice(&self.source_gid);
        out
    }

    /// Reads one in either layout, and says which.
    pub fn read(bytes: &[u8]) -> Result<(Attachment, Layout), AttachmentError> {
        match bytes.len() {
            LEN => Ok((Self::decode_current(bytes)?, Layout::Current)),
            LEGACY_LEN => Ok((Self::decode_legacy(bytes)?, Layout::Legacy)),
            n => Err(AttachmentError::Length(n)),
        }
    }

    /// Reads one in the current layout only.
    pub fn decode(bytes: &[u8]) -> Result<Attachment, AttachmentError> {
        if bytes.len() != LEN {
            return Err(AttachmentError::Length(bytes.len()));
        }
        Self::decode_current(bytes)
    }

    /// `bytes` (33 of them) as the current layout.
    fn decode_current(bytes: &[u8]) -> Result<Attachment, AttachmentError> {
        if bytes[16] != GID_LEN {
            return Err(AttachmentError::GidLength(bytes[16]));
        }
        Ok(Attachment {
            sequence_number: i64_at(bytes, 0),
            source_timestamp: i64_at(bytes, 8),
            source_gid: gid_at(bytes, 17),
        })
    }

    /// `bytes` (77 of them) as the older layout.
    fn decode_legacy(bytes: &[u8]) -> Result<Attachment, AttachmentError> {
        // name 0 at 0, its value at 16; name 1 at 24, value at 41; name 2 at 49, GID length at
        // 60, GID at 61.
        let named = |at: usize, n: &str| {
            bytes.get(at) == Some(&(n.len() as u8))
                && bytes.get(at + 1..at + 1 + n.len()) == Some(n.as_bytes())
        };
        if !(named(0, NAMES[0]) && named(24, NAMES[1]) && named(49, NAMES[2])) {
            return Err(AttachmentError::Names);
        }
        if bytes[60] != GID_LEN {
            return Err(AttachmentError::GidLength(bytes[60]));
        }
        Ok(Attachment {
            sequence_number: i64_at(bytes, 16),
            source_timestamp: i64_at(bytes, 41),
            source_gid: gid_at(bytes, 61),
        })
    }
}

/// The little-endian `i64` at `at` (the caller checked the length).
fn i64_at(bytes: &[u8], at: usize) -> i64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[at..at + 8]);
    i64::from_le_bytes(b)
}

/// The 16-byte GID at `at` (the caller checked the length).
fn gid_at(bytes: &[u8], at: usize) -> [u8; 16] {
    let mut g = [0u8; 16];
    g.copy_from_slice(&bytes[at..at + 16]);
    g
}

#[cfg(test)]
mod tests {
    use super::{Attachment, AttachmentError, LEGACY_LEN, Layout};

    /// Written by hand from `AttachmentData::serialize_to_zbytes` in attachment_helpers.cpp
    /// (rmw_zenoh 0.2.4+) and the Zenoh serialization format — rmw_zenoh's own tests serialise
    /// no attachment to take a vector from: seq 1, stamp 1 764 100 000 123 456 789 ns, GID
    /// 00 01 … 0f.
    const CURRENT: &str = "0100000000000000\
                           150da07f9a577b18\
                           10\
                           000102030405060708090a0b0c0d0e0f";

    /// The same fields in the layout of rmw_zenoh ≤ 0.2.3.
    const LEGACY: &str = "0f73657175656e63655f6e756d626572\
                          0100000000000000\
                          10736f757263655f74696d657374616d70\
                          150da07f9a577b18\
                          0a736f757263655f676964\
                          10000102030405060708090a0b0c0d0e0f";

    fn unhex(s: &str) -> Vec<u8> {
        (0..s.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&s[i..i + 2], 16).expect("hex"))
            .collect()
    }

    fn vector() -> Attachment {
        Attachment {
            sequence_number: 1,
            source_timestamp: 1_764_100_000_123_456_789,
            source_gid: core::array::from_fn(|i| i as u8),
        }
    }

    #[test]
    fn the_current_layout_is_the_33_bytes_rmw_zenoh_writes() {
        assert_eq!(vector().encode().to_vec(), unhex(CURRENT));
        assert_eq!(
            Attachment::read(&unhex(CURRENT)),
            Ok((vector(), Layout::Current))
        );
    }

    #[test]
    fn the_older_layout_is_read_and_said_to_be_older() {
        let legacy = unhex(LEGACY);
        assert_eq!(legacy.len(), LEGACY_LEN);
        assert_eq!(vector().encode_legacy(), legacy);
        assert_eq!(Attachment::read(&legacy), Ok((vector(), Layout::Legacy)));
        assert_eq!(
            Attachment::decode(&legacy),
            Err(AttachmentError::Length(77))
        );
    }

    #[test]
    fn bytes_of_another_shape_are_typed_errors() {
        let mut bad_gid = unhex(CURRENT);
        bad_gid[16] = 3;
        assert_eq!(
            Attachment::read(&bad_gid),
            Err(AttachmentError::GidLength(3))
        );
        assert_eq!(Attachment::read(&[]), Err(AttachmentError::Length(0)));
        assert_eq!(
            Attachment::read(&unhex(CURRENT)[..32]),
            Err(AttachmentError::Length(32))
        );
        let mut renamed = unhex(LEGACY);
        renamed[1] = b'S';
        assert_eq!(Attachment::read(&renamed), Err(AttachmentError::Names));
        // Any bytes: an error or an attachment, never a panic.
        for n in 0..100u8 {
            let bytes: Vec<u8> = (0..n).map(|i| i.wrapping_mul(37)).collect();
            let _ = Attachment::read(&bytes);
        }
    }
}
