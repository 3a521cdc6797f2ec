//! The ICM-20789 pad on an Arduino's I2C (`[sensors.imu_pad] firmata_port`): the workspace's
//! `firmata-sim` as its own process (a Mega 2560 running ConfigurableFirmata on a pty, the chip
//! model at rest on its I2C), the scene naming its pty as it would /dev/ttyACM0. The built
//! `handstack node --part pad` publishes the chip's frames; a board without the chip, or one at
//! another baud rate, is a plain-words "cannot open" error and a non-zero exit; and the frame
//! rate through the board is measured at 57 600 and 115 200 baud against the paper's 30 Hz.

use crate::process::FirmataSim;
use handstack::RunError;
use handstack::scene::parts::PadWiring;
use handstack::stack::platform::LinuxPlatform;
use imu_icm20789::BaroMode;
use std::time::{Duration, Instant};

/// The chip model's truth at rest in `firmata-sim`: 1013.25 hPa, 9.81 m/s² on z.
const REST_PA: f32 = 101_325.0;
const REST_Z_MPS2: f32 = 9.81;

#[cfg(feature = "cell")]
mod node {
    use super::{REST_PA, REST_Z_MPS2};
    use crate::process::{FirmataSim, finish, text};
    use hand_zenoh::config::SessionConfig;
    use hand_zenoh::msg::handstack_msgs::PressureFrame;
    use hand_zenoh::msg::sensor_msgs::Imu;
    use hand_zenoh::node::{Node, NodeOptions, Router};
    use std::process::{Child, ChildStdin};
    use std::time::Duration;

    const WAIT: Duration = Duration::from_secs(20);

    /// A node scene with only the pad, on the board at `port` (`extra`: more keys of the pad).
    fn pad_scene(dir: &std::path::Path, port: &str, extra: &str) -> std::path::PathBuf {
        std::fs::create_dir_all(dir).expect("temp dir");
        let scene = dir.join("pad.toml");
        std::fs::write(
            &scene,
            format!(
                "title = \"pad on a board\"\n[sensors.imu_pad]\nfirmata_port = \"{port}\"\n{extra}"
            ),
        )
        .expect("scene");
        scene
    }

    /// `handstack node SCENE --part pad --namespace /pad0 [--connect endpoint]`, its stdin
    /// held open (closing it is the node's normal stop).
    fn pad_node(scene: &std::path::Path, endpoint: &str) -> (Child, ChildStdin) {
        let mut node = crate::process::start_node(scene, "pad", "/pad0", endpoint);
        let stdin = node.stdin.take().expect("stdin");
        (node, stdin)
    }

    fn temp(name: &str) -> std::path::PathBuf {
        std::env::temp_dir().join(format!("handstack-firmata-{name}-{}", std::process::id()))
    }

    #[test]
    fn a_pad_node_publishes_the_frames_of_the_chip_on_a_firmata_board() {
        let sim = FirmataSim::start(&[]);
        let dir = temp("node");
        let scene = pad_scene(&dir, &sim.path, "");
        let (_router, endpoint) = Router::open_on_loopback().expect("the router");
        let mut options = NodeOptions::new("/cell", "listener");
        options.session = SessionConfig::peer(&endpoint);
        let listener = Node::open(options).expect("the listener");
        let mut imu = listener
            .subscription::<Imu>("/pad0/imu", 64)
            .expect("imu subscription");
        let mut raw = listener
            .subscription::<PressureFrame>("/pad0/tactile/raw", 64)
            .expect("raw subscription");
        let (node, stdin) = pad_node(&scene, &endpoint);
        for _ in 0..5 {
            let m = imu
                .recv_timeout(WAIT)
                .expect("imu subscription")
                .expect("an imu frame from the node")
                .message;
            let a = &m.linear_acceleration;
            let g = &m.angular_velocity;
            assert_eq!(m.header.frame_id, "pad0");
            // ±2 g at 16 384 counts per g: the model's noise is a few counts.
            assert!(
                (a.z as f32 - REST_Z_MPS2).abs() < 0.1 && a.x.abs() < 0.1 && a.y.abs() < 0.1,
                "{a:?}"
            );
            assert!(
                g.x.abs() < 0.02 && g.y.abs() < 0.02 && g.z.abs() < 0.02,
                "{g:?}"
            );
            let p = raw
                .recv_timeout(WAIT)
                .expect("raw subscription")
                .expect("a pressure frame from the node")
                .message;
            assert_eq!(p.pressure_pa.len(), 1);
            // Low Noise: 0.8 Pa rms.
            assert!((p.pressure_pa[0] - REST_PA).abs() < 10.0, "{p:?}");
        }
        drop(stdin);
        let out = finish(node);
        let err = text(&out.stderr);
        assert!(out.status.success(), "{:?}: {err}", out.status);
        assert!(err.contains("/pad0 pad: "), "{err}");
        let _ = std::fs::remove_dir_all(dir);
    }

