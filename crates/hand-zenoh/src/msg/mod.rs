//! The messages and services the stack speaks: standard ROS 2 types where they fit
//! ([`sensor_msgs`], [`geometry_msgs`], [`std_msgs`], [`builtin_interfaces`], [`std_srvs`])
//! and ours ([`handstack_msgs`], whose `.msg` files ship in `ros/handstack_msgs/` for ROS users
//! to build), and the ROS tactile toolbox's [`tactile_msgs`]. Each is declared once, in a `ros_message!` list of its fields: the struct, its
//! CDR encoding and its type description come from that one list, so they cannot disagree.
//!
//! ```
//! use hand_zenoh::msg::{Message, handstack_msgs::PressureFrame, std_msgs::Header};
//!
//! let frame = PressureFrame { header: Header::default(), pressure_pa: vec![101_325.0; 3] };
//! let bytes = frame.to_cdr();
//! assert_eq!(PressureFrame::from_cdr(&bytes)?, frame);
//! # Ok::<(), hand_zenoh::cdr::CdrError>(())
//! ```

use crate::cdr::{CdrError, CdrReader, CdrWriter};
use crate::types::{FieldDescription, FieldType, TypeDescription, type_id};

mod handstack;
mod standard;
mod tactile;

pub use handstack::handstack_msgs;
pub use standard::{
    builtin_interfaces, geometry_msgs, sensor_msgs, service_msgs, std_msgs, std_srvs,
};
pub use tactile::tactile_msgs;

