//! RTDE wire format (Universal Robots' RTDE guide, protocol version 2): package types, the
//! variable types and their big-endian encodings.

pub(crate) use ur_bridge::rtde_frame::{read_package, write_package};

/// `RTDE_REQUEST_PROTOCOL_VERSION` ('V').
pub const REQUEST_PROTOCOL_VERSION: u8 = ur_bridge::rtde_frame::REQUEST_PROTOCOL_VERSION;

/// Frames `payload` as a package of type `kind`.
pub fn package(kind: u8, payload: &[u8]) -> std::io::Result<Vec<u8>> {
    ur_bridge::rtde_frame::package(kind, payload)
}
/// `RTDE_GET_URCONTROL_VERSION` ('v').
pub const GET_URCONTROL_VERSION: u8 = 118;
/// `RTDE_TEXT_MESSAGE` ('M').
pub(crate) const TEXT_MESSAGE: u8 = 77;
/// `RTDE_DATA_PACKAGE` ('U').
pub const DATA_PACKAGE: u8 = 85;
/// `RTDE_CONTROL_PACKAGE_SETUP_OUTPUTS` ('O').
pub const SETUP_OUTPUTS: u8 = 79;
/// `RTDE_CONTROL_PACKAGE_SETUP_INPUTS` ('I').
pub const SETUP_INPUTS: u8 = 73;
/// `RTDE_CONTROL_PACKAGE_START` ('S').
pub const START: u8 = 83;
/// `RTDE_CONTROL_PACKAGE_PAUSE` ('P').
pub const PAUSE: u8 = 80;

/// An RTDE variable type, as named in recipe replies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum VarType {
    Bool,
    Uint8,
    Uint32,
    Uint64,
    Int32,
    Double,
    Vector3d,
    Vector6d,
    Vector6Int32,
}

impl VarType {
    /// The name the controller reports in a recipe reply.
    pub(crate) fn name(self) -> &'static str {
        match self {
            VarType::Bool => "BOOL",
            VarType::Uint8 => "UINT8",
            VarType::Uint32 => "UINT32",
            VarType::Uint64 => "UINT64",
            VarType::Int32 => "INT32",
            VarType::Double => "DOUBLE",
            VarType::Vector3d => "VECTOR3D",
            VarType::Vector6d => "VECTOR6D",
            VarType::Vector6Int32 => "VECTOR6INT32",
        }
    }

    /// Bytes on the wire.
    pub(crate) fn size(self) -> usize {
        match self {
            VarType::Bool | VarType::Uint8 => 1,
            VarType::Uint32 | VarType::Int32 => 4,
            VarType::Uint64 | VarType::Double => 8,
            VarType::Vector3d => 24,
            VarType::Vector6d => 48,
            VarType::Vector6Int32 => 24,
        }
    }
}

/// One variable's value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Value {
    Bool(bool),
    Uint8(u8),
    Uint32(u32),
    Uint64(u64),
    Int32(i32),
    Double(f64),
    Vector3d([f64; 3]),
    Vector6d([f64; 6]),
    Vector6Int32([i32; 6]),
}

impl Value {
    /// Appends the big-endian encoding.
    pub(crate) fn encode(&self, out: &mut Vec<u8>) {
        match *self {
            Value::Bool(b) => out.push(u8::from(b)),
            Value::Uint8(v) => out.push(v),
            Value::Uint32(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Uint64(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Int32(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Double(v) => out.extend_from_slice(&v.to_be_bytes()),
            Value::Vector3d(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Value::Vector6d(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
            Value::Vector6Int32(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_be_bytes())),
        }
    }

    /// Decodes one value of type `ty` from the front of `bytes` (which must hold `ty.size()`).
    pub(crate) fn decode(ty: VarType, bytes: &[u8]) -> Value {
        let f = |i: usize| f64::from_be_bytes(bytes[i * 8..i * 8 + 8].try_into().unwrap_or([0; 8]));
        let n = |i: usize| i32::from_be_bytes(bytes[i * 4..i * 4 + 4].try_into().unwrap_or([0; 4]));
        match ty {
            VarType::Bool => Value::Bool(bytes[0] != 0),
            VarType::Uint8 => Value::Uint8(bytes[0]),
            VarType::Uint32 => Value::Uint32(n(0) as u32),
            VarType::Uint64 => {
                Value::Uint64(u64::from_be_bytes(bytes[..8].try_into().unwrap_or([0; 8])))
            }
            VarType::Int32 => Value::Int32(n(0)),
            VarType::Double => Value::Double(f(0)),
            VarType::Vector3d => Value::Vector3d([f(0), f(1), f(2)]),
            VarType::Vector6d => Value::Vector6d(core::array::from_fn(f)),
            VarType::Vector6Int32 => Value::Vector6Int32(core::array::from_fn(n)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip() {
        let vals = [
            (VarType::Int32, Value::Int32(-7)),
            (VarType::Uint32, Value::Uint32(0xdead_beef)),
            (VarType::Double, Value::Double(-1.25)),
            (
                VarType::Vector6d,
                Value::Vector6d([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            ),
            (VarType::Vector3d, Value::Vector3d([0.5, -0.5, 9.0])),
            (
                VarType::Vector6Int32,
                Value::Vector6Int32([253, 253, 253, 253, 253, -1]),
            ),
            (VarType::Uint64, Value::Uint64(1 << 40)),
        ];
        for (ty, v) in vals {
            let mut buf = Vec::new();
            v.encode(&mut buf);
            assert_eq!(buf.len(), ty.size());
            assert_eq!(Value::decode(ty, &buf), v);
        }
    }

    #[test]
    fn short_header_is_an_error() {
        let bytes = package(START, &[]).unwrap();
        assert_eq!(bytes, [0, 3, START]);
        let bad = [0_u8, 2, START];
        assert!(read_package(&mut &bad[..]).is_err());
        assert!(read_package(&mut &[][..]).unwrap().is_none());
    }
}
