//! The simulator under load and abuse: many rapidly reconnecting clients, clients that vanish
//! mid-move, garbage on every port. Raw TCP clients (bounded: a timeout on every read and
//! write, a fixed number of connections), then a fresh `UrArm` to show the simulator is
//! still up; a controller that accepts connections and never answers is a typed timeout, not a
//! hang; an input register is one open connection's at a time. Loopback addresses 127.0.0.23–24,
//! 27–28 and 31–33 (off the other tests').

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, Shutdown, SocketAddr, TcpStream};
use std::time::{Duration, Instant};

use ur_bridge::kinematics::{self, UrModel};
use ur_bridge::{LinearMotion, UrArm, UrConfig};
use ur_sim::{SimConfig, UrSim};

use crate::grid::Grid;

/// Every read, write and connect of a raw client.
const IO_TIMEOUT: Duration = Duration::from_secs(5);
/// Every wait for the simulator to get somewhere.
const WAIT: Duration = Duration::from_secs(10);

const PROTOCOL_VERSION: u8 = b'V';
const SETUP_INPUTS: u8 = b'I';
const SETUP_OUTPUTS: u8 = b'O';
const START: u8 = b'S';
const DATA_PACKAGE: u8 = b'U';
const TEXT_MESSAGE: u8 = b'M';

fn connect(addr: SocketAddr) -> TcpStream {
    let s = TcpStream::connect_timeout(&addr, IO_TIMEOUT).expect("connect");
    s.set_read_timeout(Some(IO_TIMEOUT)).unwrap();
    s.set_write_timeout(Some(IO_TIMEOUT)).unwrap();
    // Each package goes out when written, as ur_rtde sends them (no Nagle coalescing).
    s.set_nodelay(true).unwrap();
    s
}

fn package(kind: u8, payload: &[u8]) -> Vec<u8> {
    let size = u16::try_from(payload.len() + 3).expect("small");
    let mut p = size.to_be_bytes().to_vec();
    p.push(kind);
    p.extend_from_slice(payload);
    p
}

fn read_package(s: &mut impl Read) -> (u8, Vec<u8>) {
    let mut header = [0_u8; 3];
    s.read_exact(&mut header).expect("a package header");
    let size = usize::from(u16::from_be_bytes([header[0], header[1]]));
    let mut payload = vec![0; size - 3];
    s.read_exact(&mut payload).expect("a package payload");
    (header[2], payload)
}

/// The text of an RTDE text message (length-prefixed message, source, level).
fn message_text(payload: &[u8]) -> String {
    let n = usize::from(payload[0]);
    String::from_utf8_lossy(&payload[1..1 + n]).into_owned()
}

/// Deterministic bytes (a 64-bit LCG), so every run sends the same garbage.
fn garbage(len: usize, mut seed: u64) -> Vec<u8> {
    (0..len)
        .map(|_| {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 56) as u8
        })
        .collect()
}

/// Polls `done` until it holds, bounded by [`WAIT`].
fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < WAIT, "waited {WAIT:?} for {what}");
        std::thread::yield_now();
    }
}

/// Waits `dt_s` of controller time, bounded.
fn wait_controller(sim: &UrSim, dt_s: f64) {
    let t0 = sim.controller_time_s();
    wait_for("the controller clock", || {
        sim.controller_time_s() >= t0 + dt_s
    });
}

fn on_real_ports(octet: u8) -> UrSim {
    UrSim::start(SimConfig {
        address: Ipv4Addr::new(127, 0, 0, octet),
        ..SimConfig::default()
    })
    .expect("bind the simulator")
}

/// A simulator on 127.0.0.`octet` at ports the system picks (for raw clients, not ur_rtde).
fn on_any_ports(octet: u8) -> UrSim {
    UrSim::start(SimConfig {
        address: Ipv4Addr::new(127, 0, 0, octet),
        dashboard_port: 0,
        script_port: 0,
        rtde_port: 0,
        ..SimConfig::default()
    })
    .expect("bind the simulator")
}