/// A ROS 2 message: its name, its description (for the type hash) and its CDR encoding.
pub trait Message: Sized {
    /// `package/msg/Name`.
    const NAME: &'static str;
    /// Its type description (fields in order, nested types by reference).
    fn description() -> TypeDescription;
    /// Appends its fields to `w`.
    fn write(&self, w: &mut CdrWriter);
    /// Reads its fields from `r`.
    fn read(r: &mut CdrReader<'_>) -> Result<Self, CdrError>;

    /// The whole CDR payload, header included.
    fn to_cdr(&self) -> Vec<u8> {
        let mut w = CdrWriter::new();
        self.write(&mut w);
        w.finish()
    }

    /// Decodes a whole CDR payload; any bytes beyond the message's final padding are an error.
    fn from_cdr(payload: &[u8]) -> Result<Self, CdrError> {
        let mut r = CdrReader::new(payload)?;
        let m = Self::read(&mut r)?;
        r.finish()?;
        Ok(m)
    }
}

/// A ROS 2 service: its request and response messages.
pub trait Service {
    /// `package/srv/Name`.
    const NAME: &'static str;
    /// `Name_Request`.
    type Request: Message;
    /// `package/srv/Name_Event`, the service event's type name.
    const EVENT_NAME: &'static str;
    /// `Name_Response`.
    type Response: Message;
}

/// A service's type description as REP 2011 defines it: the request, the response and the
/// service event (`service_msgs/ServiceEventInfo` with at most one request and one response).
pub fn service_description<S: Service>() -> TypeDescription {
    TypeDescription {
        name: S::NAME,
        fields: vec![
            field(
                "request_message",
                FieldType::nested(S::Request::description),
            ),
            field(
                "response_message",
                FieldType::nested(S::Response::description),
            ),
            field("event_message", FieldType::nested(event_description::<S>)),
        ],
    }
}

fn event_description<S: Service>() -> TypeDescription {
    TypeDescription {
        name: S::EVENT_NAME,
        fields: vec![
            field(
                "info",
                FieldType::nested(service_msgs::ServiceEventInfo::description),
            ),
            field(
                "request",
                FieldType::nested(S::Request::description).bounded_sequence(1),
            ),
            field(
                "response",
                FieldType::nested(S::Response::description).bounded_sequence(1),
            ),
        ],
    }
}

fn field(name: &'static str, ty: FieldType) -> FieldDescription {
    FieldDescription { name, ty }
}

/// A message's definition as rosbag2 stores it in a bag (MCAP schema encoding `ros2msg`): its
/// fields as `.msg` lines, then every type it refers to, each once, depth first, under rosbag2's
/// delimiter — 80 `=` and `MSG: package/Name` (rosbag2_cpp's
/// `local_message_definition_source.cpp`, ROS 2 Jazzy). Readers (rosbags, Foxglove,
/// `mcap-ros2-support`) decode a bag's CDR from it.
///
/// ```
/// use hand_zenoh::msg::{Message, definition, std_msgs::Header};
///
/// let text = definition(&Header::description());
/// assert!(text.starts_with("builtin_interfaces/Time stamp\nstring frame_id\n"));
/// assert!(text.contains("\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"));
/// ```
pub fn definition(description: &TypeDescription) -> String {
    let mut out = String::new();
    let mut seen = std::collections::BTreeSet::new();
    definition_into(description, &mut out, &mut seen);
    out
}

fn definition_into(
    d: &TypeDescription,
    out: &mut String,
    seen: &mut std::collections::BTreeSet<&'static str>,
) {
    for f in &d.fields {
        out.push_str(&field_type_text(&f.ty));
        out.push(' ');
        out.push_str(f.name);
        out.push('\n');
    }
    for f in &d.fields {
        if let Some(nested) = f.ty.nested {
            let n = nested();
            if seen.insert(n.name) {
                out.push('\n');
                out.push_str(&"=".repeat(80));
                out.push_str("\nMSG: ");
                out.push_str(&short_name(n.name));
                out.push('\n');
                definition_into(&n, out, seen);
            }
        }
    }
}

/// `pkg/msg/Name` as a `.msg` file writes it: `pkg/Name`.
fn short_name(name: &str) -> String {
    name.replacen("/msg/", "/", 1)
}

/// A field's type as a `.msg` line writes it (`float32[]`, `float64[9]`, `std_msgs/Header`).
fn field_type_text(ty: &crate::types::FieldType) -> String {
    let (element, suffix) = match ty.type_id {
        id @ 145.. => (id - 144, "[]".to_owned()),
        id @ 97..=144 => (id - 96, format!("[<={}]", ty.capacity)),
        id @ 49..=96 => (id - 48, format!("[{}]", ty.capacity)),
        id => (id, String::new()),
    };
    let name = match element {
        type_id::NESTED => ty.nested.map_or_else(String::new, |n| short_name(n().name)),
        type_id::INT8 => "int8".into(),
        type_id::UINT8 => "uint8".into(),
        type_id::INT16 => "int16".into(),
        type_id::UINT16 => "uint16".into(),
        type_id::INT32 => "int32".into(),
        type_id::UINT32 => "uint32".into(),
        type_id::INT64 => "int64".into(),
        type_id::UINT64 => "uint64".into(),
        type_id::FLOAT32 => "float32".into(),
        type_id::FLOAT64 => "float64".into(),
        type_id::CHAR => "char".into(),
        type_id::BOOL => "bool".into(),
        type_id::STRING if ty.string_capacity > 0 => format!("string<={}", ty.string_capacity),
        _ => "string".into(),
    };
    name + &suffix
}

/// A value that can be a message field: its type for the description, its CDR encoding.
pub trait CdrField: Sized {
    /// Its field type.
    fn field_type() -> FieldType;
    /// The fewest bytes one value takes (bounds a sequence's claimed count).
    const MIN_SIZE: usize;
    /// Appends it to `w`.
    fn put(&self, w: &mut CdrWriter);
    /// Reads one from `r`.
    fn get(r: &mut CdrReader<'_>) -> Result<Self, CdrError>;
}

macro_rules! primitive {
    ($($t:ty => $id:ident, $put:ident;)*) => {$(
        impl CdrField for $t {
            fn field_type() -> FieldType {
                FieldType::plain(type_id::$id)
            }
            const MIN_SIZE: usize = core::mem::size_of::<$t>();
            fn put(&self, w: &mut CdrWriter) {
                w.$put(*self)
            }
            fn get(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
                r.$put()
            }
        }
    )*};
}

primitive! {
    i8 => INT8, i8;
    u8 => UINT8, u8;
    i16 => INT16, i16;
    u16 => UINT16, u16;
    i32 => INT32, i32;
    u32 => UINT32, u32;
    i64 => INT64, i64;
    u64 => UINT64, u64;
    f32 => FLOAT32, f32;
    f64 => FLOAT64, f64;
    bool => BOOL, bool;
}

impl CdrField for String {
    fn field_type() -> FieldType {
        FieldType::plain(type_id::STRING)
    }
    const MIN_SIZE: usize = 5;
    fn put(&self, w: &mut CdrWriter) {
        w.string(self)
    }
    fn get(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
        r.string()
    }
}

impl<T: CdrField> CdrField for Vec<T> {
    fn field_type() -> FieldType {
        T::field_type().sequence()
    }
    const MIN_SIZE: usize = 4;
    fn put(&self, w: &mut CdrWriter) {
        w.seq_len(self.len());
        self.iter().for_each(|v| v.put(w));
    }
    fn get(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
        let n = r.seq_len(T::MIN_SIZE, "sequence")?;
        (0..n).map(|_| T::get(r)).collect()
    }
}

impl<T: CdrField + Copy + Default, const N: usize> CdrField for [T; N] {
    fn field_type() -> FieldType {
        T::field_type().array(N as u64)
    }
    const MIN_SIZE: usize = T::MIN_SIZE * N;
    fn put(&self, w: &mut CdrWriter) {
        self.iter().for_each(|v| v.put(w));
    }
    fn get(r: &mut CdrReader<'_>) -> Result<Self, CdrError> {
        let mut out = [T::default(); N];
        for v in &mut out {
            *v = T::get(r)?;
        }
        Ok(out)
    }
}

/// Declares ROS 2 messages from their field lists: the struct (with the docs given), and its
/// [`Message`] and [`CdrField`] implementations.
macro_rules! ros_message {
    ($(
        $(#[$meta:meta])*
        pub struct $name:ident = $ros:literal {
            $( $(#[$fmeta:meta])* pub $field:ident: $ty:ty, )*
        }
    )*) => {$(
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, Default)]
        pub struct $name {
            $( $(#[$fmeta])* pub $field: $ty, )*
        }

        impl $crate::msg::Message for $name {
            const NAME: &'static str = $ros;
            fn description() -> $crate::types::TypeDescription {
                $crate::types::TypeDescription {
                    name: $ros,
                    fields: vec![$($crate::types::FieldDescription {
                        name: stringify!($field),
                        ty: <$ty as $crate::msg::CdrField>::field_type(),
                    }),*],
                }
            }
            fn write(&self, w: &mut $crate::cdr::CdrWriter) {
                $( $crate::msg::CdrField::put(&self.$field, w); )*
                // An empty message is one placeholder byte on the wire.
                if <[&str]>::is_empty(&[$(stringify!($field)),*]) {
                    w.u8(0);
                }
            }
            fn read(
                r: &mut $crate::cdr::CdrReader<'_>,
            ) -> Result<Self, $crate::cdr::CdrError> {
                if <[&str]>::is_empty(&[$(stringify!($field)),*]) {
                    r.u8()?;
                }
                Ok(Self { $( $field: $crate::msg::CdrField::get(r)?, )* })
            }
        }

        impl $crate::msg::CdrField for $name {
            fn field_type() -> $crate::types::FieldType {
                $crate::types::FieldType::nested(
                    <$name as $crate::msg::Message>::description,
                )
            }
            const MIN_SIZE: usize = 1;
            fn put(&self, w: &mut $crate::cdr::CdrWriter) {
                $crate::msg::Message::write(self, w)
            }
            fn get(
                r: &mut $crate::cdr::CdrReader<'_>,
            ) -> Result<Self, $crate::cdr::CdrError> {
                <$name as $crate::msg::Message>::read(r)
            }
        }
    )*};
}
pub(crate) use ros_message;
