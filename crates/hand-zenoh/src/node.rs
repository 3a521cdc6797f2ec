//! A ROS 2 node on Zenoh, as rmw_zenoh makes one: a session, a liveliness token for the node
//! and one per publisher, subscription, service and client, data on hashed keys with an
//! attachment on every sample. A ROS 2 node with `RMW_IMPLEMENTATION=rmw_zenoh_cpp` connected
//! to the same router sees the topics and calls the services.
//!
//! ```no_run
//! use hand_zenoh::msg::{handstack_msgs::PressureFrame, std_srvs::{Trigger, TriggerResponse}};
//! use hand_zenoh::node::{Node, NodeOptions};
//!
//! let node = Node::open(NodeOptions::new("/hand0", "tactile"))?; // peer of tcp/127.0.0.1:7447
//! let mut raw = node.publisher::<PressureFrame>("tactile/raw")?; // /hand0/tactile/raw
//! raw.publish(&PressureFrame { pressure_pa: vec![101_325.0; 3], ..Default::default() })?;
//! let _tare = node.service::<Trigger, _>("tactile/tare", |_| TriggerResponse {
//!     success: true,
//!     message: "tared".into(),
//! })?;
//! # Ok::<(), hand_zenoh::NodeError>(())
//! ```

use crate::attachment::{Attachment, AttachmentError, Layout};
use crate::cdr::CdrWriter;
use crate::config::SessionConfig;
use crate::error::NodeError;
use crate::keys::{self, DEFAULT_QOS, EndpointInfo, EntityKind, NodeInfo};
use crate::msg::{Message, Service, service_description};
use crate::types::{HashMode, TypeDescription, dds_type_name};
use std::collections::HashMap;
use std::marker::PhantomData;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};
use zenoh::Wait;
use zenoh::handlers::FifoChannelHandler;
use zenoh::liveliness::LivelinessToken;
use zenoh::sample::{Sample, SampleKind};

/// Who a node is and how it joins.
#[derive(Debug, Clone)]
pub struct NodeOptions {
    /// ROS domain id (0).
    pub domain_id: u32,
    /// Namespace (`/hand0`).
    pub namespace: String,
    /// Node name (`tactile`).
    pub name: String,
    /// Hashed keys (Iron and later) or Humble's `TypeHashNotSupported`.
    pub hash_mode: HashMode,
    /// The Zenoh session.
    pub session: SessionConfig,
}

impl NodeOptions {
    /// Node `name` in `namespace`, domain 0, hashed keys, the default session (peer of a
    /// router on `tcp/127.0.0.1:7447`).
    pub fn new(namespace: &str, name: &str) -> NodeOptions {
        NodeOptions {
            domain_id: 0,
            namespace: namespace.to_owned(),
            name: name.to_owned(),
            hash_mode: HashMode::Rihs01,
            session: SessionConfig::default(),
        }
    }
}

/// A node: its session and its token. Entities it makes hold their own tokens and are
/// withdrawn when dropped; dropping the node closes the session.
pub struct Node {
    session: zenoh::Session,
    info: NodeInfo,
    hash_mode: HashMode,
    next_id: AtomicU64,
    _token: LivelinessToken,
}

impl core::fmt::Debug for Node {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Node").field("info", &self.info).finish()
    }
}

fn check_name(name: &str) -> Result<(), NodeError> {
    let ok = !name.is_empty()
        && !name.contains("//")
        && (name == "/" || !name.ends_with('/'))
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/');
    if ok {
        Ok(())
    } else {
        Err(NodeError::Name(name.to_owned()))
    }
}

/// Nanoseconds since the Unix epoch (rmw_zenoh's source timestamps).
pub fn now_ns() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| i64::try_from(d.as_nanos()).unwrap_or(i64::MAX))
        .unwrap_or(0)
}

struct Endpoint {
    name: String,
    key: String,
    gid: [u8; 16],
    _token: LivelinessToken,
}

