//! The RTDE server (port 30004), protocol version 2: version negotiation, controller version,
//! output and input recipes with the real variable types, start / pause, and data packages at
//! the requested frequency.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use super::Shared;
use super::variables::{input_type, output_type, output_value};
use super::wire::{self, Value, VarType};

/// How START delivers the output recipe.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Streaming {
    /// A thread sends a data package every period until PAUSE or the connection ends.
    Thread,
    /// One data package at once, no thread: the in-memory (fuzzing) path, which must not
    /// leave a thread behind.
    Once,
}

/// The most input recipes a connection may set up: recipe ids are one byte, 0 means refused.
const MAX_INPUT_RECIPES: usize = 255;

/// What the client asked for on this connection.
struct Session {
    id: u64,
    output: Option<(Vec<(String, VarType)>, f64)>,
    inputs: Vec<Vec<(String, VarType)>>,
    streaming: Option<Arc<AtomicBool>>,
    mode: Streaming,
}

fn parse_names(bytes: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(bytes)
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect()
}

fn send<W: Write>(out: &Mutex<W>, kind: u8, payload: &[u8]) -> std::io::Result<()> {
    let mut s = out.lock().unwrap_or_else(|e| e.into_inner());
    wire::write_package(&mut *s, kind, payload)
}

/// Serves one RTDE connection until it closes or the simulator stops.
pub(crate) fn serve(shared: &Arc<Shared>, stream: TcpStream, id: u64) -> std::io::Result<()> {
    stream.set_nodelay(true)?;
    let out = Arc::new(Mutex::new(stream.try_clone()?));
    let reader = std::io::BufReader::new(stream);
    serve_io(shared, reader, &out, id, Streaming::Thread, |_| {})
}

/// RTDE over any byte stream (a socket, or a fuzzer's bytes): reads packages from `reader`
/// until it ends, answers on `out`; `after_package` runs after each handled package.
pub(crate) fn serve_io<W: Write + Send + 'static>(
    shared: &Arc<Shared>,
    mut reader: impl Read,
    out: &Arc<Mutex<W>>,
    id: u64,
    mode: Streaming,
    mut after_package: impl FnMut(&Shared),
) -> std::io::Result<()> {
    let mut session = Session {
        id,
        output: None,
        inputs: Vec::new(),
        streaming: None,
        mode,
    };
    let result = (|| -> std::io::Result<()> {
        loop {
            let (kind, payload) = match wire::read_package(&mut reader) {
                Ok(Some(package)) => package,
                Ok(None) => return Ok(()),
                // A header that cannot be framed: say why, then drop the connection (nothing
                // after it can be framed either).
                Err(e) if e.kind() == std::io::ErrorKind::InvalidData => {
                    return text(out, &format!("{e}: closing the connection"));
                }
                Err(e) => return Err(e),
            };
            if shared.stopped() {
                return Ok(());
            }
            handle(shared, out, &mut session, kind, &payload)?;
            after_package(shared);
        }
    })();
    if let Some(flag) = session.streaming.take() {
        flag.store(false, Ordering::SeqCst);
    }
    shared.release_inputs(session.id);
    result
}

