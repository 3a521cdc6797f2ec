//! The barometric fingertip on an Arduino's I2C (`[sensors.fingertip] firmata_port`): three
//! MS5611 behind a TCA9548A switch at 0x70, channels 0, 1 and 2, on the workspace's
//! `firmata-sim` as its own process (a Mega 2560 running ConfigurableFirmata on a pty), the
//! scene naming its pty as it would /dev/ttyACM0. The built `handstack run` reads each sensor's
//! pressure through the board and the switch; a board without the switch, or a channel
//! without its sensor, is a plain-words "cannot open" error and exit status 1; and the frame
//! rate through the board is measured at 57 600 and 115 200 baud against the grasp loop's
//! 100 Hz.

use crate::process::{FirmataSim, finish, text};
use baro_drivers::{Address, Osr};
use hand_traits::{PressureFrame, TactileSource};
use handstack::RunError;
use handstack::scene::Scene;
use handstack::stack::fingertip::RealFingertip;
use handstack::stack::platform::LinuxPlatform;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The three sensors' pressures the board is started with, mbar (`--fingertip-mbar`).
const MBAR: [f64; 3] = [1000.0, 1010.0, 1020.0];
/// `firmata-sim` arguments for a board with the fingertip at [`MBAR`] and no ICM-20789.
const TIP: [&str; 5] = ["--no-imu", "--fingertip-mbar", "1000", "1010", "1020"];

/// The fingertip node (`handstack node --part fingertip`) on the board publishes each frame
/// of the three sensors as it reads them.
#[cfg(feature = "cell")]
#[test]
fn a_fingertip_node_publishes_the_pressures_read_through_the_board() {
    use hand_zenoh::config::SessionConfig;
    use hand_zenoh::msg::handstack_msgs::PressureFrame;
    use hand_zenoh::node::{Node, NodeOptions, Router};

    let sim = FirmataSim::with_args(&TIP);
    let dir = temp("node");
    let scene = dir.join("tip.toml");
    std::fs::write(
        &scene,
        format!(
            "title = \"fingertip node\"\n[sensors.fingertip]\nosr = 1024\n\
             firmata_port = \"{}\"\n",
            sim.path
        ),
    )
    .expect("scene");
    let (_router, endpoint) = Router::open_on_loopback().expect("the router");
    let mut options = NodeOptions::new("/cell", "listener");
    options.session = SessionConfig::peer(&endpoint);
    let listener = Node::open(options).expect("the listener");
    let mut raw = listener
        .subscription::<PressureFrame>("/tip0/tactile/raw", 64)
        .expect("raw subscription");
    let mut node = Command::new(env!("CARGO_BIN_EXE_handstack"))
        .arg("node")
        .arg(&scene)
        .args(["--part", "fingertip", "--namespace", "/tip0"])
        .args(["--connect", &endpoint])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack node starts");
    let stdin = node.stdin.take().expect("stdin");
    for _ in 0..3 {
        let p = raw
            .recv_timeout(Duration::from_secs(20))
            .expect("raw subscription")
            .expect("a pressure frame from the node")
            .message;
        assert_eq!(p.pressure_pa.len(), 3, "{p:?}");
        for (k, mbar) in MBAR.iter().enumerate() {
            // OSR 1024: 2.7 Pa rms.
            let got = f64::from(p.pressure_pa[k]);
            assert!((got - mbar * 100.0).abs() < 20.0, "sensor {}: {p:?}", k + 1);
        }
    }
    // Closing stdin is the node's normal stop.
    drop(stdin);
    let out = finish(node);
    let _ = std::fs::remove_dir_all(dir);
    assert!(
        out.status.success(),
        "{:?}: {}",
        out.status,
        text(&out.stderr)
    );
}

