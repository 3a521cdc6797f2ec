//! Shared by the node tests: a free loopback endpoint, a peer node of a router.

use hand_zenoh::config::SessionConfig;
use hand_zenoh::node::{Node, NodeOptions};

/// `tcp/127.0.0.1:PORT` on a port free a moment ago.
pub(crate) fn free_endpoint() -> String {
    hand_zenoh::config::free_loopback_endpoint().expect("a free loopback port")
}

/// Node `name` in `namespace`, a peer of the router at `endpoint`.
pub(crate) fn node(endpoint: &str, namespace: &str, name: &str) -> Node {
    let mut o = NodeOptions::new(namespace, name);
    o.session = SessionConfig::peer(endpoint);
    Node::open(o).expect("node")
}
