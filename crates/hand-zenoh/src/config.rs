//! How a node joins the cell: its Zenoh session's mode and endpoints. The defaults are
//! rmw_zenoh's (peer, connect to a router on `tcp/127.0.0.1:7447`) with every door that could
//! leave the machine shut: multicast scouting off, listening on loopback only, TCP only.
//!
//! ```
//! use hand_zenoh::config::{SessionConfig, Mode};
//!
//! let c = SessionConfig::default();
//! assert_eq!(c.mode, Mode::Peer);
//! assert_eq!(c.connect, ["tcp/127.0.0.1:7447"]);
//! let router = SessionConfig::router("tcp/127.0.0.1:7447");
//! assert!(router.connect.is_empty());
//! ```

use crate::error::NodeError;

/// A Zenoh session's role.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    /// A peer: talks to other peers directly once the router has introduced them.
    #[default]
    Peer,
    /// A client: everything goes through the router.
    Client,
    /// A router: routes and introduces (any Zenoh session in this mode is a router;
    /// `zenohd` need not be installed).
    Router,
}

impl Mode {
    fn json(self) -> &'static str {
        match self {
            Mode::Peer => "\"peer\"",
            Mode::Client => "\"client\"",
            Mode::Router => "\"router\"",
        }
    }
}

/// A node's Zenoh session settings.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SessionConfig {
    /// Peer, client or router.
    pub mode: Mode,
    /// Endpoints to connect to (`tcp/127.0.0.1:7447`).
    pub connect: Vec<String>,
    /// Endpoints to listen on (`tcp/127.0.0.1:0`: loopback, any free port).
    pub listen: Vec<String>,
}

impl Default for SessionConfig {
    fn default() -> Self {
        SessionConfig {
            mode: Mode::Peer,
            connect: vec!["tcp/127.0.0.1:7447".to_owned()],
            listen: vec!["tcp/127.0.0.1:0".to_owned()],
        }
    }
}

impl SessionConfig {
    /// A peer connecting to the router at `endpoint`.
    pub fn peer(endpoint: &str) -> SessionConfig {
        SessionConfig {
            connect: vec![endpoint.to_owned()],
            ..SessionConfig::default()
        }
    }

    /// A router listening on `endpoint`.
    pub fn router(endpoint: &str) -> SessionConfig {
        SessionConfig {
            mode: Mode::Router,
            connect: Vec::new(),
            listen: vec![endpoint.to_owned()],
        }
    }

    /// The Zenoh configuration: these settings, multicast scouting off, and a connect retry
    /// that goes on for ever (a router restarted later is found again without a restart).
    pub fn to_zenoh(&self) -> Result<zenoh::Config, NodeError> {
        let mut c = zenoh::Config::default();
        let list = |v: &[String]| {
            let quoted: Vec<String> = v.iter().map(|e| format!("{e:?}")).collect();
            format!("[{}]", quoted.join(","))
        };
        let set = |c: &mut zenoh::Config, key: &str, value: &str| {
            c.insert_json5(key, value)
                .map_err(|e| NodeError::Config(format!("{key} = {value}: {e}")))
        };
        set(&mut c, "mode", self.mode.json())?;
        set(&mut c, "connect/endpoints", &list(&self.connect))?;
        set(&mut c, "listen/endpoints", &list(&self.listen))?;
        set(&mut c, "scouting/multicast/enabled", "false")?;
        if self.mode != Mode::Router {
            // Start even when the router is not up yet; keep trying to reach it.
            set(&mut c, "connect/timeout_ms", "0")?;
            set(&mut c, "connect/exit_on_failure", "false")?;
        }
        Ok(c)
    }
}

/// `tcp/127.0.0.1:PORT` on a port that was free a moment ago (bound, read, released): for
/// tests and cells on one machine. Another process may take the port before it is used.
pub fn free_loopback_endpoint() -> std::io::Result<String> {
    let port = std::net::TcpListener::bind("127.0.0.1:0")?
        .local_addr()?
        .port();
    Ok(format!("tcp/127.0.0.1:{port}"))
}

/// Linux: the inodes of the UDP sockets process `pid` (this process for `None`) holds. A node
/// on these settings holds none (Zenoh's UDP transports are not built and multicast scouting
/// is off); tests check it so, of their own process and of node processes. Empty where
/// `/proc` cannot be read.
pub fn udp_sockets(pid: Option<u32>) -> Vec<String> {
    let udp: Vec<String> = ["/proc/net/udp", "/proc/net/udp6"]
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .flat_map(|t| {
            t.lines()
                .skip(1)
                .filter_map(|l| l.split_whitespace().nth(9).map(str::to_owned))
                .collect::<Vec<_>>()
        })
        .collect();
    let fds = match pid {
        Some(p) => format!("/proc/{p}/fd"),
        None => "/proc/self/fd".to_owned(),
    };
    std::fs::read_dir(fds)
        .map(|d| {
            d.filter_map(|e| std::fs::read_link(e.ok()?.path()).ok())
                .filter_map(|l| {
                    let l = l.to_string_lossy();
                    let inode = l.strip_prefix("socket:[")?.strip_suffix(']')?.to_owned();
                    udp.contains(&inode).then_some(inode)
                })
                .collect()
        })
        .unwrap_or_default()
}