/// A fresh directory for one test's scene.
fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("handstack-tip-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// A readout scene of `frames` frames on the fingertip at `port` (`extra`: more of its keys).
fn readout_scene(dir: &Path, port: &str, frames: usize, extra: &str) -> PathBuf {
    let scene = dir.join("tip.toml");
    std::fs::write(
        &scene,
        format!(
            "title = \"fingertip on a board\"\n[sensors.fingertip]\nosr = 1024\n\
             firmata_port = \"{port}\"\n{extra}[experiment.readout]\nframes = {frames}\n"
        ),
    )
    .expect("scene");
    scene
}

/// `handstack run --json SCENE`, to its end (bounded): exit status, stdout, stderr.
fn handstack_run(scene: &Path) -> (Option<i32>, String, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_handstack"))
        .arg("run")
        .arg("--json")
        .arg(scene)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack run starts");
    let out = finish(child);
    (out.status.code(), text(&out.stdout), text(&out.stderr))
}

/// The most frames per second the board's line allows at `baud` and `osr`, per frame of the
/// driver's scheduler through the switch, each message on the line one after the other (10
/// bits a byte; a one-byte I2C write is 7 bytes of Firmata, a read request 7, a 3-byte reply
/// 13, a 1-byte reply 9):
/// - the D2 starts: three channel selections and three commands (6 writes); then the wait,
///   begun with a round trip to the board (the switch's control byte: 7 out, 9 back) and
///   lasting the longest conversion time;
/// - per sensor, its selection, the ADC command, the read request and its reply, then the D1
///   start (7 + 7 + 7 + 13 + 7); the wait again (round trip and conversion);
/// - per sensor, its selection, the ADC command, the read request and its reply;
/// - and the board's I2C reads at 100 kHz (six ADC reads of 40 bit times, two control-byte
///   reads of 22), which no line transfer overlaps: each reply goes after its read.
fn line_bound_hz(baud: f64, osr: Osr) -> f64 {
    let byte = 10.0 / baud;
    let wait = f64::from(osr.conversion_time_max_ns()) * 1e-9;
    let round_trip = 7.0 + 9.0;
    let bytes = 6.0 * 7.0
        + round_trip
        + 3.0 * (7.0 + 7.0 + 7.0 + 13.0 + 7.0)
        + round_trip
        + 3.0 * (7.0 + 7.0 + 7.0 + 13.0);
    let i2c = (6.0 * 40.0 + 2.0 * 22.0) / 100_000.0;
    1.0 / (bytes * byte + 2.0 * wait + i2c)
}

#[test]
fn a_readout_through_the_board_and_its_switch_gives_each_sensors_pressure() {
    let sim = FirmataSim::with_args(&TIP);
    let dir = temp("readout");
    let frames = 30;
    let scene = readout_scene(&dir, &sim.path, frames, "");
    let (code, out, err) = handstack_run(&scene);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, Some(0), "{err}");
    let outcomes: serde_json::Value = serde_json::from_str(&out).expect("JSON on stdout");
    let figure = |name: &str| -> f64 {
        outcomes[0]["figures"]
            .as_array()
            .and_then(|f| f.iter().find(|f| f["name"] == name))
            .and_then(|f| f["value"].as_f64())
            .unwrap_or_else(|| panic!("no figure {name} in {out}"))
    };
    assert_eq!(figure("frames"), frames as f64);
    for (k, mbar) in MBAR.iter().enumerate() {
        let mean = figure(&format!("sensor{}_mean_pa", k + 1));
        let sd = figure(&format!("sensor{}_sd_pa", k + 1));
        // The chip model's noise at OSR 1024 is 2.7 Pa rms (datasheet's 0.027 mbar), so the
        // mean of 30 frames is within 1 Pa of the truth, and the compensation rounds to 1 Pa:
        // 5 Pa is a bound no sensor on another channel (10 hPa away) could meet.
        assert!(
            (mean - mbar * 100.0).abs() < 5.0,
            "sensor {}: {mean} Pa, {} Pa expected",
            k + 1,
            mbar * 100.0
        );
        assert!(sd < 10.0, "sensor {}: sd {sd} Pa", k + 1);
    }
    // The period is at least what the line allows (a bound however loaded the machine), and
    // not more than twice that.
    let period_ms = figure("frame_period_ms");
    let least_ms = 1e3 / line_bound_hz(57_600.0, Osr::Osr1024);
    assert!(
        period_ms >= least_ms * 0.98 && period_ms <= least_ms * 2.5,
        "frame period {period_ms} ms, the line's least {least_ms} ms"
    );
}

/// The first `error:` line of `handstack run` on a readout scene whose board was started with
/// `sim_args` (`extra`: more of the fingertip's keys); the exit status must be 1.
fn cannot_open(name: &str, sim_args: &[&str], extra: &str) -> (String, String) {
    let sim = FirmataSim::with_args(sim_args);
    let dir = temp(name);
    let scene = readout_scene(&dir, &sim.path, 10, extra);
    let (code, _, err) = handstack_run(&scene);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, Some(1), "{err}");
    let line = err
        .lines()
        .find(|l| l.starts_with("error:"))
        .unwrap_or_else(|| panic!("no error line: {err}"))
        .to_owned();
    assert!(
        !line.contains("Kind") && !line.contains('{') && !line.contains("Some("),
        "{line}"
    );
    (line, sim.path.clone())
}

#[test]
fn a_board_without_the_fingertip_is_a_cannot_open_error() {
    let (line, port) = cannot_open("no-tip", &["--no-fingertips"], "");
    // The switch's read back is not acknowledged: the board's I2C NACK, in words.
    assert!(
        line.contains(&format!(
            "cannot open sensors.fingertip at {port}: no TCA9548A I2C switch answers at 0x70 \
             (the three MS5611 sit behind one): board on {port}: I2C device 0x70: no answer \
             (NACK: 0 of 1 bytes came back)"
        )),
        "{line}"
    );
}