fn handle<W: Write + Send + 'static>(
    shared: &Arc<Shared>,
    out: &Arc<Mutex<W>>,
    session: &mut Session,
    kind: u8,
    payload: &[u8],
) -> std::io::Result<()> {
    match kind {
        wire::REQUEST_PROTOCOL_VERSION => {
            let version = payload
                .get(..2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]))
                .unwrap_or(0);
            send(out, kind, &[u8::from(version == 1 || version == 2)])
        }
        wire::GET_URCONTROL_VERSION => {
            let (a, b, c, d) = shared.config.controller_version;
            let mut p = Vec::with_capacity(16);
            for v in [a, b, c, d] {
                p.extend_from_slice(&v.to_be_bytes());
            }
            send(out, kind, &p)
        }
        wire::SETUP_OUTPUTS => {
            let Some(freq_bytes) = payload.get(..8) else {
                return send(out, kind, &[0]);
            };
            let freq = f64::from_be_bytes(freq_bytes.try_into().unwrap_or([0; 8]));
            let names = parse_names(&payload[8..]);
            let types: Vec<Option<VarType>> = names.iter().map(|n| output_type(n)).collect();
            let ok = types.iter().all(Option::is_some) && freq.is_finite() && freq > 0.0;
            let listed: Vec<&str> = types
                .iter()
                .map(|t| t.map_or("NOT_FOUND", VarType::name))
                .collect();
            let mut reply = vec![u8::from(ok)];
            reply.extend_from_slice(listed.join(",").as_bytes());
            if ok {
                let freq = freq.min(shared.config.max_frequency_hz);
                session.output = Some((
                    names.into_iter().zip(types.into_iter().flatten()).collect(),
                    freq,
                ));
            }
            send(out, kind, &reply)
        }
        wire::SETUP_INPUTS => {
            if session.inputs.len() >= MAX_INPUT_RECIPES {
                return send(out, kind, b"\0");
            }
            let names = parse_names(payload);
            let claims = shared.claim_inputs(session.id, &names);
            let mut listed = Vec::with_capacity(names.len());
            let mut recipe = Vec::with_capacity(names.len());
            let mut ok = true;
            for (name, claimed) in names.iter().zip(claims) {
                match (input_type(name), claimed) {
                    (None, _) => {
                        ok = false;
                        listed.push("NOT_FOUND");
                    }
                    (Some(_), false) => {
                        ok = false;
                        listed.push("IN_USE");
                    }
                    (Some(t), true) => {
                        listed.push(t.name());
                        recipe.push((name.clone(), t));
                    }
                }
            }
            let id = if ok {
                session.inputs.push(recipe);
                u8::try_from(session.inputs.len()).unwrap_or(0)
            } else {
                0
            };
            let mut reply = vec![id];
            reply.extend_from_slice(listed.join(",").as_bytes());
            send(out, kind, &reply)
        }
        wire::START => {
            let Some((vars, freq)) = session.output.clone() else {
                return send(out, kind, &[0]);
            };
            // The reply goes out before the first data package: ur_rtde reads exactly one
            // package after START and takes it for the reply.
            send(out, kind, &[1])?;
            match session.mode {
                Streaming::Once => send_outputs(shared, out, &vars, &mut Vec::new()),
                Streaming::Thread if session.streaming.is_none() => {
                    let flag = Arc::new(AtomicBool::new(true));
                    session.streaming = Some(flag.clone());
                    let (shared, out) = (shared.clone(), out.clone());
                    shared
                        .clone()
                        .spawn(move || stream_outputs(&shared, &out, &vars, freq, &flag));
                    Ok(())
                }
                Streaming::Thread => Ok(()),
            }
        }
        wire::PAUSE => {
            if let Some(flag) = session.streaming.take() {
                flag.store(false, Ordering::SeqCst);
            }
            send(out, kind, &[1])
        }
        wire::DATA_PACKAGE => {
            let Some((&recipe_id, mut rest)) = payload.split_first() else {
                return Ok(());
            };
            let Some(recipe) = usize::from(recipe_id)
                .checked_sub(1)
                .and_then(|i| session.inputs.get(i))
            else {
                return text(out, &format!("unknown input recipe {recipe_id}"));
            };
            let need: usize = recipe.iter().map(|(_, t)| t.size()).sum();
            if rest.len() < need {
                return text(
                    out,
                    &format!(
                        "input package for recipe {recipe_id}: {} bytes, need {need}",
                        rest.len()
                    ),
                );
            }
            let mut c = shared.lock();
            for (name, ty) in recipe {
                let (bytes, tail) = rest.split_at(ty.size());
                c.set_input(name, Value::decode(*ty, bytes));
                rest = tail;
            }
            Ok(())
        }
        _ => text(out, &format!("unknown package type {kind}")),
    }
}

/// An RTDE text message (level 1 = error) back to the client.
fn text<W: Write>(out: &Mutex<W>, message: &str) -> std::io::Result<()> {
    let msg = &message.as_bytes()[..message.len().min(255)];
    let source = b"RTDE";
    let mut p = Vec::with_capacity(msg.len() + source.len() + 3);
    p.push(u8::try_from(msg.len()).unwrap_or(u8::MAX));
    p.extend_from_slice(msg);
    p.push(source.len() as u8);
    p.extend_from_slice(source);
    p.push(1);
    send(out, wire::TEXT_MESSAGE, &p)
}

/// One data package of the output recipe, read from the controller now.
fn send_outputs<W: Write>(
    shared: &Shared,
    out: &Mutex<W>,
    vars: &[(String, VarType)],
    payload: &mut Vec<u8>,
) -> std::io::Result<()> {
    payload.clear();
    payload.push(1); // output recipe id
    {
        let c = shared.lock();
        for (name, ty) in vars {
            output_value(&c, name, *ty).encode(payload);
        }
    }
    send(out, wire::DATA_PACKAGE, payload)?;
    out.lock().unwrap_or_else(|e| e.into_inner()).flush()
}

/// Sends the output recipe every `1/freq` s of simulated time while `flag` holds.
fn stream_outputs<W: Write>(
    shared: &Shared,
    out: &Mutex<W>,
    vars: &[(String, VarType)],
    freq: f64,
    flag: &AtomicBool,
) {
    // As many packages per control cycle at any time scale.
    let period = shared
        .config
        .time_scale
        .wall(Duration::from_secs_f64(1.0 / freq));
    let start = Instant::now();
    let mut n: u32 = 0;
    let mut payload = Vec::with_capacity(1 + vars.iter().map(|(_, t)| t.size()).sum::<usize>());
    while flag.load(Ordering::SeqCst) && !shared.stopped() {
        if send_outputs(shared, out, vars, &mut payload).is_err() {
            break;
        }
        n = n.wrapping_add(1);
        // Paced against the start so the rate does not drift with the send time.
        let due = start + period * n;
        if let Some(wait) = due.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
    }
}