/// A fresh ur_rtde client connects, reads the state and moves: the simulator is still up.
fn fresh_client_works(sim: &UrSim, octet: u8) {
    wait_for("every abusive connection to close", || {
        sim.connections() == 0
    });
    let mut config = UrConfig::new(format!("127.0.0.{octet}"));
    config.move_timeout = Duration::from_secs(20);
    let mut arm =
        UrArm::connect(config).unwrap_or_else(|e| panic!("connect: {e}; log {:?}", sim.log()));
    assert!(
        arm.status().unwrap().is_program_running(),
        "{:?}",
        sim.log()
    );
    let grid = Grid::ur3();
    let fast = LinearMotion {
        speed_m_per_s: 0.5,
        accel_m_per_s2: 2.0,
    };
    arm.move_linear(grid.pose(4), &fast)
        .unwrap_or_else(|e| panic!("moveL: {e}; log {:?}", sim.log()));
    assert!(arm.tool_pose().unwrap().distance_m(grid.pose(4)) < 1e-4);
}

#[test]
fn sixteen_clients_reconnecting_twenty_times_each_are_all_served() {
    const CLIENTS: usize = 16;
    const RECONNECTS: usize = 20;
    let sim = on_real_ports(23);
    let [dashboard, script, rtde]: [SocketAddr; 3] = sim.addresses().try_into().unwrap();
    let workers: Vec<_> = (0..CLIENTS)
        .map(|client| {
            std::thread::spawn(move || {
                for round in 0..RECONNECTS {
                    let d = connect(dashboard);
                    let mut lines = BufReader::new(d.try_clone().unwrap());
                    let mut line = String::new();
                    lines.read_line(&mut line).unwrap();
                    assert_eq!(line, "Connected: Universal Robots Dashboard Server\n");
                    (&d).write_all(b"robotmode\n").unwrap();
                    line.clear();
                    lines.read_line(&mut line).unwrap();
                    assert_eq!(
                        line, "Robotmode: RUNNING\n",
                        "client {client} round {round}"
                    );

                    let mut r = connect(rtde);
                    r.write_all(&package(PROTOCOL_VERSION, &[0, 2])).unwrap();
                    assert_eq!(read_package(&mut r), (PROTOCOL_VERSION, vec![1]));

                    // Half a program, then gone.
                    let mut s = connect(script);
                    s.write_all(b"def half():\n  textmsg(\"no end\")\n")
                        .unwrap();
                }
            })
        })
        .collect();
    for w in workers {
        w.join().expect("a client failed");
    }
    fresh_client_works(&sim, 23);
}

#[test]
fn garbage_on_every_port_is_reported_or_dropped_and_the_simulator_stays_up() {
    let sim = on_real_ports(24);
    let [dashboard, script, rtde]: [SocketAddr; 3] = sim.addresses().try_into().unwrap();

    // Dashboard: garbage lines are answered as unknown commands, the connection stays usable.
    let mut d = connect(dashboard);
    let mut lines: Vec<u8> = garbage(8 * 1024, 1)
        .into_iter()
        .map(|b| if b == b'\n' { b' ' } else { b })
        .collect();
    for i in (0..lines.len()).step_by(1000).skip(1) {
        lines[i] = b'\n';
    }
    lines.extend_from_slice(b"\nrobotmode\n");
    d.write_all(&lines).unwrap();
    d.shutdown(Shutdown::Write).unwrap();
    let mut reply = String::new();
    BufReader::new(&d).read_to_string(&mut reply).unwrap();
    assert!(reply.starts_with("Connected: "), "{reply}");
    assert_eq!(
        reply.matches("could not understand: ").count(),
        9,
        "{reply}"
    );
    assert!(reply.ends_with("Robotmode: RUNNING\n"), "{reply}");
    // A line longer than any command: said, and the connection ends.
    let mut d = connect(dashboard);
    let _ = d.write_all(&[b'x'; 5_000]);
    let mut reply = String::new();
    let _ = BufReader::new(&d).read_to_string(&mut reply);
    assert!(
        reply.ends_with("could not understand: a line over 4096 bytes\nDisconnected\n"),
        "{reply}"
    );

    // RTDE: an unknown package type and an unknown input recipe are answered with a text
    // message; a header that cannot be framed is said and the connection closes.
    let mut r = connect(rtde);
    r.write_all(&package(1, &garbage(300, 2))).unwrap();
    let (kind, payload) = read_package(&mut r);
    assert_eq!(kind, TEXT_MESSAGE);
    assert_eq!(message_text(&payload), "unknown package type 1");
    r.write_all(&package(DATA_PACKAGE, &[9, 1, 2, 3])).unwrap();
    let (kind, payload) = read_package(&mut r);
    assert_eq!(
        (kind, message_text(&payload)),
        (TEXT_MESSAGE, "unknown input recipe 9".into())
    );
    r.write_all(&[0, 1, b'X']).unwrap();
    let (kind, payload) = read_package(&mut r);
    assert_eq!(kind, TEXT_MESSAGE);
    assert!(message_text(&payload).contains("closing the connection"));
    let mut rest = Vec::new();
    assert_eq!(r.read_to_end(&mut rest).unwrap(), 0, "closed");
    // Raw garbage, then the client goes: whatever it framed is answered or dropped.
    let mut r = connect(rtde);
    let _ = r.write_all(&garbage(64 * 1024, 3));
    let _ = r.shutdown(Shutdown::Write);
    let _ = r.read_to_end(&mut Vec::new());

    // Script: what is not ur_rtde's control script is logged and not run; a program with no
    // end is dropped once it outgrows the intake's bound.
    let mut s = connect(script);
    s.write_all(&garbage(4 * 1024, 4)).unwrap();
    s.write_all(b"\ndef not_rtde_control():\n  movej([0,0,0,0,0,0])\nend\n")
        .unwrap();
    drop(s);
    wait_for("the script log", || {
        sim.log()
            .iter()
            .any(|l| l.starts_with("script not run: not ur_rtde's control script"))
    });
    let mut s = connect(script);
    let chunk = vec![b'#'; 64 * 1024];
    for _ in 0..(2 << 20) / chunk.len() {
        if s.write_all(&chunk).is_err() {
            break; // the intake dropped the connection
        }
    }
    drop(s);
    wait_for("the intake to drop the endless program", || {
        sim.log()
            .iter()
            .any(|l| l.starts_with("script intake: over 1048576 bytes"))
    });

    fresh_client_works(&sim, 24);
}