#[test]
fn a_channel_without_its_sensor_is_a_cannot_open_error_naming_it() {
    // The board's switch has sensors on channels 0, 1 and 2; the scene says 0, 1 and 3.
    let (line, port) = cannot_open("no-sensor", &TIP, "mux_channels = [0, 1, 3]\n");
    assert!(
        line.contains(&format!(
            "cannot open sensors.fingertip at {port}: MS5611 of sensor 3 at 0x77 on switch \
             channel 3: bus error: board on {port}: I2C device 0x77: no answer (NACK: 0 of 2 \
             bytes came back)"
        )),
        "{line}"
    );
}

#[test]
fn a_switch_at_another_address_is_a_cannot_open_error() {
    let (line, port) = cannot_open("mux-address", &TIP, "mux_address = 0x71\n");
    assert!(
        line.contains(&format!(
            "cannot open sensors.fingertip at {port}: no TCA9548A I2C switch answers at 0x71"
        )),
        "{line}"
    );
}

/// The scene keys: a board in place of the buses, its switch's keys only with it, and each
/// error at its key's line and column.
#[test]
fn scene_keys_name_the_board_and_its_switch() {
    let tip = |keys: &str| {
        format!(
            "title = \"t\"\n[sensors.fingertip]\nosr = 1024\n{keys}[experiment.readout]\n\
             frames = 10\n"
        )
    };
    let scene = Scene::parse(
        "tip.toml",
        &tip(
            "firmata_port = \"/dev/ttyACM0\"\nfirmata_baud = 115200\nmux_address = 0x74\n\
              mux_channels = [7, 0, 3]\n",
        ),
    )
    .expect("a board's fingertip");
    let wiring = scene
        .file
        .sensors
        .fingertip
        .as_ref()
        .and_then(|t| t.get_ref().wiring());
    assert_eq!(
        wiring,
        Some(handstack::scene::parts::FingertipWiring::Firmata {
            port: "/dev/ttyACM0",
            baud: 115_200,
            mux_address: 0x74,
            mux_channels: &[7, 0, 3],
        })
    );
    let err = |keys: &str| {
        Scene::parse("tip.toml", &tip(keys))
            .map(drop)
            .expect_err("a bad fingertip")
            .to_string()
    };
    let buses = "i2c_buses = [\"/dev/i2c-1\", \"/dev/i2c-3\", \"/dev/i2c-4\"]\n";
    assert_eq!(
        err(&format!("{buses}firmata_port = \"/dev/ttyACM0\"\n")),
        "tip.toml:5:16: `sensors.fingertip.firmata_port` is named beside `i2c_buses`; allowed: \
         one of `i2c_buses` (three I2C buses of this computer) or `firmata_port` (the serial \
         port of a Firmata board the sensors are wired to, behind a TCA9548A switch)"
    );
    assert_eq!(
        err(&format!("{buses}mux_channels = [0, 1, 2]\n")),
        "tip.toml:5:16: `sensors.fingertip.mux_channels` is named without `firmata_port`; \
         allowed: `mux_channels` only with the board's `firmata_port`"
    );
    assert_eq!(
        err(&format!("{buses}firmata_baud = 57600\n")),
        "tip.toml:5:16: `sensors.fingertip.firmata_baud` is named without `firmata_port`; \
         allowed: `firmata_baud` only with the board's `firmata_port`"
    );
    let port = "firmata_port = \"/dev/ttyACM0\"\n";
    assert_eq!(
        err(&format!("{port}firmata_baud = 56000\n")),
        "tip.toml:5:16: `sensors.fingertip.firmata_baud` is 56000; allowed: a Firmata sketch's \
         baud rate: 9600, 14400, 19200, 28800, 38400, 57600, 74880, 115200, 230400, 250000, \
         500000, 1000000"
    );
    assert_eq!(
        err(&format!("{port}mux_address = 0x68\n")),
        "tip.toml:5:15: `sensors.fingertip.mux_address` is 0x68; allowed: 0x70…0x77 (TCA9548A \
         pins A2…A0)"
    );
    let channels = "allowed: three distinct switch channels 0…7, one per MS5611 (sensor 1 first)";
    assert_eq!(
        err(&format!("{port}mux_channels = [0, 1]\n")),
        format!("tip.toml:5:16: `sensors.fingertip.mux_channels` names 2 channels; {channels}")
    );
    assert_eq!(
        err(&format!("{port}mux_channels = [0, 8, 1]\n")),
        format!("tip.toml:5:16: `sensors.fingertip.mux_channels` names channel 8; {channels}")
    );
    assert_eq!(
        err(&format!("{port}mux_channels = [2, 1, 2]\n")),
        format!(
            "tip.toml:5:16: `sensors.fingertip.mux_channels` names a channel twice; {channels}"
        )
    );
    // The handstack binary reads real chips only: a fingertip without either is refused.
    let none = err("");
    assert!(
        none.starts_with(
            "tip.toml:2:1: `sensors.fingertip` names no hardware (`i2c_buses`, \
                          `firmata_port` or `serial_port`)"
        ),
        "{none}"
    );
}

