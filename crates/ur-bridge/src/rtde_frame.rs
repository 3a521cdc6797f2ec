//! RTDE package framing (Universal Robots' RTDE guide: a big-endian u16 size that counts the
//! 3-byte header, a type byte, the payload), shared by the bridge's handshake check and the
//! simulated controller's server.

use std::io::{self, Read, Write};

/// `RTDE_REQUEST_PROTOCOL_VERSION` ('V').
pub(crate) const REQUEST_PROTOCOL_VERSION: u8 = 86;

/// Reads one package: (type, payload). `Ok(None)` at a clean end of stream.
pub(crate) fn read_package(r: &mut impl Read) -> io::Result<Option<(u8, Vec<u8>)>> {
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

/// Frames `payload` as a package of type `kind`.
pub(crate) fn package(kind: u8, payload: &[u8]) -> io::Result<Vec<u8>> {
    let size = u16::try_from(payload.len() + 3)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "package over 65535 bytes"))?;
    let mut out = Vec::with_capacity(payload.len() + 3);
    out.extend_from_slice(&size.to_be_bytes());
    out.push(kind);
    out.extend_from_slice(payload);
    Ok(out)
}

/// Writes one package.
pub(crate) fn write_package(w: &mut impl Write, kind: u8, payload: &[u8]) -> io::Result<()> {
    w.write_all(&package(kind, payload)?)
}
