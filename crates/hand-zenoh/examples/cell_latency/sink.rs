//! The sink: one subscription per topic, each read by its own thread (blocking receive), so a
//! sample's receive time is taken as soon as it is decoded. Discovery is waited for
//! explicitly: over `rmw`, every expected publisher's liveliness token in the graph; then, in
//! both modes, a first sample on every topic. The window of `--seconds` starts there: only
//! samples received inside it are counted, and loss is the sequence gaps the subscription
//! counts from its first sample in the window (`stats().lost` over `rmw`, the payload's
//! sequence number over `bare`).
//!
//! Prints `{"event":"measuring"}` when the window starts, `{"event":"done"}` when it ends (the
//! orchestrator reads each process's CPU time at both), then the result as one JSON line.

use crate::Error;
use crate::args::{Args, Stop};
use crate::topics::{FINGERTIPS, PAD_IMU, PAD_RAW, fingertip_topics, key, split_bare};
use hand_zenoh::config::SessionConfig;
use hand_zenoh::keys::{EntityKind, mangle};
use hand_zenoh::msg::Message;
use hand_zenoh::msg::handstack_msgs::PressureFrame;
use hand_zenoh::msg::sensor_msgs::Imu;
use hand_zenoh::node::{Node, NodeOptions, Subscription, now_ns};
use serde_json::json;
use std::collections::HashSet;
use std::marker::PhantomData;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicI64, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use zenoh::Wait;
use zenoh::handlers::{FifoChannel, FifoChannelHandler};
use zenoh::sample::Sample;

/// Unread samples a subscription holds (both modes).
const DEPTH: usize = 100;
/// How long a reader blocks before it looks at the window and the stop flag again.
const POLL: Duration = Duration::from_millis(50);

/// What a reader takes from: this crate's subscription or a bare subscriber.
trait Source: Send {
    /// The next sample's receive and send times (ns since the Unix epoch).
    fn next(&mut self, timeout: Duration) -> Result<Option<(i64, i64)>, Error>;
    /// Samples missing by sequence number so far.
    fn lost(&self) -> u64;
    /// Samples dropped because they did not decode.
    fn malformed(&self) -> u64;
}

struct Rmw<M: Message> {
    sub: Subscription<M>,
    no_attachment: u64,
}

impl<M: Message + Send> Source for Rmw<M> {
    fn next(&mut self, timeout: Duration) -> Result<Option<(i64, i64)>, Error> {
        let Some(r) = self.sub.recv_timeout(timeout)? else {
            return Ok(None);
        };
        match r.attachment {
            Some(a) => Ok(Some((r.received_ns, a.source_timestamp))),
            None => {
                self.no_attachment += 1;
                Ok(None)
            }
        }
    }
    fn lost(&self) -> u64 {
        self.sub.stats().lost
    }
    fn malformed(&self) -> u64 {
        // Undecodable, an unreadable attachment, or none: each a sample not received whole.
        let s = self.sub.stats();
        s.malformed + s.refused + self.no_attachment
    }
}

struct Bare<M> {
    sub: zenoh::pubsub::Subscriber<FifoChannelHandler<Sample>>,
    last: Option<u64>,
    lost: u64,
    malformed: u64,
    _m: PhantomData<fn() -> M>,
}

impl<M: Message> Source for Bare<M> {
    fn next(&mut self, timeout: Duration) -> Result<Option<(i64, i64)>, Error> {
        let deadline = Instant::now() + timeout;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            let Some(sample) = self.sub.recv_timeout(left)? else {
                break;
            };
            let bytes = sample.payload().to_bytes();
            let Some((cdr, seq, sent)) = split_bare(&bytes) else {
                self.malformed += 1;
                continue;
            };
            if M::from_cdr(cdr).is_err() {
                self.malformed += 1;
                continue;
            }
            if let Some(last) = self.last.filter(|&l| seq > l) {
                self.lost += seq - last - 1;
            }
            self.last = Some(seq);
            return Ok(Some((now_ns(), sent)));
        }
        Ok(None)
    }
    fn lost(&self) -> u64 {
        self.lost
    }
    fn malformed(&self) -> u64 {
        self.malformed
    }
}

/// The window, shared by the readers: its start (0 until discovery completes) and length.
struct Window {
    start_ns: AtomicI64,
    length_ns: i64,
    abort: AtomicBool,
}

