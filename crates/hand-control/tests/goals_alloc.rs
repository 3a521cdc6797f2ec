//! The servo hand's per-cycle bus calls allocate nothing once warm: `write_goals`,
//! `read_states_into` (a sync read into a caller's buffer), `torque_off_all`, and the
//! `GripperActuator` cycle built on them (`command` then `state`).
//!
//! # How the count is kept honest
//!
//! dhat's global allocator counts the heap blocks of *every* thread in the process, so whatever
//! answers the bus is counted too. `dxl-sim`'s simulated bus cannot be that answerer here: its
//! thread allocates for every packet it receives (`protocol::Parser::next_packet` unstuffs into a
//! fresh `Vec`, the simulator builds its reply in another, each status packet's data is a
//! `Vec`), a sync write included — so a window around `write_goals` would count the simulator's
//! blocks, and a strict zero would be impossible even for an allocation-free driver.
//!
//! The bus's far end is therefore a scripted responder on a pty pair (`SerialPort::pair`, as the
//! simulator uses): a thread that knows the exact bytes of every instruction this test sends
//! (built with `protocol::encode` before the thread starts) and answers PINGs and the SYNC READ
//! with status packets encoded up front. Its loop only reads into a stack buffer, compares bytes
//! and writes prepared slices: it allocates nothing, so every block counted in a window is the
//! driver's. The windows count *all* threads — nothing is excluded or subtracted — so the test
//! fails if `write_goals` (or any of the others) allocates even once in its window. A canary
//! window (one `Box`) checks that the counting allocator is really installed.
//!
//! The responder also counts the goal packets it receives and the status replies decode to
//! scripted values, one of them byte-stuffed on the wire (`FF FF FD` in Present Load /
//! Velocity), so the windows measure calls that did their work. A plain `main`, no test harness:
//! dhat counts every thread's blocks, the responder's included, so the responder allocates
//! nothing while it serves a window (it answers from prepared replies).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use hand_control::protocol::{encode, instruction_id, packet_id};
use hand_control::{RawGoals, RawServoState, ServoHand};
use hand_traits::{Effort, Faults, GripperActuator, GripperCommand};
use serial2::SerialPort;

#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

const IDS: [u8; 2] = [1, 2];
const WARM_UP: usize = 20;
const CALLS: usize = 200;
const STATUS: u8 = 0x55;
/// MX-28(2.0): model number 30, firmware 45 (as the simulator answers).
const MODEL: u16 = 30;

/// What the responder does when it has received a request's bytes.
enum Action {
    /// Writes these bytes back.
    Reply(Vec<u8>),
    /// Only counts the packet (a broadcast sync write has no answer).
    Count,
}

/// One instruction the responder recognises, and how many times it has seen it.
struct Rule {
    request: Vec<u8>,
    action: Action,
    seen: AtomicUsize,
}

/// The far end of the bus: matches requests byte for byte, answers from prepared bytes.
struct Responder {
    rules: Arc<Vec<Rule>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Responder {
    fn spawn(device: SerialPort, rules: Vec<Rule>) -> Self {
        let rules = Arc::new(rules);
        let stop = Arc::new(AtomicBool::new(false));
        let thread = {
            let (rules, stop) = (Arc::clone(&rules), Arc::clone(&stop));
            std::thread::spawn(move || respond(device, &rules, &stop))
        };
        Self {
            rules,
            stop,
            thread: Some(thread),
        }
    }

    /// How many times the rule whose request is `request` has fired.
    fn seen(&self, request: &[u8]) -> usize {
        self.rules
            .iter()
            .find(|r| r.request == request)
            .map_or(0, |r| r.seen.load(Ordering::SeqCst))
    }
}

impl Drop for Responder {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            t.join().expect("responder thread");
        }
    }
}

