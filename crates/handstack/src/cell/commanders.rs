//! Who commands a node: the publishers of one of its input topics, as the graph's liveliness
//! tokens say. A node whose last commander leaves goes to its safe state.

use hand_zenoh::NodeError;
use hand_zenoh::keys::{EntityKind, mangle, resolve};
use hand_zenoh::node::{Graph, Node};
use std::collections::HashSet;

/// The publishers of one topic of a node.
pub(crate) struct Commanders {
    graph: Graph,
    topic: String,
    tokens: HashSet<String>,
}

impl Commanders {
    /// Watches the publishers of `topic` (relative to `node`'s namespace).
    pub(crate) fn watch(node: &Node, topic: &str) -> Result<Commanders, NodeError> {
        Ok(Commanders {
            graph: node.graph()?,
            topic: mangle(&resolve(&node.info().namespace, topic)),
            tokens: HashSet::new(),
        })
    }

    /// Reads the graph's changes so far; `true` when the last publisher has just left.
    pub(crate) fn last_left(&mut self) -> Result<bool, NodeError> {
        let mut left = false;
        while let Some(change) = self.graph.try_recv()? {
            if change.kind != Some(EntityKind::Publisher)
                || change.name.as_deref() != Some(&self.topic)
            {
                continue;
            }
            if change.alive {
                self.tokens.insert(change.token);
                left = false;
            } else if self.tokens.remove(&change.token) && self.tokens.is_empty() {
                left = true;
            }
        }
        Ok(left)
    }
}