/// What one topic's reader counted inside the window.
struct TopicResult {
    topic: String,
    latencies_ns: Vec<i64>,
    lost: u64,
    malformed: u64,
    error: Option<String>,
}

fn reader(
    topic: String,
    mut src: Box<dyn Source>,
    window: Arc<Window>,
    first: mpsc::Sender<()>,
    stop: Stop,
) -> TopicResult {
    let mut seen = false;
    let mut baseline = None;
    let mut out = TopicResult {
        topic,
        latencies_ns: Vec::with_capacity(4096),
        lost: 0,
        malformed: 0,
        error: None,
    };
    loop {
        if stop.stopped() || window.abort.load(Ordering::Relaxed) {
            break;
        }
        let start = window.start_ns.load(Ordering::Acquire);
        if start != 0 && now_ns() >= start + window.length_ns {
            break;
        }
        let lost_before = src.lost();
        match src.next(POLL) {
            Ok(Some((received, sent))) => {
                if !seen {
                    seen = true;
                    let _ = first.send(());
                }
                let start = window.start_ns.load(Ordering::Acquire);
                if start == 0 || received < start {
                    continue;
                }
                if received >= start + window.length_ns {
                    break;
                }
                let base = *baseline.get_or_insert(lost_before);
                out.lost = src.lost() - base;
                out.latencies_ns.push(received - sent);
            }
            Ok(None) => {}
            Err(e) => {
                out.error = Some(e.to_string());
                break;
            }
        }
    }
    out.malformed = src.malformed();
    out
}

/// The topics a sink for `hands` hands (and the pad) expects: (topic, is IMU).
fn expected(hands: usize, pad: bool) -> Vec<(String, bool)> {
    let mut t: Vec<(String, bool)> = (0..hands)
        .flat_map(fingertip_topics)
        .map(|n| (n, false))
        .collect();
    if pad {
        t.push((PAD_IMU.to_owned(), true));
        t.push((PAD_RAW.to_owned(), false));
    }
    t
}

/// Nearest-rank percentile of sorted `v`.
fn percentile(v: &[i64], p: f64) -> i64 {
    if v.is_empty() {
        return 0;
    }
    let rank = (p * v.len() as f64).ceil() as usize;
    v[rank.clamp(1, v.len()) - 1]
}