/// Frames per second of the fingertip read as the stack reads it ([`RealFingertip`]: the
/// driver's scheduler over the three sensors, each through its switch channel) through the
/// board at `baud` for 1.5 s; and the last frame.
fn frames_per_second(baud: u32, osr: Osr) -> (f64, PressureFrame<3>) {
    let rate = baud.to_string();
    let mut args = TIP.to_vec();
    args.extend(["--baud", &rate]);
    let sim = FirmataSim::with_args(&args);
    let mut tip = RealFingertip::open_firmata(
        &LinuxPlatform::new(),
        &sim.path,
        baud,
        0x70,
        &[0, 1, 2],
        Address::CsbLow,
        osr,
    )
    .unwrap_or_else(|e| panic!("the fingertip at {baud} baud: {e}"));
    let mut last = tip.read_frame().expect("a first frame");
    let start = Instant::now();
    let mut n = 0u32;
    while start.elapsed() < Duration::from_millis(1500) {
        last = tip.read_frame().expect("a frame");
        n += 1;
    }
    (f64::from(n) / start.elapsed().as_secs_f64(), last)
}

#[test]
fn the_fingertips_frame_rate_through_the_board_at_57600_and_115200_baud() {
    let loop_hz = 1e6 / hand_control::grasp_loop::LoopConfig::DEFAULT_PERIOD_US as f64;
    for osr in [Osr::Osr256, Osr::Osr1024, Osr::Osr4096] {
        for baud in [57_600, 115_200] {
            let (hz, f) = frames_per_second(baud, osr);
            let bound = line_bound_hz(f64::from(baud), osr);
            println!(
                "MS5611 fingertip through a Firmata board and a TCA9548A, OSR {}: {hz:.1} \
                 frames/s at {baud} baud (the line's bound {bound:.1}; the grasp loop's \
                 {loop_hz} Hz)",
                osr.ratio()
            );
            for (k, mbar) in MBAR.iter().enumerate() {
                // OSR 256: 6.5 Pa rms; a single frame within 40 Pa.
                let p = f64::from(f.pressure_pa[k]);
                assert!((p - mbar * 100.0).abs() < 40.0, "sensor {}: {f:?}", k + 1);
            }
            // The line's bound holds however loaded the machine; the lower one leaves it room.
            assert!(hz <= bound * 1.02, "{hz} above the line's bound {bound}");
            assert!(hz >= bound * 0.4, "{hz}, the line's bound {bound}");
        }
    }
    // Not even the line's bound reaches the grasp loop's rate at the fastest OSR and baud.
    assert!(line_bound_hz(115_200.0, Osr::Osr256) < loop_hz);
}

/// A port where nothing is: the error names the fingertip, the port and the serial port's
/// words, the same as the pad's (one opening of a board for both); a wiring of other than
/// three channels is refused before the port is opened.
#[test]
fn a_missing_port_is_a_cannot_open_error_naming_it() {
    let e = RealFingertip::open_firmata(
        &LinuxPlatform::new(),
        "/dev/ttyACM-none",
        57_600,
        0x70,
        &[0, 1, 2],
        Address::CsbLow,
        Osr::Osr1024,
    )
    .map(drop)
    .expect_err("no such port");
    assert!(
        matches!(e, RunError::Open { device: "sensors.fingertip", ref path, .. } if path == "/dev/ttyACM-none"),
        "{e:?}"
    );
    assert!(
        e.to_string().starts_with(
            "cannot open sensors.fingertip at /dev/ttyACM-none: Firmata board: serial port: "
        ),
        "{e}"
    );
    // Two channels for three sensors: refused before the port is opened.
    let e = RealFingertip::open_firmata(
        &LinuxPlatform::new(),
        "/dev/ttyACM-none",
        57_600,
        0x70,
        &[0, 1],
        Address::CsbLow,
        Osr::Osr1024,
    )
    .map(drop)
    .expect_err("two channels");
    assert_eq!(
        e.to_string(),
        "cannot open sensors.fingertip at /dev/ttyACM-none: 2 switch channels named; the \
         fingertip's three MS5611 need three"
    );
}