    /// Runs the pad node on the scene with `extra` keys for a board started with `sim_args`;
    /// its exit status, its stderr and the board's port.
    fn failed_node(name: &str, sim_args: &[&str], extra: &str) -> (Option<i32>, String, String) {
        let sim = FirmataSim::start(sim_args);
        let dir = temp(name);
        let scene = pad_scene(&dir, &sim.path, extra);
        // No router: the pad is opened before the node joins, and fails first.
        let (node, stdin) = pad_node(&scene, "tcp/127.0.0.1:9");
        let out = finish(node);
        drop(stdin);
        let _ = std::fs::remove_dir_all(dir);
        (out.status.code(), text(&out.stderr), sim.path.clone())
    }

    #[test]
    fn a_board_without_the_chip_is_a_cannot_open_error() {
        let (code, err, port) = failed_node("no-imu", &["--no-imu"], "");
        assert_eq!(code, Some(1), "{err}");
        let line = err.lines().find(|l| l.starts_with("error:")).unwrap_or("");
        // The chip's WHO_AM_I read (0x68) comes back short: the board's I2C NACK, in words.
        assert!(
            line.starts_with(&format!(
                "error: /pad0 pad: cannot open sensors.imu_pad at {port}: ICM-20789: "
            )) && line.contains("I2C device 0x68: no answer"),
            "{err}"
        );
        assert!(!line.contains("Kind") && !line.contains('{'), "{err}");
    }

    #[test]
    fn a_board_at_another_baud_rate_is_a_cannot_open_error() {
        // The sketch runs at 57 600; the scene says 115 200: what arrives is not Firmata.
        let (code, err, port) = failed_node("baud", &[], "firmata_baud = 115200\n");
        assert_eq!(code, Some(1), "{err}");
        let line = err.lines().find(|l| l.starts_with("error:")).unwrap_or("");
        assert!(
            line.starts_with(&format!(
                "error: /pad0 pad: cannot open sensors.imu_pad at {port}: Firmata board: "
            )) && line.contains("115200 baud"),
            "{err}"
        );
        assert!(!line.contains("Kind") && !line.contains('{'), "{err}");
    }
}