impl Node {
    /// Opens the session and declares the node's token.
    pub fn open(options: NodeOptions) -> Result<Node, NodeError> {
        check_name(&options.namespace)?;
        check_name(&options.name)?;
        let session = zenoh::open(options.session.to_zenoh()?)
            .wait()
            .map_err(NodeError::zenoh)?;
        let info = NodeInfo {
            domain_id: options.domain_id,
            zid: session.zid().to_string(),
            nid: 0,
            enclave: "/".to_owned(),
            namespace: options.namespace,
            name: options.name,
        };
        let token_key = keys::liveliness_token(&info, 0, EntityKind::Node, None);
        let token = session
            .liveliness()
            .declare_token(token_key)
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Node {
            session,
            info,
            hash_mode: options.hash_mode,
            next_id: AtomicU64::new(1),
            _token: token,
        })
    }

    /// Where the node sits in the graph.
    pub fn info(&self) -> &NodeInfo {
        &self.info
    }

    /// The Zenoh session, for what this crate does not wrap.
    pub fn session(&self) -> &zenoh::Session {
        &self.session
    }

    fn endpoint(
        &self,
        name: &str,
        description: &TypeDescription,
        kind: EntityKind,
    ) -> Result<Endpoint, NodeError> {
        let name = keys::resolve(&self.info.namespace, name);
        check_name(&name)?;
        let dds = dds_type_name(description.name);
        let hash = self.hash_mode.key_text(description);
        let key = keys::topic_key(self.info.domain_id, &name, &dds, &hash);
        let id = self.next_id.fetch_add(1, Ordering::Relaxed);
        let endpoint = EndpointInfo {
            name: &name,
            dds_type: &dds,
            hash: &hash,
            qos: DEFAULT_QOS,
        };
        let token_key = keys::liveliness_token(&self.info, id, kind, Some(endpoint));
        let gid = keys::gid(&token_key);
        let token = self
            .session
            .liveliness()
            .declare_token(token_key)
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Endpoint {
            name,
            key,
            gid,
            _token: token,
        })
    }

    /// A publisher of `M` on `name` (relative names go under the node's namespace).
    pub fn publisher<M: Message>(&self, name: &str) -> Result<Publisher<M>, NodeError> {
        let ep = self.endpoint(name, &M::description(), EntityKind::Publisher)?;
        let inner = self
            .session
            .declare_publisher(ep.key.clone())
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Publisher {
            inner,
            ep,
            seq: 0,
            buf: CdrWriter::new(),
            _m: PhantomData,
        })
    }

    /// A subscription to `M` on `name`, holding up to `depth` unread samples.
    pub fn subscription<M: Message>(
        &self,
        name: &str,
        depth: usize,
    ) -> Result<Subscription<M>, NodeError> {
        let ep = self.endpoint(name, &M::description(), EntityKind::Subscription)?;
        let inner = self
            .session
            .declare_subscriber(ep.key.clone())
            .with(zenoh::handlers::FifoChannel::new(depth.max(1)))
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Subscription {
            inner,
            ep,
            stats: SubscriptionStats::default(),
            last_seq: HashMap::new(),
            refusals: Vec::new(),
            unsaid: 0,
            _m: PhantomData,
        })
    }

    /// Serves `S` on `name`: `handler` answers each request. A request that does not decode
    /// is answered with an error reply and counted ([`ServiceServer::malformed`]).
    pub fn service<S, F>(&self, name: &str, handler: F) -> Result<ServiceServer, NodeError>
    where
        S: Service,
        F: Fn(S::Request) -> S::Response + Send + Sync + 'static,
    {
        let ep = self.endpoint(name, &service_description::<S>(), EntityKind::Service)?;
        let counts = Arc::new(ServiceCounts::default());
        let seen = Arc::clone(&counts);
        let queryable = self
            .session
            .declare_queryable(ep.key.clone())
            .complete(true)
            .callback(move |query| {
                let bytes = query.payload().map(|p| p.to_bytes().into_owned());
                let request = bytes
                    .as_deref()
                    .ok_or(NodeError::Payload(crate::cdr::CdrError::NoHeader(0)))
                    .and_then(|b| S::Request::from_cdr(b).map_err(NodeError::from));
                // A request carries its client's sequence number and GID; the reply echoes
                // them (rmw_zenoh docs/design.md, "Service Servers"), so one without a readable
                // attachment cannot be answered as a ROS 2 client expects: refused, counted.
                let asked = match query.attachment().map(|a| Attachment::read(&a.to_bytes())) {
                    Some(Ok((a, _))) => Ok(a),
                    Some(Err(e)) => Err(format!("request attachment: {e}")),
                    None => Err("the request has no attachment (sequence number, GID)".to_owned()),
                };
                match (request, asked) {
                    (Ok(req), Ok(asked)) => {
                        seen.handled.fetch_add(1, Ordering::Relaxed);
                        let response = handler(req).to_cdr();
                        let att = Attachment {
                            sequence_number: asked.sequence_number,
                            source_timestamp: now_ns(),
                            source_gid: asked.source_gid,
                        };
                        let _ = query
                            .reply(query.key_expr().clone(), response)
                            .attachment(att.encode())
                            .wait();
                    }
                    (Err(e), _) => {
                        seen.malformed.fetch_add(1, Ordering::Relaxed);
                        let _ = query.reply_err(e.to_string()).wait();
                    }
                    (Ok(_), Err(why)) => {
                        seen.refused.fetch_add(1, Ordering::Relaxed);
                        let _ = query.reply_err(why).wait();
                    }
                }
            })
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(ServiceServer {
            _queryable: queryable,
            _ep: ep,
            counts,
        })
    }

    /// A client of `S` on `name`.
    pub fn client<S: Service>(&self, name: &str) -> Result<Client<S>, NodeError> {
        let ep = self.endpoint(name, &service_description::<S>(), EntityKind::Client)?;
        // Only to learn when a server's queryable is reachable: a server's liveliness token
        // can arrive before its queryable does, and a query sent between the two is answered
        // by no one.
        let querier = self
            .session
            .declare_querier(ep.key.clone())
            .wait()
            .map_err(NodeError::zenoh)?;
        let matching = querier
            .matching_listener()
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Client {
            session: self.session.clone(),
            ep,
            seq: 0,
            matched: false,
            matching,
            _querier: querier,
            _s: PhantomData,
        })
    }

    /// Waits until an entity of `kind` on `name` (resolved against this node's namespace)
    /// is in the graph, by its liveliness token; `false` when `timeout` passes first.
    pub fn wait_for(
        &self,
        kind: EntityKind,
        name: &str,
        timeout: Duration,
    ) -> Result<bool, NodeError> {
        let graph = self.graph()?;
        let wanted = keys::mangle(&keys::resolve(&self.info.namespace, name));
        let deadline = Instant::now() + timeout;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match graph.recv_timeout(left) {
                Ok(Some(change)) if change.alive => {
                    if change.kind == Some(kind) && change.name.as_deref() == Some(&wanted) {
                        return Ok(true);
                    }
                }
                Ok(Some(_)) => {}
                Ok(None) | Err(_) => break,
            }
        }
        Ok(false)
    }

    /// The graph as it changes: every entity already there, then each that comes or goes.
    pub fn graph(&self) -> Result<Graph, NodeError> {
        let inner = self
            .session
            .liveliness()
            .declare_subscriber(format!("{}/{}/**", keys::ADMIN_SPACE, self.info.domain_id))
            .history(true)
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(Graph { inner })
    }
}

