//! Samples a node's subscription could not read for their attachment (neither of rmw_zenoh's
//! layouts): counted in the node's report, and each way they were unreadable said once on
//! stderr when first seen, so a peer on an rmw_zenoh this node cannot read is noticed at once
//! without a line per sample.

use hand_zenoh::msg::Message;
use hand_zenoh::node::Subscription;

/// Says on stderr each new way `sub`'s samples were unreadable.
pub(crate) fn say_new<M: Message>(sub: &mut Subscription<M>) {
    let name = sub.name().to_owned();
    for why in sub.new_refusals() {
        eprintln!("{name}: samples refused, counted and dropped: {why}");
    }
}