/// A client of ur_rtde's register protocol over raw RTDE, which can vanish without a goodbye
/// (no `stopScript`, as when its process is killed).
struct RawControl {
    rtde: TcpStream,
}

/// ur_rtde's command numbers and the async flag this test sends.
const MOVEL: i32 = 3;
const SET_WATCHDOG: i32 = 35;

impl RawControl {
    /// Uploads a control script the simulator recognises, sets up one input recipe (command,
    /// async flag, eight doubles) and streams the script's handshake register.
    fn connect(sim: &UrSim) -> Self {
        let [_, script, rtde]: [SocketAddr; 3] = sim.addresses().try_into().unwrap();
        let mut r = connect(rtde);
        r.write_all(&package(PROTOCOL_VERSION, &[0, 2])).unwrap();
        assert_eq!(read_package(&mut r), (PROTOCOL_VERSION, vec![1]));
        let mut outputs = 125.0_f64.to_be_bytes().to_vec();
        outputs.extend_from_slice(b"output_int_register_0");
        r.write_all(&package(SETUP_OUTPUTS, &outputs)).unwrap();
        assert_eq!(read_package(&mut r), (SETUP_OUTPUTS, b"\x01INT32".to_vec()));
        let names: Vec<String> = ["input_int_register_0", "input_int_register_1"]
            .into_iter()
            .map(String::from)
            .chain((0..8).map(|i| format!("input_double_register_{i}")))
            .collect();
        r.write_all(&package(SETUP_INPUTS, names.join(",").as_bytes()))
            .unwrap();
        let (kind, reply) = read_package(&mut r);
        assert_eq!((kind, reply[0]), (SETUP_INPUTS, 1), "recipe 1");
        r.write_all(&package(START, &[])).unwrap();
        assert_eq!(read_package(&mut r), (START, vec![1]));
        let mut s = connect(script);
        s.write_all(
            b"def rtde_control():\n# HEADER_BEGIN\n    global reg_offset_int = # int register offset\n0\n    def signal_ready():\n    def process_cmd(cmd):\nend\n",
        )
        .unwrap();
        wait_for("the control script", || {
            sim.log().iter().any(|l| l == "RTDE Control Script Loaded")
        });
        Self { rtde: r }
    }

    fn send(&mut self, cmd: i32, asynchronous: bool, args: [f64; 8]) {
        let mut p = vec![1_u8];
        p.extend_from_slice(&cmd.to_be_bytes());
        p.extend_from_slice(&i32::from(asynchronous).to_be_bytes());
        for a in args {
            p.extend_from_slice(&a.to_be_bytes());
        }
        self.rtde.write_all(&package(DATA_PACKAGE, &p)).unwrap();
    }