/// A Zenoh router in this process (a session in router mode: `zenohd` need not be installed);
/// dropping it closes it.
pub struct Router(zenoh::Session);

impl Router {
    /// Opens a router listening on `endpoint` (`tcp/127.0.0.1:7447`), multicast scouting off.
    pub fn open(endpoint: &str) -> Result<Router, NodeError> {
        zenoh::open(SessionConfig::router(endpoint).to_zenoh()?)
            .wait()
            .map(Router)
            .map_err(NodeError::zenoh)
    }

    /// Opens a router on a free loopback port and returns it with its endpoint. A port found
    /// free ([`crate::config::free_loopback_endpoint`]) can be taken by another socket before
    /// the router binds it (an outbound connection's ephemeral port, on a busy machine): then
    /// another port is tried, up to [`Router::LOOPBACK_TRIES`] in all.
    pub fn open_on_loopback() -> Result<(Router, String), NodeError> {
        let mut last = None;
        for _ in 0..Self::LOOPBACK_TRIES {
            let endpoint = crate::config::free_loopback_endpoint()
                .map_err(|e| NodeError::Config(format!("no free loopback port: {e}")))?;
            match Router::open(&endpoint) {
                Ok(r) => return Ok((r, endpoint)),
                Err(e) => last = Some(e),
            }
        }
        Err(last.unwrap_or_else(|| NodeError::Config("no router opened".into())))
    }

    /// Ports [`Router::open_on_loopback`] tries.
    pub const LOOPBACK_TRIES: usize = 5;

    /// Closes it now (its peers see their links drop).
    pub fn close(self) -> Result<(), NodeError> {
        self.0.close().wait().map_err(NodeError::zenoh)
    }
}

