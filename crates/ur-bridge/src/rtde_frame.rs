//! RTDE package framing (Universal Robots' RTDE guide: a big-endian u16 size that counts the
//! 3-byte header, a type byte, the payload), as a client and a server both write it.
//!
//! ```
//! use ur_bridge::rtde_frame::{REQUEST_PROTOCOL_VERSION, package, read_package};
//! // "Speak protocol version 2", framed; and read back.
//! let bytes = package(REQUEST_PROTOCOL_VERSION, &[0, 2])?;
//! assert_eq!(bytes, [0, 5, b'V', 0, 2]);
//! let (kind, payload) = read_package(&mut &bytes[..])?.expect("one package");
//! assert_eq!((kind, payload), (REQUEST_PROTOCOL_VERSION, vec![0, 2]));
//! # Ok::<(), std::io::Error>(())
//! ```

use std::io::{self, Read, Write};

/// `RTDE_REQUEST_PROTOCOL_VERSION` ('V').
pub const REQUEST_PROTOCOL_VERSION: u8 = 86;

/// Reads one package: (type, payload). `Ok(None)` at a clean end of stream; a size below the
/// header's 3 bytes is [`io::ErrorKind::InvalidData`].
pub fn read_package(r: &mut impl Read) -> io::Result<Option<(u8, Vec<u8>)>> {
    let mut header = [0_u8; 3];
    match r.read_exact(&mut header) {
        Ok(()) => {}
        Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return Ok(None),
        Err(e) => return Err(e),
    }
    let size = usize::from(u16::from_be_bytes([header[0], header[1]]));
    if size < 3 {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("package size {size} < header"),
        ));
    }
    let mut payload = vec![0; size - 3];
    r.read_exact(&mut payload)?;
    Ok(Some((header[2], payload)))
}

/// Frames `payload` as a package of type `kind`; a payload over 65532 bytes is
/// [`io::ErrorKind::InvalidInput`].
pub fn package(kind: u8, payload: &[u8]) -> io::Result<Vec<u8>> {
    let size = u16::try_from(payload.len() + 3)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "package over 65535 bytes"))?;
    let mut out = Vec::with_capacity(payload.len() + 3);
    out.extend_from_slice(&size.to_be_bytes());
    out.push(kind);
    out.extend_from_slice(payload);
    Ok(out)
}

/// Writes one package.
pub fn write_package(w: &mut impl Write, kind: u8, payload: &[u8]) -> io::Result<()> {
    w.write_all(&package(kind, payload)?)
}