    /// Reads the stream until `output_int_register_0` is `want` (1 ready, 2 done), bounded.
    fn wait_register(&mut self, want: i32) {
        let start = Instant::now();
        loop {
            let (kind, payload) = read_package(&mut self.rtde);
            if kind == DATA_PACKAGE && i32::from_be_bytes(payload[1..5].try_into().unwrap()) == want
            {
                return;
            }
            assert!(start.elapsed() < WAIT, "register 0 never read {want}");
        }
    }

    /// ur_rtde's handshake: the command until the script says done, then "no command" until
    /// it says ready.
    fn command(&mut self, cmd: i32, args: [f64; 8]) {
        self.send(cmd, false, args);
        self.wait_register(2);
        self.send(0, false, [0.0; 8]);
        self.wait_register(1);
    }

    /// A slow asynchronous moveL to `target`, returned once the arm moves.
    fn start_move(&mut self, sim: &UrSim, target: &ur_bridge::Pose, speed: f64) {
        let q0 = sim.joints();
        let p = target.position_m;
        let r = target.rotation_vec_rad;
        self.send(
            MOVEL,
            true,
            [p[0], p[1], p[2], r[0], r[1], r[2], speed, 1.0],
        );
        self.wait_register(2);
        let start = Instant::now();
        while sim.joints() == q0 {
            assert!(
                start.elapsed() < WAIT,
                "the move did not start: {:?}",
                sim.log()
            );
            std::thread::yield_now();
        }
    }
}

fn tcp(sim: &UrSim) -> ur_bridge::Pose {
    kinematics::to_pose(&UrModel::ur3().forward(&sim.joints()))
}

/// Whether the joints stay put over 50 ms of controller time.
fn at_rest(sim: &UrSim) -> bool {
    let q = sim.joints();
    wait_controller(sim, 0.05);
    sim.joints() == q
}

#[test]
fn a_client_vanishing_mid_move_without_a_watchdog_leaves_the_move_to_finish() {
    // As on a real controller: nothing in ur_rtde's script notices a client that went, so the
    // running move ends at its target and the arm rests there.
    let sim = on_any_ports(27);
    let target = *Grid::ur3().pose(0);
    let mut client = RawControl::connect(&sim);
    client.start_move(&sim, &target, 0.25);
    drop(client);
    wait_for("the move to end at its target", || {
        tcp(&sim).distance_m(&target) < 1e-4
    });
    // The last cycles of the ramp, then still.
    wait_controller(&sim, 0.05);
    assert!(at_rest(&sim), "{:?}", sim.log());
    assert!(
        sim.log().iter().all(|l| !l.contains("protective stop")),
        "{:?}",
        sim.log()
    );
}