/// Publishes `M` with rmw_zenoh's attachment; the sequence number counts from 1.
pub struct Publisher<M> {
    inner: zenoh::pubsub::Publisher<'static>,
    ep: Endpoint,
    seq: i64,
    buf: CdrWriter,
    _m: PhantomData<fn(&M)>,
}

impl<M: Message> Publisher<M> {
    /// Sends `message`; returns its sequence number.
    pub fn publish(&mut self, message: &M) -> Result<i64, NodeError> {
        self.buf.clear();
        message.write(&mut self.buf);
        self.seq += 1;
        let att = Attachment {
            sequence_number: self.seq,
            source_timestamp: now_ns(),
            source_gid: self.ep.gid,
        };
        self.inner
            .put(self.buf.as_bytes().to_vec())
            .attachment(att.encode())
            .wait()
            .map_err(NodeError::zenoh)?;
        Ok(self.seq)
    }

    /// Waits until at least one subscription matches this publisher (its declaration, not only
    /// its liveliness token, has reached this session); `false` when `timeout` passes first.
    pub fn wait_matched(&self, timeout: Duration) -> Result<bool, NodeError> {
        let listener = self
            .inner
            .matching_listener()
            .wait()
            .map_err(NodeError::zenoh)?;
        let now = self
            .inner
            .matching_status()
            .wait()
            .map_err(NodeError::zenoh)?;
        if now.matching() {
            return Ok(true);
        }
        let deadline = Instant::now() + timeout;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match listener.recv_timeout(left).map_err(NodeError::zenoh)? {
                Some(status) if status.matching() => return Ok(true),
                Some(_) => {}
                None => break,
            }
        }
        Ok(false)
    }

    /// The data key.
    pub fn key(&self) -> &str {
        &self.ep.key
    }

    /// The topic's fully qualified name.
    pub fn name(&self) -> &str {
        &self.ep.name
    }

    /// The publisher's GID.
    pub fn gid(&self) -> [u8; 16] {
        self.ep.gid
    }
}

/// A received message and what came with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Received<M> {
    /// The message.
    pub message: M,
    /// The attachment (`None` when the writer sent none, as a bare Zenoh writer would).
    pub attachment: Option<Attachment>,
    /// When it was taken from the subscription (ns since the Unix epoch).
    pub received_ns: i64,
}

/// What a subscription has seen. Every sample it was given is in exactly one of `received`,
/// `malformed` and `refused`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SubscriptionStats {
    /// Messages decoded and returned.
    pub received: u64,
    /// Samples dropped because the payload did not decode.
    pub malformed: u64,
    /// Samples dropped because their attachment could not be read (neither rmw_zenoh layout).
    pub refused: u64,
    /// Of `received`, those that came without an attachment (a bare Zenoh writer).
    pub missing_attachment: u64,
    /// Of `received`, those whose attachment had the layout of rmw_zenoh ≤ 0.2.3 (Jazzy) /
    /// ≤ 0.1.1 (Humble).
    pub legacy_attachment: u64,
    /// Samples missing by the writers' sequence numbers (counted per writer GID).
    pub lost: u64,
}

/// Receives `M`; malformed and refused samples are counted and dropped, never returned.
pub struct Subscription<M> {
    inner: zenoh::pubsub::Subscriber<FifoChannelHandler<Sample>>,
    ep: Endpoint,
    stats: SubscriptionStats,
    last_seq: HashMap<[u8; 16], i64>,
    /// Each way an attachment was refused, once: said when first seen.
    refusals: Vec<AttachmentError>,
    /// Refusals not yet handed out by [`Subscription::new_refusals`].
    unsaid: usize,
    _m: PhantomData<fn() -> M>,
}

/// The most distinct refusals a subscription remembers (each is said once).
const REFUSALS_KEPT: usize = 16;