/// `handstack check` takes a scene naming the board, and refuses one naming both a bus and a
/// board, at the key's line and column.
#[test]
fn check_takes_firmata_port_and_refuses_it_beside_i2c_bus() {
    use crate::process::{finish, text};
    let dir = std::env::temp_dir().join(format!("handstack-firmata-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    // `handstack run` needs an experiment: the readout, on a fingertip of its own.
    let tip = "[sensors.fingertip]\nosr = 1024\n\
               i2c_buses = [\"/dev/i2c-1\", \"/dev/i2c-3\", \"/dev/i2c-4\"]\n\
               [experiment.readout]\nframes = 10\n";
    let good = dir.join("good.toml");
    std::fs::write(
        &good,
        format!(
            "title = \"t\"\n[sensors.imu_pad]\nfirmata_port = \"/dev/ttyACM0\"\n\
             firmata_baud = 115200\n{tip}"
        ),
    )
    .expect("scene");
    let both = dir.join("both.toml");
    std::fs::write(
        &both,
        format!(
            "title = \"t\"\n[sensors.imu_pad]\ni2c_bus = \"/dev/i2c-2\"\n\
             firmata_port = \"/dev/ttyACM0\"\n{tip}"
        ),
    )
    .expect("scene");
    let check = |scene: &std::path::Path| {
        let child = std::process::Command::new(env!("CARGO_BIN_EXE_handstack"))
            .arg("check")
            .arg(scene)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("handstack check starts");
        finish(child)
    };
    let out = check(&good);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains(": ok (readout)"));
    let out = check(&both);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        text(&out.stderr).trim(),
        format!(
            "error: {}:4:16: `sensors.imu_pad.firmata_port` is named beside `i2c_bus`; allowed: \
             one of `i2c_bus` (an I2C bus of this computer) or `firmata_port` (the serial port of \
             a Firmata board the chip is wired to)",
            both.display()
        )
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A pty with nothing behind it (the test holds its other end and never writes): no version
/// report through the reset's wait, none when asked; the error says what to look for.
#[test]
fn a_port_nothing_answers_on_is_a_cannot_open_error_in_words() {
    use std::os::unix::io::AsRawFd;
    let (_far, near) = serial2::SerialPort::pair().expect("a pty pair");
    let port = std::fs::read_link(format!("/proc/self/fd/{}", near.as_raw_fd()))
        .expect("the pty's path")
        .display()
        .to_string();
    let wiring = PadWiring::Firmata {
        port: &port,
        baud: 57_600,
    };
    let e = handstack::stack::pad::open_wired(&LinuxPlatform::new(), wiring, BaroMode::LowNoise)
        .map(drop)
        .expect_err("nothing answers");
    assert!(
        matches!(e, RunError::Open { device: "sensors.imu_pad", ref path, .. } if *path == port),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "cannot open sensors.imu_pad at {port}: Firmata board: no protocol version report \
             within 1000 ms (at 57600 baud; is StandardFirmata or ConfigurableFirmata running on \
             it?)"
        )
    );
}

/// Frames per second of the pad read as the stack reads it ([`handstack::stack::pad::RealPad`]:
/// a barometer conversion in `mode` started, the IMU burst, the conversion's wait, the pressure
/// read), through the board at `baud` for 1.5 s; and the last frame.
fn frames_per_second(baud: u32, mode: BaroMode) -> (f64, hand_traits::ImuFrame) {
    use hand_traits::TactileSource;
    let rate = baud.to_string();
    let sim = FirmataSim::start(&["--baud", &rate]);
    let wiring = PadWiring::Firmata {
        port: &sim.path,
        baud,
    };
    let mut pad = handstack::stack::pad::open_wired(&LinuxPlatform::new(), wiring, mode)
        .unwrap_or_else(|e| panic!("the pad at {baud} baud: {e}"));
    let mut last = pad.read_frame().expect("a first frame");
    let start = Instant::now();
    let mut n = 0u32;
    while start.elapsed() < Duration::from_millis(1500) {
        last = pad.read_frame().expect("a frame");
        n += 1;
    }
    (f64::from(n) / start.elapsed().as_secs_f64(), last)
}

/// The most frames per second the board's line allows at `baud` in `mode`: per frame, its
/// bytes on the line (the command write and the IMU request, 9 + 9 out; the 14-byte IMU
/// reply, 35 back; the pressure request, 7 out; its 9-byte reply, 25 back: 10 bits each), the
/// I2C transfers at 100 kHz (about 32 bytes of 9 bits) and the conversion's worst-case wait,
/// which the driver starts after the IMU burst.
fn line_bound_hz(baud: f64, mode: BaroMode) -> f64 {
    let s = (9.0 + 9.0 + 35.0 + 7.0 + 25.0) * 10.0 / baud
        + 32.0 * 9.0 / 100_000.0
        + f64::from(mode.conversion_time_max_us()) * 1e-6;
    1.0 / s
}

#[test]
fn the_pads_frame_rate_through_the_board_at_57600_and_115200_baud() {
    let paper = handstack::stack::pad::FRAME_RATE_HZ;
    for mode in [BaroMode::LowNoise, BaroMode::Normal] {
        for baud in [57_600, 115_200] {
            let (hz, f) = frames_per_second(baud, mode);
            let bound = line_bound_hz(f64::from(baud), mode);
            println!(
                "ICM-20789 pad through a Firmata board, {mode:?}: {hz:.1} frames/s at {baud} \
                 baud (the line's bound {bound:.1}; the paper's {paper} Hz)"
            );
            assert!((f.accel_mps2[2] - REST_Z_MPS2).abs() < 0.1, "{f:?}");
            let p = f.pressure_pa.expect("a pressure each frame");
            // Low Noise 0.8 Pa rms, Normal 1.6 Pa.
            assert!((p - REST_PA).abs() < 20.0, "{f:?}");
            // The line's bound holds however loaded the machine; the lower one leaves it room.
            assert!(hz <= bound * 1.02, "{hz} above the line's bound {bound}");
            assert!(hz >= bound * 0.5, "{hz}, the line's bound {bound}");
        }
    }
    // In the paper's Low Noise mode not even the line's bound reaches 30 Hz at either rate.
    assert!(line_bound_hz(115_200.0, BaroMode::LowNoise) < paper);
}

/// A port that is not there: the open error names it and the serial port's words.
#[test]
fn a_missing_port_is_a_cannot_open_error_naming_it() {
    let wiring = PadWiring::Firmata {
        port: "/dev/ttyACM-none",
        baud: 57_600,
    };
    let e = handstack::stack::pad::open_wired(&LinuxPlatform::new(), wiring, BaroMode::LowNoise)
        .map(drop)
        .expect_err("no such port");
    assert!(
        matches!(e, RunError::Open { device: "sensors.imu_pad", ref path, .. } if path == "/dev/ttyACM-none"),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(
        msg.starts_with(
            "cannot open sensors.imu_pad at /dev/ttyACM-none: Firmata board: serial port: "
        ),
        "{msg}"
    );
}
