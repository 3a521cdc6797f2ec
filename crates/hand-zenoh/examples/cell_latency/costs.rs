//! `costs`: what each step of the rmw path costs in this process, beside the bare path's
//! steps (ns per call, the mean of many calls): where an overhead over bare Zenoh could come
//! from. The publish calls go to a sink session of this process over a loopback router.

use crate::Error;
use crate::args::Args;
use crate::topics::{bare_payload, fingertip_frame, key, split_bare};
use hand_zenoh::attachment::Attachment;
use hand_zenoh::cdr::CdrWriter;
use hand_zenoh::config::SessionConfig;
use hand_zenoh::msg::Message;
use hand_zenoh::msg::handstack_msgs::PressureFrame;
use hand_zenoh::node::{Node, NodeOptions, now_ns};
use serde_json::json;
use std::collections::HashMap;
use std::hint::black_box;
use std::time::{Duration, Instant};
use zenoh::Wait;

fn ns_per<T>(n: u32, mut f: impl FnMut(u32) -> T) -> f64 {
    let t = Instant::now();
    for i in 0..n {
        black_box(f(i));
    }
    t.elapsed().as_nanos() as f64 / f64::from(n)
}

/// `costs [--calls N]`.
pub(crate) fn run(args: &Args<'_>) -> Result<(), Error> {
    let n: u32 = args.parse("--calls", 200_000)?;
    let frame = fingertip_frame("hand0/fingertip0", 0, 7);
    let att = Attachment {
        sequence_number: 7,
        source_timestamp: now_ns(),
        source_gid: [3; 16],
    };
    let att_bytes = att.encode();
    let cdr = frame.to_cdr();
    let bare = bare_payload(cdr.clone(), 7);
    let mut w = CdrWriter::new();
    let mut seqs: HashMap<[u8; 16], i64> = HashMap::new();
    let mut out = json!({
        "payload_bytes_cdr": cdr.len(),
        "attachment_bytes": att_bytes.len(),
        "bare_trailer_bytes": bare.len() - cdr.len(),
        "now_ns": ns_per(n, |_| now_ns()),
        "cdr_encode_reused_buffer": ns_per(n, |_| { w.clear(); frame.write(&mut w); w.as_bytes().len() }),
        "to_vec_copy": ns_per(n, |_| w.as_bytes().to_vec()),
        "cdr_encode_to_cdr": ns_per(n, |_| frame.to_cdr()),
        "attachment_encode": ns_per(n, |_| att.encode()),
        "attachment_decode": ns_per(n, |_| Attachment::decode(&att_bytes)),
        "gap_hashmap_insert": ns_per(n, |i| seqs.insert(att.source_gid, i64::from(i))),
        "cdr_decode": ns_per(n, |_| PressureFrame::from_cdr(&cdr)),
        "bare_payload_append": ns_per(n, |_| bare_payload(cdr.clone(), 7)),
        "bare_split": ns_per(n, |_| split_bare(&bare)),
    });

    // The publish calls, to a subscriber in another session over a loopback router.
    let endpoint = hand_zenoh::config::free_loopback_endpoint()?;
    let _router = zenoh::open(SessionConfig::router(&endpoint).to_zenoh()?).wait()?;
    let mut sink_options = NodeOptions::new("/sink", "costs");
    sink_options.session = SessionConfig::peer(&endpoint);
    let sink = Node::open(sink_options)?;
    let topic = "/hand0/tactile/raw0";
    let _sub = sink
        .session()
        .declare_subscriber(key::<PressureFrame>(topic))
        .callback(|s| {
            black_box(s.payload().len());
        })
        .wait()?;
    let mut options = NodeOptions::new("/hand0", "tactile");
    options.session = SessionConfig::peer(&endpoint);
    let node = Node::open(options)?;
    let mut rmw = node.publisher::<PressureFrame>("tactile/raw0")?;
    let bare_pub = node
        .session()
        .declare_publisher(key::<PressureFrame>(topic))
        .wait()?;
    if !sink.wait_for(
        hand_zenoh::keys::EntityKind::Publisher,
        topic,
        Duration::from_secs(10),
    )? {
        return Err("the publisher never showed in the graph".into());
    }
    let m = n / 10;
    // Paced, not flooded: one call every 20 µs is far below what the link takes.
    let paced = |f: &mut dyn FnMut() -> Result<(), Error>| -> Result<f64, Error> {
        let mut total = Duration::ZERO;
        for _ in 0..m {
            let t = Instant::now();
            f()?;
            total += t.elapsed();
            let until = t + Duration::from_micros(20);
            while Instant::now() < until {
                std::hint::spin_loop();
            }
        }
        Ok(total.as_nanos() as f64 / f64::from(m))
    };
    for round in 0..2 {
        let r = paced(&mut || {
            rmw.publish(&frame)?;
            Ok(())
        })?;
        let mut seq = 0;
        let b = paced(&mut || {
            seq += 1;
            bare_pub.put(bare_payload(frame.to_cdr(), seq)).wait()?;
            Ok(())
        })?;
        out[format!("publish_rmw_round{round}")] = json!(r);
        out[format!("put_bare_round{round}")] = json!(b);
    }
    println!("{}", serde_json::to_string_pretty(&out)?);
    Ok(())
}
