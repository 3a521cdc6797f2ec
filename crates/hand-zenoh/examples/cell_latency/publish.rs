//! The router, the hands and the pad. Publishers are paced by a deadline loop (the next
//! deadline is the last plus one period; sleep until it), not by waiting for anything.

use crate::Error;
use crate::args::{Args, Stop};
use crate::topics::{
    FINGERTIPS, HAND_HZ, PAD_HZ, PAD_IMU, PAD_RAW, bare_payload, fingertip_frame, fingertip_names,
    fingertip_topics, imu, key, pad_frame,
};
use hand_zenoh::config::SessionConfig;
use hand_zenoh::msg::Message;
use hand_zenoh::msg::handstack_msgs::PressureFrame;
use hand_zenoh::msg::sensor_msgs::Imu;
use hand_zenoh::node::{Node, NodeOptions, Publisher};
use std::time::{Duration, Instant};
use zenoh::Wait;

/// How long a role lives at most when its stdin never closes (`--seconds` overrides).
const DEFAULT_CAP_S: f64 = 120.0;

fn cap(args: &Args<'_>) -> Result<Duration, Error> {
    Ok(Duration::from_secs_f64(
        args.parse("--seconds", DEFAULT_CAP_S)?,
    ))
}

/// `router --listen E`: a Zenoh session in router mode until stdin closes.
pub(crate) fn router(args: &Args<'_>) -> Result<(), Error> {
    let listen = args.required("--listen")?;
    let (stop, closed) = Stop::watch_stdin(cap(args)?);
    let _session = zenoh::open(SessionConfig::router(listen).to_zenoh()?).wait()?;
    println!("{{\"event\":\"listening\"}}");
    stop.wait(&closed);
    Ok(())
}

/// Calls `tick(n)` for n = 0, 1, … every `1 / hz` s until `stop`.
fn pace(hz: f64, stop: &Stop, mut tick: impl FnMut(u64) -> Result<(), Error>) -> Result<(), Error> {
    let period = Duration::from_secs_f64(1.0 / hz);
    let mut next = Instant::now();
    let mut n = 0;
    while !stop.stopped() {
        tick(n)?;
        n += 1;
        next += period;
        if let Some(d) = next.checked_duration_since(Instant::now()) {
            std::thread::sleep(d);
        }
    }
    Ok(())
}

/// `hands --first K --count N --connect E [--bare]`: hands K … K + N − 1, a thread each.
pub(crate) fn hands(args: &Args<'_>) -> Result<(), Error> {
    let first: usize = args.parse("--first", 0)?;
    let count: usize = args.parse("--count", 1)?;
    let connect = args.required("--connect")?.to_owned();
    let bare = args.flag("--bare");
    let (stop, _closed) = Stop::watch_stdin(cap(args)?);
    let threads: Vec<_> = (first..first + count)
        .map(|k| {
            let (connect, stop) = (connect.clone(), stop.clone());
            std::thread::spawn(move || {
                if bare {
                    bare_hand(k, &connect, &stop)
                } else {
                    rmw_hand(k, &connect, &stop)
                }
            })
        })
        .collect();
    for t in threads {
        t.join().map_err(|_| "a hand thread panicked")??;
    }
    Ok(())
}

fn frame_ids(hand: usize) -> [String; FINGERTIPS] {
    std::array::from_fn(|i| format!("hand{hand}/fingertip{i}"))
}

fn rmw_hand(hand: usize, connect: &str, stop: &Stop) -> Result<(), Error> {
    let mut options = NodeOptions::new(&format!("/hand{hand}"), "tactile");
    options.session = SessionConfig::peer(connect);
    let node = Node::open(options)?;
    let mut raw = fingertip_names()
        .iter()
        .map(|n| node.publisher::<PressureFrame>(n))
        .collect::<Result<Vec<_>, _>>()?;
    let ids = frame_ids(hand);
    pace(HAND_HZ, stop, |n| {
        for (tip, p) in raw.iter_mut().enumerate() {
            p.publish(&fingertip_frame(&ids[tip], tip, n))?;
        }
        Ok(())
    })
}

fn bare_session(connect: &str) -> Result<zenoh::Session, Error> {
    zenoh::open(SessionConfig::peer(connect).to_zenoh()?).wait()
}

fn bare_publisher<M: Message>(
    session: &zenoh::Session,
    topic: &str,
) -> Result<zenoh::pubsub::Publisher<'static>, Error> {
    session.declare_publisher(key::<M>(topic)).wait()
}

fn bare_hand(hand: usize, connect: &str, stop: &Stop) -> Result<(), Error> {
    let session = bare_session(connect)?;
    let raw = fingertip_topics(hand)
        .iter()
        .map(|t| bare_publisher::<PressureFrame>(&session, t))
        .collect::<Result<Vec<_>, _>>()?;
    let ids = frame_ids(hand);
    pace(HAND_HZ, stop, |n| {
        for (tip, p) in raw.iter().enumerate() {
            let cdr = fingertip_frame(&ids[tip], tip, n).to_cdr();
            p.put(bare_payload(cdr, n + 1)).wait()?;
        }
        Ok(())
    })
}

/// `pad --connect E [--bare]`: node `/pad0`, `sensor_msgs/Imu` on `/pad0/imu` and a
/// `PressureFrame` on `/pad0/tactile/raw`, 30 Hz each.
pub(crate) fn pad(args: &Args<'_>) -> Result<(), Error> {
    let connect = args.required("--connect")?;
    let (stop, _closed) = Stop::watch_stdin(cap(args)?);
    if args.flag("--bare") {
        let session = bare_session(connect)?;
        let imu_pub = bare_publisher::<Imu>(&session, PAD_IMU)?;
        let raw = bare_publisher::<PressureFrame>(&session, PAD_RAW)?;
        pace(PAD_HZ, &stop, |n| {
            imu_pub.put(bare_payload(imu(n).to_cdr(), n + 1)).wait()?;
            raw.put(bare_payload(pad_frame(n).to_cdr(), n + 1)).wait()?;
            Ok(())
        })
    } else {
        let mut options = NodeOptions::new("/pad0", "pad");
        options.session = SessionConfig::peer(connect);
        let node = Node::open(options)?;
        let mut imu_pub: Publisher<Imu> = node.publisher("imu")?;
        let mut raw: Publisher<PressureFrame> = node.publisher("tactile/raw")?;
        debug_assert_eq!(imu_pub.key(), key::<Imu>(PAD_IMU));
        pace(PAD_HZ, &stop, |n| {
            imu_pub.publish(&imu(n))?;
            raw.publish(&pad_frame(n))?;
            Ok(())
        })
    }
}