#[test]
fn a_client_vanishing_mid_move_with_a_watchdog_stops_the_arm() {
    const WATCHDOG_HZ: f64 = 2.0;
    let sim = on_any_ports(28);
    let target = *Grid::ur3().pose(0);
    let mut client = RawControl::connect(&sim);
    client.command(
        SET_WATCHDOG,
        [WATCHDOG_HZ, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    );
    assert!(
        sim.log()
            .iter()
            .any(|l| l == "rtde_set_watchdog(\"input_int_register_0\", 2, \"stop\")"),
        "{:?}",
        sim.log()
    );
    // 0.14 m at 2 cm/s: seven seconds, of which the watchdog lets half a second pass.
    client.start_move(&sim, &target, 0.02);
    drop(client);
    const SAID: &str = "RTDE watchdog: input_int_register_0 not updated for ";
    let mut line = None;
    wait_for("the watchdog", || {
        line = sim.log().into_iter().find(|l| l.starts_with(SAID));
        line.is_some()
    });
    assert!(at_rest(&sim), "{:?}", sim.log());
    // Stopped within one control cycle past its period, short of the target.
    let line = line.unwrap_or_default();
    let silent_s: f64 = line[SAID.len()..]
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!(silent_s <= 1.0 / WATCHDOG_HZ + 0.008 + 1e-9, "{line}");
    assert!(line.ends_with("program stopped"), "{line}");
    assert!(tcp(&sim).distance_m(&target) > 0.1, "{:?}", tcp(&sim));
}

/// A controller at 127.0.0.`octet` that accepts on 29999, 30003 and 30004 and never answers,
/// except that the dashboard greets when `greet`. Its threads hold every connection until the
/// test process ends (bounded: 8 accepts a port).
fn silent_controller(octet: u8, greet: bool) {
    for port in [29999, 30003, 30004] {
        let listener = std::net::TcpListener::bind((Ipv4Addr::new(127, 0, 0, octet), port))
            .expect("bind the silent controller");
        std::thread::spawn(move || {
            let mut held = Vec::new();
            for stream in listener.incoming().take(8).flatten() {
                if greet && port == 29999 {
                    let _ = (&stream).write_all(b"Connected: Universal Robots Dashboard Server\n");
                }
                held.push(stream);
            }
            std::thread::sleep(Duration::from_secs(600));
        });
    }
}

/// `UrArm::connect` to 127.0.0.`octet` on another thread; its result, or a panic after 30 s
/// (a hang fails the test instead of stalling the suite).
fn connect_bounded(octet: u8) -> (Result<UrArm, ur_bridge::UrError>, Duration) {
    let (tx, rx) = std::sync::mpsc::channel();
    let start = Instant::now();
    std::thread::spawn(move || {
        let _ = tx.send(UrArm::connect(UrConfig::new(format!("127.0.0.{octet}"))));
    });
    let result = rx
        .recv_timeout(Duration::from_secs(30))
        .expect("UrArm::connect hung past 30 s against a silent controller");
    (result, start.elapsed())
}

#[test]
fn a_controller_that_accepts_and_never_answers_is_a_timeout_not_a_hang() {
    // Nothing answers: ur_rtde's dashboard client gives up on the greeting after its 2 s.
    silent_controller(31, false);
    let (result, took) = connect_bounded(31);
    match result {
        Err(ur_bridge::UrError::Timeout { what, .. }) => {
            assert!(what.contains("dashboard"), "{what}")
        }
        other => panic!(
            "expected a dashboard timeout, got {:?}",
            other.map(|_| "an arm")
        ),
    }
    assert!(took < Duration::from_secs(10), "{took:?}");
    // The dashboard greets, RTDE accepts and never answers: ur_rtde alone waits forever
    // there; the bridge's own bounded handshake says so in 2 s.
    silent_controller(32, true);
    let (result, took) = connect_bounded(32);
    match result {
        Err(e @ ur_bridge::UrError::Timeout { .. }) => {
            assert!(e.to_string().contains("RTDE handshake (port 30004)"), "{e}")
        }
        other => panic!(
            "expected an RTDE timeout, got {:?}",
            other.map(|_| "an arm")
        ),
    }
    assert!(took < Duration::from_secs(10), "{took:?}");
}

/// Sets up an RTDE input recipe of `input_int_register_0` on a new raw connection to `rtde`;
/// the recipe id the simulator answers (0: refused) and the variable types it lists.
fn claim_register(rtde: SocketAddr) -> (TcpStream, u8, String) {
    let mut r = connect(rtde);
    r.write_all(&package(PROTOCOL_VERSION, &[0, 2])).unwrap();
    assert_eq!(read_package(&mut r), (PROTOCOL_VERSION, vec![1]));
    r.write_all(&package(SETUP_INPUTS, b"input_int_register_0"))
        .unwrap();
    let (kind, reply) = read_package(&mut r);
    assert_eq!(kind, SETUP_INPUTS);
    let listed = String::from_utf8_lossy(&reply[1..]).into_owned();
    (r, reply[0], listed)
}

/// An input register is one connection's while it is open (the real controller answers
/// `IN_USE` to a second client, and ur_rtde then throws), and free once that connection has
/// closed: a client that drops its connection and sets up the same recipe on a new one at once
/// gets it, however late the simulator reads the close.
#[test]
fn an_input_register_is_in_use_while_its_connection_is_open_and_free_once_closed() {
    let sim = on_any_ports(33);
    let [_, _, rtde]: [SocketAddr; 3] = sim.addresses().try_into().unwrap();
    let (first, id, listed) = claim_register(rtde);
    assert_eq!((id, listed.as_str()), (1, "INT32"));
    let (_second, id, listed) = claim_register(rtde);
    assert_eq!((id, listed.as_str()), (0, "IN_USE"));
    assert!(
        sim.log()
            .iter()
            .any(|l| l.contains("input_int_register_0") && l.ends_with("IN_USE")),
        "{:?}",
        sim.log()
    );
    // Closed, then claimed again at once from a new connection, twenty times over.
    drop(first);
    for round in 0..20 {
        let (again, id, listed) = claim_register(rtde);
        assert_eq!((id, listed.as_str()), (1, "INT32"), "round {round}");
        again.shutdown(Shutdown::Both).unwrap();
    }
}