impl<M: Message> Subscription<M> {
    /// The next well-formed message, waiting up to `timeout`; `None` when none came.
    pub fn recv_timeout(&mut self, timeout: Duration) -> Result<Option<Received<M>>, NodeError> {
        let deadline = Instant::now() + timeout;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match self.inner.recv_timeout(left) {
                Ok(Some(sample)) => {
                    if let Some(r) = self.take(&sample) {
                        return Ok(Some(r));
                    }
                }
                Ok(None) => break,
                Err(e) => return Err(NodeError::zenoh(e)),
            }
        }
        Ok(None)
    }

    /// The next well-formed message already received, without waiting.
    pub fn try_recv(&mut self) -> Result<Option<Received<M>>, NodeError> {
        while let Some(sample) = self.inner.try_recv().map_err(NodeError::zenoh)? {
            if let Some(r) = self.take(&sample) {
                return Ok(Some(r));
            }
        }
        Ok(None)
    }

    fn take(&mut self, sample: &Sample) -> Option<Received<M>> {
        let attachment = match sample.attachment().map(|a| Attachment::read(&a.to_bytes())) {
            Some(Ok((a, layout))) => Some((a, layout)),
            Some(Err(e)) => {
                self.stats.refused += 1;
                if !self.refusals.contains(&e) && self.refusals.len() < REFUSALS_KEPT {
                    self.refusals.push(e);
                }
                return None;
            }
            None => None,
        };
        let Ok(message) = M::from_cdr(&sample.payload().to_bytes()) else {
            self.stats.malformed += 1;
            return None;
        };
        match attachment {
            None => self.stats.missing_attachment += 1,
            Some((_, Layout::Legacy)) => self.stats.legacy_attachment += 1,
            Some((_, Layout::Current)) => {}
        }
        let attachment = attachment.map(|(a, _)| a);
        if let Some(a) = attachment {
            let last = self.last_seq.insert(a.source_gid, a.sequence_number);
            if let Some(last) = last.filter(|&l| a.sequence_number > l) {
                self.stats.lost += u64::try_from(a.sequence_number - last - 1).unwrap_or(0);
            }
        }
        self.stats.received += 1;
        Some(Received {
            message,
            attachment,
            received_ns: now_ns(),
        })
    }

    /// What it has seen so far.
    pub fn stats(&self) -> SubscriptionStats {
        self.stats
    }

    /// The topic's fully qualified name.
    pub fn name(&self) -> &str {
        &self.ep.name
    }

    /// The ways attachments were refused since the last call, each said once in the
    /// subscription's life (a writer on a third layout is logged once, not once a sample).
    pub fn new_refusals(&mut self) -> &[AttachmentError] {
        let new = &self.refusals[self.unsaid..];
        self.unsaid = self.refusals.len();
        new
    }
}

#[derive(Debug, Default)]
struct ServiceCounts {
    handled: AtomicU64,
    malformed: AtomicU64,
    refused: AtomicU64,
}

/// A served service; dropping it withdraws it.
pub struct ServiceServer {
    _queryable: zenoh::query::Queryable<()>,
    _ep: Endpoint,
    counts: Arc<ServiceCounts>,
}

impl ServiceServer {
    /// Requests answered.
    pub fn handled(&self) -> u64 {
        self.counts.handled.load(Ordering::Relaxed)
    }

    /// Requests that did not decode (answered with an error reply).
    pub fn malformed(&self) -> u64 {
        self.counts.malformed.load(Ordering::Relaxed)
    }

    /// Requests without a readable attachment (answered with an error reply).
    pub fn refused(&self) -> u64 {
        self.counts.refused.load(Ordering::Relaxed)
    }
}

/// Calls `S`.
pub struct Client<S> {
    session: zenoh::Session,
    ep: Endpoint,
    seq: i64,
    matched: bool,
    matching:
        zenoh::matching::MatchingListener<FifoChannelHandler<zenoh::matching::MatchingStatus>>,
    _querier: zenoh::query::Querier<'static>,
    _s: PhantomData<fn() -> S>,
}

