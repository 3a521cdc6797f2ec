//! The node layer's errors.

use crate::attachment::AttachmentError;
use crate::cdr::CdrError;

/// Why a node, publisher, subscription or service call failed.
#[derive(Debug, thiserror::Error)]
pub enum NodeError {
    /// The session settings cannot be made into a Zenoh configuration.
    #[error("zenoh configuration: {0}")]
    Config(String),
    /// Zenoh refused (opening the session, declaring an entity, sending).
    #[error("zenoh: {0}")]
    Zenoh(String),
    /// A name that ROS 2 does not accept (empty, `//`, a trailing `/`).
    #[error("`{0}` is not a valid ROS 2 name")]
    Name(String),
    /// A service call got no reply within its timeout.
    #[error("no reply from `{service}` within {timeout_ms} ms")]
    Timeout {
        /// The service's name.
        service: String,
        /// The timeout.
        timeout_ms: u128,
    },
    /// The server replied with an error.
    #[error("`{service}` replied with an error: {reason}")]
    Refused {
        /// The service's name.
        service: String,
        /// What it said.
        reason: String,
    },
    /// A reply that is not this request's answer: its attachment is missing, unreadable, or does
    /// not echo the request's sequence number and this client's GID (rmw_zenoh's design.md,
    /// "Service Servers"). The response is not used.
    #[error("`{service}` sent a reply that is not this request's: {reason}")]
    NotEchoed {
        /// The service's name.
        service: String,
        /// What the reply's attachment said instead.
        reason: String,
    },
    /// A payload that is not the expected message.
    #[error("payload: {0}")]
    Payload(#[from] CdrError),
    /// An attachment that is not rmw_zenoh's.
    #[error("attachment: {0}")]
    Attachment(#[from] AttachmentError),
}

impl NodeError {
    #[cfg(feature = "node")]
    pub(crate) fn zenoh(e: impl core::fmt::Display) -> NodeError {
        NodeError::Zenoh(e.to_string())
    }
}
