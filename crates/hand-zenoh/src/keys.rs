//! rmw_zenoh's names on the wire. Data and services live at
//! `<domain_id>/<name without its outer slashes>/<DDS type name>/<type hash>`; every node,
//! publisher, subscription, service and client declares a liveliness token
//! `@ros2_lv/<domain>/<zid>/<nid>/<id>/<NN|MP|MS|SS|SC>/<enclave>/<namespace>/<node>
//! [/<name>/<type>/<hash>/<qos>]` with `/` inside a part written `%` (an empty part is `%`);
//! an entity's 16-byte GID is the XXH3-128 of its token, low half first.
//!
//! ```
//! use hand_zenoh::keys::{topic_key, mangle};
//!
//! assert_eq!(
//!     topic_key(0, "/hand0/tactile/raw", "handstack_msgs::msg::dds_::PressureFrame_", "TypeHashNotSupported"),
//!     "0/hand0/tactile/raw/handstack_msgs::msg::dds_::PressureFrame_/TypeHashNotSupported",
//! );
//! assert_eq!(mangle("/hand0"), "%hand0");
//! ```

/// The liveliness admin space.
pub const ADMIN_SPACE: &str = "@ros2_lv";

/// The QoS part of a token for the default profile (reliable, volatile, keep last 10): each
/// setting equal to the default is left empty.
pub const DEFAULT_QOS: &str = "::,:,:,:,,";

/// What an entity is, as a token says it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntityKind {
    /// A node (`NN`).
    Node,
    /// A publisher (`MP`).
    Publisher,
    /// A subscription (`MS`).
    Subscription,
    /// A service server (`SS`).
    Service,
    /// A service client (`SC`).
    Client,
}

impl EntityKind {
    /// Its two letters.
    pub fn code(self) -> &'static str {
        match self {
            EntityKind::Node => "NN",
            EntityKind::Publisher => "MP",
            EntityKind::Subscription => "MS",
            EntityKind::Service => "SS",
            EntityKind::Client => "SC",
        }
    }
}

/// A name part of a token: `/` becomes `%`, and an empty part is `%`.
pub fn mangle(name: &str) -> String {
    if name.is_empty() {
        "%".to_owned()
    } else {
        name.replace('/', "%")
    }
}

/// The key of a topic's data or a service's queries.
pub fn topic_key(domain_id: u32, name: &str, dds_type: &str, hash: &str) -> String {
    format!("{domain_id}/{}/{dds_type}/{hash}", name.trim_matches('/'))
}

/// Where a node sits in the graph.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NodeInfo {
    /// ROS domain id.
    pub domain_id: u32,
    /// The session's Zenoh id, as Zenoh prints it.
    pub zid: String,
    /// The node's id within the session.
    pub nid: u64,
    /// The enclave (`/` by default).
    pub enclave: String,
    /// The namespace (`/hand0`).
    pub namespace: String,
    /// The node's name.
    pub name: String,
}

/// A topic or service an entity is about.
#[derive(Debug, Clone, Copy)]
pub struct EndpointInfo<'a> {
    /// Its fully qualified name (`/hand0/tactile/raw`).
    pub name: &'a str,
    /// Its DDS type name.
    pub dds_type: &'a str,
    /// Its type hash text.
    pub hash: &'a str,
    /// Its QoS part.
    pub qos: &'a str,
}

/// The liveliness token of entity `id` of `node`: the node itself (`endpoint` `None`) or a
/// publisher, subscription, service or client.
pub fn liveliness_token(
    node: &NodeInfo,
    id: u64,
    kind: EntityKind,
    endpoint: Option<EndpointInfo<'_>>,
) -> String {
    let mut key = format!(
        "{ADMIN_SPACE}/{}/{}/{}/{id}/{}/{}/{}/{}",
        node.domain_id,
        node.zid,
        node.nid,
        kind.code(),
        mangle(node.enclave.trim_end_matches('/')),
        mangle(node.namespace.trim_end_matches('/')),
        mangle(&node.name),
    );
    if let Some(e) = endpoint {
        key.push_str(&format!(
            "/{}/{}/{}/{}",
            mangle(e.name),
            mangle(e.dds_type),
            mangle(e.hash),
            e.qos
        ));
    }
    key
}

/// An entity's GID: XXH3-128 of its liveliness token, low 64 bits first, each little-endian.
pub fn gid(token: &str) -> [u8; 16] {
    let h = xxhash_rust::xxh3::xxh3_128(token.as_bytes());
    let mut out = [0u8; 16];
    out[..8].copy_from_slice(&(h as u64).to_le_bytes());
    out[8..].copy_from_slice(&((h >> 64) as u64).to_le_bytes());
    out
}

/// A name as seen from `namespace`: an absolute name (`/arm0/goal`) stays; a relative one
/// (`tactile/raw`) goes under the namespace.
pub fn resolve(namespace: &str, name: &str) -> String {
    if name.starts_with('/') {
        name.to_owned()
    } else {
        format!("{}/{name}", namespace.trim_end_matches('/'))
    }
}