impl<S: Service> Client<S> {
    /// Sends `request` once a server is reachable, and waits for the response; both within
    /// `timeout`.
    pub fn call(
        &mut self,
        request: &S::Request,
        timeout: Duration,
    ) -> Result<S::Response, NodeError> {
        let deadline = Instant::now() + timeout;
        let timed_out = |ep: &Endpoint| NodeError::Timeout {
            service: ep.name.clone(),
            timeout_ms: timeout.as_millis(),
        };
        while let Some(status) = self.matching.try_recv().map_err(NodeError::zenoh)? {
            self.matched = status.matching();
        }
        while !self.matched {
            let left = deadline
                .checked_duration_since(Instant::now())
                .ok_or_else(|| timed_out(&self.ep))?;
            match self.matching.recv_timeout(left).map_err(NodeError::zenoh)? {
                Some(status) => self.matched = status.matching(),
                None => return Err(timed_out(&self.ep)),
            }
        }
        self.seq += 1;
        let att = Attachment {
            sequence_number: self.seq,
            source_timestamp: now_ns(),
            source_gid: self.ep.gid,
        };
        let replies = self
            .session
            .get(self.ep.key.clone())
            // As rmw_zenoh's clients query (`rmw_client_data.cpp`, ClientData::make: target
            // ALL_COMPLETE, consolidation NONE): each reply is delivered as it comes, not held
            // for the query's end.
            .target(zenoh::query::QueryTarget::AllComplete)
            .consolidation(zenoh::query::ConsolidationMode::None)
            .payload(request.to_cdr())
            .attachment(att.encode())
            .timeout(deadline.saturating_duration_since(Instant::now()))
            .wait()
            .map_err(NodeError::zenoh)?;
        let reply = replies.recv().map_err(|_| timed_out(&self.ep))?;
        match reply.into_result() {
            Ok(sample) => {
                // The reply echoes this request's sequence number and this client's GID.
                let not_echoed = match sample.attachment().map(|a| Attachment::read(&a.to_bytes()))
                {
                    None => Some("no attachment".to_owned()),
                    Some(Err(e)) => Some(format!("attachment: {e}")),
                    Some(Ok((a, _))) if a.sequence_number != self.seq => Some(format!(
                        "sequence number {}, not this request's {}",
                        a.sequence_number, self.seq
                    )),
                    Some(Ok((a, _))) if a.source_gid != self.ep.gid => {
                        Some("another client's GID".to_owned())
                    }
                    Some(Ok(_)) => None,
                };
                if let Some(reason) = not_echoed {
                    return Err(NodeError::NotEchoed {
                        service: self.ep.name.clone(),
                        reason,
                    });
                }
                Ok(S::Response::from_cdr(&sample.payload().to_bytes())?)
            }
            Err(e) => Err(NodeError::Refused {
                service: self.ep.name.clone(),
                reason: String::from_utf8_lossy(&e.payload().to_bytes()).into_owned(),
            }),
        }
    }

    /// The client's GID: every request's attachment carries it, and a reply must echo it.
    pub fn gid(&self) -> [u8; 16] {
        self.ep.gid
    }

    /// The service's fully qualified name.
    pub fn name(&self) -> &str {
        &self.ep.name
    }
}

/// One change of the graph, read from a liveliness token.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GraphChange {
    /// `true` when the entity appeared, `false` when it went.
    pub alive: bool,
    /// Its kind (`None` for a token that is not rmw_zenoh's).
    pub kind: Option<EntityKind>,
    /// Its node's namespace, mangled (`%hand0`).
    pub namespace: String,
    /// Its node's name.
    pub node: String,
    /// Its topic or service, mangled (`%hand0%tactile%raw`), for all but nodes.
    pub name: Option<String>,
    /// The whole token.
    pub token: String,
}

/// The graph's changes, as a node sees them.
pub struct Graph {
    inner: zenoh::pubsub::Subscriber<FifoChannelHandler<Sample>>,
}

impl Graph {
    /// The next change already seen, without waiting.
    pub fn try_recv(&self) -> Result<Option<GraphChange>, NodeError> {
        let sample = self.inner.try_recv().map_err(NodeError::zenoh)?;
        Ok(sample.map(|s| parse_token(s.key_expr().as_str(), s.kind() == SampleKind::Put)))
    }

    /// The next change, waiting up to `timeout`.
    pub fn recv_timeout(&self, timeout: Duration) -> Result<Option<GraphChange>, NodeError> {
        let sample = self.inner.recv_timeout(timeout).map_err(NodeError::zenoh)?;
        Ok(sample.map(|s| parse_token(s.key_expr().as_str(), s.kind() == SampleKind::Put)))
    }
}

fn parse_token(token: &str, alive: bool) -> GraphChange {
    let parts: Vec<&str> = token.split('/').collect();
    let kind = parts.get(5).and_then(|k| {
        [
            EntityKind::Node,
            EntityKind::Publisher,
            EntityKind::Subscription,
            EntityKind::Service,
            EntityKind::Client,
        ]
        .into_iter()
        .find(|e| e.code() == *k)
    });
    let part = |i: usize| parts.get(i).map(|s| (*s).to_owned());
    GraphChange {
        alive,
        kind,
        namespace: part(7).unwrap_or_default(),
        node: part(8).unwrap_or_default(),
        name: part(9),
        token: token.to_owned(),
    }
}
