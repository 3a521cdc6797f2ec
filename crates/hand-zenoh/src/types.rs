//! ROS 2 type descriptions and their RIHS01 hashes (REP 2011): the SHA-256 of the type's
//! description — its fields' names and type ids, and every type it refers to, sorted by name —
//! written as the JSON that `rosidl` hashes. Iron and later put the hash in every key
//! expression; Humble has none and writes `TypeHashNotSupported` there ([`HashMode`]).
//!
//! ```
//! use hand_zenoh::msg::{Message, sensor_msgs::Imu};
//! use hand_zenoh::types::type_hash;
//!
//! // The same hash ROS 2 Jazzy's sensor_msgs and rosbags give (tests/it/ros_interop.rs checks).
//! let hash = type_hash(&Imu::description());
//! assert!(hash.to_string().starts_with("RIHS01_"));
//! ```

use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// A field's type as `type_description_interfaces/FieldType` numbers it.
#[derive(Debug, Clone, Copy)]
pub struct FieldType {
    /// The type id: the element's id, plus 48 for a fixed array, 96 for a bounded sequence,
    /// 144 for an unbounded sequence.
    pub type_id: u8,
    /// The array's length or the bounded sequence's bound, else 0.
    pub capacity: u64,
    /// A bounded string's bound, else 0.
    pub string_capacity: u64,
    /// A nested message's description, else `None`.
    pub nested: Option<fn() -> TypeDescription>,
}

/// The element type ids of `type_description_interfaces/FieldType`.
pub mod type_id {
    /// A nested message.
    pub const NESTED: u8 = 1;
    /// `int8`.
    pub const INT8: u8 = 2;
    /// `uint8`.
    pub const UINT8: u8 = 3;
    /// `int16`.
    pub const INT16: u8 = 4;
    /// `uint16`.
    pub const UINT16: u8 = 5;
    /// `int32`.
    pub const INT32: u8 = 6;
    /// `uint32`.
    pub const UINT32: u8 = 7;
    /// `int64`.
    pub const INT64: u8 = 8;
    /// `uint64`.
    pub const UINT64: u8 = 9;
    /// `float32`.
    pub const FLOAT32: u8 = 10;
    /// `float64`.
    pub const FLOAT64: u8 = 11;
    /// `char`.
    pub const CHAR: u8 = 13;
    /// `bool`.
    pub const BOOL: u8 = 15;
    /// `string`.
    pub const STRING: u8 = 17;
}

impl FieldType {
    /// A single value of element type `type_id`.
    pub const fn plain(type_id: u8) -> FieldType {
        FieldType {
            type_id,
            capacity: 0,
            string_capacity: 0,
            nested: None,
        }
    }

    /// A nested message.
    pub const fn nested(description: fn() -> TypeDescription) -> FieldType {
        FieldType {
            nested: Some(description),
            ..FieldType::plain(type_id::NESTED)
        }
    }

    /// A fixed array of `n` of these.
    pub const fn array(self, n: u64) -> FieldType {
        FieldType {
            type_id: self.type_id + 48,
            capacity: n,
            ..self
        }
    }

    /// A sequence of at most `n` of these.
    pub const fn bounded_sequence(self, n: u64) -> FieldType {
        FieldType {
            type_id: self.type_id + 96,
            capacity: n,
            ..self
        }
    }

    /// An unbounded sequence of these.
    pub const fn sequence(self) -> FieldType {
        FieldType {
            type_id: self.type_id + 144,
            ..self
        }
    }
}

/// One field of a message.
#[derive(Debug, Clone)]
pub struct FieldDescription {
    /// Its name in the `.msg` file.
    pub name: &'static str,
    /// Its type.
    pub ty: FieldType,
}

/// A message (or service, or service event) type: its fully qualified ROS name
/// (`sensor_msgs/msg/Imu`) and its fields in order.
#[derive(Debug, Clone)]
pub struct TypeDescription {
    /// `package/msg/Name` (`package/srv/Name` for services).
    pub name: &'static str,
    /// Its fields, in order.
    pub fields: Vec<FieldDescription>,
}

/// A RIHS01 type hash.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TypeHash(pub [u8; 32]);

impl core::fmt::Display for TypeHash {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("RIHS01_")?;
        self.0.iter().try_for_each(|b| write!(f, "{b:02x}"))
    }
}

/// What a key expression carries in its type-hash place.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum HashMode {
    /// The RIHS01 hash (ROS 2 Iron, Jazzy and later).
    #[default]
    Rihs01,
    /// `TypeHashNotSupported` (ROS 2 Humble's rmw_zenoh, which has no type hashes).
    Humble,
}

impl HashMode {
    /// The key-expression text for `description` under this mode.
    pub fn key_text(self, description: &TypeDescription) -> String {
        match self {
            HashMode::Rihs01 => type_hash(description).to_string(),
            HashMode::Humble => "TypeHashNotSupported".to_owned(),
        }
    }
}

/// ROS 2's type hash of `description`.
pub fn type_hash(description: &TypeDescription) -> TypeHash {
    let mut referenced = BTreeMap::new();
    collect(description, &mut referenced);
    let mut json = String::from("{\"type_description\": ");
    write_type(&mut json, description);
    json.push_str(", \"referenced_type_descriptions\": [");
    let others = referenced.values().filter(|d| d.name != description.name);
    for (i, d) in others.enumerate() {
        if i > 0 {
            json.push_str(", ");
        }
        write_type(&mut json, d);
    }
    json.push_str("]}");
    TypeHash(Sha256::digest(json.as_bytes()).into())
}

fn collect(d: &TypeDescription, seen: &mut BTreeMap<&'static str, TypeDescription>) {
    for f in &d.fields {
        if let Some(nested) = f.ty.nested {
            let n = nested();
            if !seen.contains_key(n.name) {
                collect(&n, seen);
                seen.insert(n.name, n);
            }
        }
    }
}

/// One type as Python's `json.dumps` writes it (`", "` and `": "` separators), as rosidl
/// hashes it. An empty message gets the placeholder field every ROS 2 generator adds.
fn write_type(out: &mut String, d: &TypeDescription) {
    const PLACEHOLDER: FieldDescription = FieldDescription {
        name: "structure_needs_at_least_one_member",
        ty: FieldType::plain(type_id::UINT8),
    };
    let fields: &[FieldDescription] = if d.fields.is_empty() {
        core::slice::from_ref(&PLACEHOLDER)
    } else {
        &d.fields
    };
    let _ = write!(out, "{{\"type_name\": \"{}\", \"fields\": [", d.name);
    for (i, f) in fields.iter().enumerate() {
        let nested = f.ty.nested.map(|n| n().name).unwrap_or("");
        let _ = write!(
            out,
            "{}{{\"name\": \"{}\", \"type\": {{\"type_id\": {}, \"capacity\": {}, \
             \"string_capacity\": {}, \"nested_type_name\": \"{}\"}}}}",
            if i > 0 { ", " } else { "" },
            f.name,
            f.ty.type_id,
            f.ty.capacity,
            f.ty.string_capacity,
            nested
        );
    }
    out.push_str("]}");
}

/// The DDS-style type name rmw_zenoh puts in keys: `sensor_msgs/msg/Imu` →
/// `sensor_msgs::msg::dds_::Imu_`.
pub fn dds_type_name(ros_name: &str) -> String {
    match ros_name.rsplit_once('/') {
        Some((path, name)) => format!("{}::dds_::{name}_", path.replace('/', "::")),
        None => format!("{ros_name}_"),
    }
}