/// The responder's loop: no heap allocation anywhere in it (stack buffers, slice compares,
/// prepared replies; serial2's read / write and its timeout error allocate nothing).
fn respond(mut device: SerialPort, rules: &[Rule], stop: &AtomicBool) {
    device
        .set_read_timeout(Duration::from_millis(10))
        .expect("read timeout");
    let mut acc = [0u8; 4096];
    let mut len = 0;
    let mut chunk = [0u8; 512];
    while !stop.load(Ordering::SeqCst) {
        let n = match device.read(&mut chunk) {
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::TimedOut => continue,
            Err(_) => return,
        };
        if len + n > acc.len() {
            // Unmatched bytes piling up: keep the newest few (a request's start).
            acc.copy_within(len - 64..len, 0);
            len = 64;
        }
        acc[len..len + n].copy_from_slice(&chunk[..n]);
        len += n;
        // Requests in arrival order: the earliest match first.
        while let Some((at, rule)) = rules
            .iter()
            .filter_map(|r| {
                acc[..len]
                    .windows(r.request.len())
                    .position(|w| w == r.request.as_slice())
                    .map(|at| (at, r))
            })
            .min_by_key(|&(at, _)| at)
        {
            let end = at + rule.request.len();
            acc.copy_within(end..len, 0);
            len -= end;
            rule.seen.fetch_add(1, Ordering::SeqCst);
            if let Action::Reply(bytes) = &rule.action {
                if device.write_all(bytes).is_err() {
                    return;
                }
            }
        }
    }
}

fn packet(id: u8, instruction: u8, params: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    encode(&mut out, id, instruction, params);
    out
}

/// A broadcast SYNC WRITE of `value` (`width` bytes) to `address` of every servo in `IDS`.
fn sync_write(address: u16, width: u8, value: i32) -> Vec<u8> {
    let mut p = address.to_le_bytes().to_vec();
    p.extend_from_slice(&u16::from(width).to_le_bytes());
    for id in IDS {
        p.push(id);
        p.extend_from_slice(&value.to_le_bytes()[..usize::from(width)]);
    }
    packet(packet_id::BROADCAST, instruction_id::SYNC_WRITE, &p)
}

/// MX-28 state block: Present Load (126, 2 B), Present Velocity (128, 4 B), Present Position
/// (132, 4 B).
fn state_status(s: &RawServoState) -> Vec<u8> {
    let mut p = vec![if s.alert { 0x80 } else { 0 }];
    p.extend_from_slice(&(s.load as i16).to_le_bytes());
    p.extend_from_slice(&s.velocity.to_le_bytes());
    p.extend_from_slice(&s.position.to_le_bytes());
    packet(s.id, STATUS, &p)
}

/// Heap blocks allocated (by any thread) while `f` runs `CALLS` times.
fn blocks(mut f: impl FnMut()) -> u64 {
    let before = dhat::HeapStats::get().total_blocks;
    for _ in 0..CALLS {
        f();
    }
    dhat::HeapStats::get().total_blocks - before
}