/// `sink --connect E --hands N [--pad] --seconds S [--bare] [--discovery-timeout D]`.
pub(crate) fn run(args: &Args<'_>) -> Result<(), Error> {
    let connect = args.required("--connect")?;
    let hands: usize = args.parse("--hands", 1)?;
    let pad = args.flag("--pad");
    let seconds: f64 = args.parse("--seconds", 10.0)?;
    let discovery_s: f64 = args.parse("--discovery-timeout", 60.0)?;
    let bare = args.flag("--bare");
    let (stop, _closed) = Stop::watch_stdin(Duration::from_secs_f64(discovery_s + seconds + 30.0));
    let topics = expected(hands, pad);
    let window = Arc::new(Window {
        start_ns: AtomicI64::new(0),
        length_ns: (seconds * 1e9) as i64,
        abort: AtomicBool::new(false),
    });
    let opened = Instant::now();
    let deadline = opened + Duration::from_secs_f64(discovery_s);
    let (first_tx, first_rx) = mpsc::channel();
    let spawn = |topic: &str, src: Box<dyn Source>| -> JoinHandle<TopicResult> {
        let (topic, window, first, stop) = (
            topic.to_owned(),
            Arc::clone(&window),
            first_tx.clone(),
            stop.clone(),
        );
        std::thread::spawn(move || reader(topic, src, window, first, stop))
    };

    // Declared before any reader starts, kept until every reader is joined.
    let mut node = None;
    let mut session = None;
    let mut readers = Vec::new();
    let mut missing: Vec<String> = Vec::new();
    if bare {
        let s = zenoh::open(SessionConfig::peer(connect).to_zenoh()?).wait()?;
        for (topic, is_imu) in &topics {
            let declare = |k: String| s.declare_subscriber(k).with(FifoChannel::new(DEPTH)).wait();
            let src: Box<dyn Source> = if *is_imu {
                Box::new(Bare::<Imu> {
                    sub: declare(key::<Imu>(topic))?,
                    last: None,
                    lost: 0,
                    malformed: 0,
                    _m: PhantomData,
                })
            } else {
                Box::new(Bare::<PressureFrame> {
                    sub: declare(key::<PressureFrame>(topic))?,
                    last: None,
                    lost: 0,
                    malformed: 0,
                    _m: PhantomData,
                })
            };
            readers.push(spawn(topic, src));
        }
        session = Some(s);
    } else {
        let mut options = NodeOptions::new("/sink", "cell_sink");
        options.session = SessionConfig::peer(connect);
        let n = Node::open(options)?;
        for (topic, is_imu) in &topics {
            let src: Box<dyn Source> = if *is_imu {
                Box::new(Rmw {
                    sub: n.subscription::<Imu>(topic, DEPTH)?,
                    no_attachment: 0,
                })
            } else {
                Box::new(Rmw {
                    sub: n.subscription::<PressureFrame>(topic, DEPTH)?,
                    no_attachment: 0,
                })
            };
            readers.push(spawn(topic, src));
        }
        // Every publisher's liveliness token in the graph.
        let graph = n.graph()?;
        let mut want: HashSet<String> = topics.iter().map(|(t, _)| mangle(t)).collect();
        while !want.is_empty() {
            let Some(left) = deadline.checked_duration_since(Instant::now()) else {
                break;
            };
            if let Some(change) = graph.recv_timeout(left)? {
                if change.alive && change.kind == Some(EntityKind::Publisher) {
                    if let Some(name) = &change.name {
                        want.remove(name);
                    }
                }
            }
        }
        missing.extend(want.into_iter().map(|m| format!("token {m}")));
        node = Some(n);
    }
    let tokens_s = opened.elapsed().as_secs_f64();
    // A first sample on every topic.
    let mut firsts = 0;
    while missing.is_empty() && firsts < topics.len() {
        let Some(left) = deadline.checked_duration_since(Instant::now()) else {
            missing.push(format!(
                "first samples: {firsts} of {} topics",
                topics.len()
            ));
            break;
        };
        if first_rx.recv_timeout(left).is_ok() {
            firsts += 1;
        }
    }
    let discovered_s = opened.elapsed().as_secs_f64();
    if missing.is_empty() {
        window.start_ns.store(now_ns(), Ordering::Release);
        println!(
            "{}",
            json!({"event": "measuring", "discovery_s": discovered_s})
        );
        std::thread::sleep(Duration::from_secs_f64(seconds));
        println!("{}", json!({"event": "done"}));
    } else {
        window.abort.store(true, Ordering::Relaxed);
    }
    let results: Vec<TopicResult> = readers
        .into_iter()
        .map(|r| r.join().map_err(|_| "a reader panicked"))
        .collect::<Result<_, _>>()?;
    drop(node);
    drop(session);

    let mut all: Vec<i64> = results
        .iter()
        .flat_map(|r| r.latencies_ns.iter().copied())
        .collect();
    all.sort_unstable();
    let us = |ns: i64| ns as f64 / 1e3;
    let errors: Vec<String> = results
        .iter()
        .filter_map(|r| r.error.as_ref().map(|e| format!("{}: {e}", r.topic)))
        .chain(missing.iter().map(|m| format!("discovery timed out: {m}")))
        .collect();
    let result = json!({
        "event": "result",
        "mode": if bare { "bare" } else { "rmw" },
        "hands": hands,
        "topics": topics.len(),
        "fingertips_per_hand": FINGERTIPS,
        "window_s": seconds,
        "tokens_s": tokens_s,
        "discovery_s": discovered_s,
        "samples": all.len(),
        "rate_hz": all.len() as f64 / seconds,
        "p50_us": us(percentile(&all, 0.50)),
        "p99_us": us(percentile(&all, 0.99)),
        "max_us": us(all.last().copied().unwrap_or(0)),
        "min_us": us(all.first().copied().unwrap_or(0)),
        "mean_us": if all.is_empty() { 0.0 } else { us(all.iter().sum::<i64>()) / all.len() as f64 },
        "lost": results.iter().map(|r| r.lost).sum::<u64>(),
        "malformed": results.iter().map(|r| r.malformed).sum::<u64>(),
        "silent_topics": results.iter().filter(|r| r.latencies_ns.is_empty()).count(),
        "errors": errors,
    });
    println!("{result}");
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("; ").into())
    }
}
