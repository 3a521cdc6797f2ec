//! The attachment rmw_zenoh puts on every sample, query and reply: the writer's sequence
//! number, the source timestamp (ns since the Unix epoch) and its 16-byte GID, written with
//! Zenoh's extension serializer as three name / value pairs (a LEB128 length and the UTF-8 of
//! each name, `int64`s little-endian, the GID as a byte sequence: its length, 16, then the
//! bytes; 77 bytes in all).
//!
//! ```
//! use hand_zenoh::attachment::Attachment;
//!
//! let a = Attachment { sequence_number: 7, source_timestamp: 1_700_000_000_000_000_000, source_gid: [9; 16] };
//! assert_eq!(Attachment::decode(&a.encode())?, a);
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

/// Why bytes are not an rmw_zenoh attachment.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AttachmentError {
    /// The bytes end early.
    #[error("attachment ends at byte {0}")]
    Truncated(usize),
    /// A name is not the one expected there (or the GID is not 16 bytes long).
    #[error("attachment field {index} is not `{expected}`")]
    Name {
        /// 0, 1 or 2.
        index: usize,
        /// The name rmw_zenoh writes there.
        expected: &'static str,
    },
    /// Bytes follow the GID.
    #[error("{0} bytes left over after the attachment")]
    Trailing(usize),
}

const NAMES: [&str; 3] = ["sequence_number", "source_timestamp", "source_gid"];

impl Attachment {
    /// Its bytes.
    pub fn encode(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(64);
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
        out.push(16);
        out.extend_from_slice(&self.source_gid);
        out
    }

    /// Reads one from `bytes`.
    pub fn decode(bytes: &[u8]) -> Result<Attachment, AttachmentError> {
        let mut pos = 0;
        let mut take = |n: usize| -> Result<&[u8], AttachmentError> {
            let b = bytes
                .get(pos..pos + n)
                .ok_or(AttachmentError::Truncated(pos))?;
            pos += n;
            Ok(b)
        };
        let mut fields = [[0u8; 16]; 3];
        for (index, expected) in NAMES.iter().enumerate() {
            let len = usize::from(take(1)?[0]);
            if take(len)? != expected.as_bytes() {
                return Err(AttachmentError::Name { index, expected });
            }
            if index == 2 && take(1)? != [16] {
                return Err(AttachmentError::Name { index, expected });
            }
            let width = if index == 2 { 16 } else { 8 };
            fields[index][..width].copy_from_slice(take(width)?);
        }
        if pos != bytes.len() {
            return Err(AttachmentError::Trailing(bytes.len() - pos));
        }
        let int = |f: &[u8; 16]| i64::from_le_bytes(f[..8].try_into().unwrap_or([0; 8]));
        Ok(Attachment {
            sequence_number: int(&fields[0]),
            source_timestamp: int(&fields[1]),
            source_gid: fields[2],
        })
    }
}