fn bus_calls_allocate_nothing_once_warm() {
    let _profiler = dhat::Profiler::builder().testing().build();
    // The canary: the counting allocator is installed and a window sees a block.
    let canary = blocks(|| drop(std::hint::black_box(Box::new(7u64))));
    assert_eq!(canary, CALLS as u64, "dhat is not counting");

    let states = [
        RawServoState {
            id: 1,
            position: 2048,
            velocity: 12,
            load: 100,
            alert: false,
        },
        // Load −1 (FF FF) then velocity −3 (FD FF FF FF): FF FF FD on the wire gets a stuffing
        // FD that the driver must remove.
        RawServoState {
            id: 2,
            position: 1000,
            velocity: -3,
            load: -1,
            alert: false,
        },
    ];
    let goals = RawGoals {
        position: 2200,
        effort: 300,
    };
    let cmd = GripperCommand {
        position_rad: 3.5,
        effort: Effort::from_torque_limit_raw(400),
    };
    let cmd_goals =
        hand_control::encode_goals(&hand_control::control_table::MX_28, &cmd).expect("in range");
    let goal_packets =
        |g: &RawGoals| [sync_write(100, 2, g.effort), sync_write(116, 4, g.position)];
    let sync_read = {
        let mut p = vec![126, 0, 10, 0];
        p.extend_from_slice(&IDS);
        packet(packet_id::BROADCAST, instruction_id::SYNC_READ, &p)
    };
    let mut rules: Vec<Rule> = IDS
        .iter()
        .map(|&id| Rule {
            request: packet(id, instruction_id::PING, &[]),
            action: Action::Reply(packet(
                id,
                STATUS,
                &[0, MODEL.to_le_bytes()[0], MODEL.to_le_bytes()[1], 45],
            )),
            seen: AtomicUsize::new(0),
        })
        .collect();
    rules.push(Rule {
        request: sync_read.clone(),
        action: Action::Reply(states.iter().flat_map(state_status).collect()),
        seen: AtomicUsize::new(0),
    });
    let torque_off = sync_write(64, 1, 0);
    for request in goal_packets(&goals)
        .into_iter()
        .chain(goal_packets(&cmd_goals))
        .chain([torque_off.clone()])
    {
        rules.push(Rule {
            request,
            action: Action::Count,
            seen: AtomicUsize::new(0),
        });
    }

    let (device, client) = SerialPort::pair().expect("pty pair");
    let responder = Responder::spawn(device, rules);
    let mut hand =
        ServoHand::with_reply_latency(client, &IDS, Duration::from_secs(1)).expect("identify");
    let mut out = [RawServoState::default(); IDS.len()];
    for _ in 0..WARM_UP {
        hand.write_goals(&goals).expect("write");
        hand.torque_off_all().expect("torque off");
        hand.read_states_into(&mut out).expect("read");
        hand.command(&cmd).expect("command");
        hand.state().expect("state");
    }

    let write = blocks(|| hand.write_goals(&goals).expect("write"));
    let torque_off_blocks = blocks(|| hand.torque_off_all().expect("torque off"));
    let mut n = 0;
    let read = blocks(|| n = hand.read_states_into(&mut out).expect("read"));
    let mut faults = Faults::NONE;
    let cycle = blocks(|| {
        hand.command(&cmd).expect("command");
        faults = faults.union(hand.state().expect("state").faults);
    });
    println!(
        "blocks in {CALLS} calls after {WARM_UP}: write_goals {write}, torque_off_all \
         {torque_off_blocks}, read_states_into {read}, command + state {cycle}"
    );

    // The calls did their work: every packet reached the far end, the replies decoded.
    assert_eq!(n, IDS.len());
    assert_eq!(out, states);
    assert!(faults.is_empty());
    let total = WARM_UP + CALLS;
    for p in goal_packets(&goals) {
        assert_eq!(responder.seen(&p), total, "goal packets sent");
    }
    for p in goal_packets(&cmd_goals) {
        assert_eq!(responder.seen(&p), total, "command packets sent");
    }
    assert_eq!(responder.seen(&torque_off), total);
    assert_eq!(responder.seen(&sync_read), 2 * total);

    assert_eq!(
        write, 0,
        "write_goals allocated {write} blocks in {CALLS} calls"
    );
    assert_eq!(
        torque_off_blocks, 0,
        "torque_off_all allocated {torque_off_blocks} blocks in {CALLS} calls"
    );
    assert_eq!(
        read, 0,
        "read_states_into allocated {read} blocks in {CALLS} calls"
    );
    assert_eq!(
        cycle, 0,
        "command + state allocated {cycle} blocks in {CALLS} calls"
    );
}

// No libtest harness (`harness = false`): its main thread allocates (the running-test table, the
// timeout queue) while a test thread runs, and dhat counts every thread's blocks.
fn main() {
    bus_calls_allocate_nothing_once_warm();
    println!("bus_calls_allocate_nothing_once_warm: ok");
}
