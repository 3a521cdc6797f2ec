//! Naming real hardware really opens it: a hardware grasp scene (a `serial_port`, here the pty
//! of a running bus simulator) reads only real fingertip buses and fails before any servo
//! command when they are missing or cannot be opened; a scene whose `host` is a started
//! ur-bridge simulator moves that arm; a missing I2C bus or serial port is a typed "cannot open
//! …" error naming the path; the readout experiment reads the simulated fingertip.

mod common;

use handstack::RunError;
use handstack::progress::Quiet;
use handstack::runs::{RunContext, run};
use handstack::scene::Scene;
use std::net::Ipv4Addr;

fn run_text(text: &str) -> Result<handstack::Outcome, RunError> {
    let scene = Scene::parse("hw.toml", text)?;
    run(&scene, &RunContext::new(&Quiet))
}

/// The servos of `bus` have had no command: torque off, Goal PWM at its power-on value.
fn untouched(bus: &hand_control::sim::SimBus, ids: &[u8]) {
    let table = &hand_control::control_table::MX_28;
    for &id in ids {
        let (on, pwm) = bus
            .with_servo(id, |s| {
                (s.torque_enabled(), s.get(table.goal_effort.address))
            })
            .expect("servo");
        assert!(!on, "servo {id} torque");
        assert_eq!(pwm, table.effort_limit.default, "servo {id} Goal PWM");
    }
}

#[test]
fn a_hardware_grasp_never_reads_a_simulated_fingertip_and_fails_before_any_servo_command() {
    use hand_control::sim::{SimBus, SimConfig};
    let (bus, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2])).expect("pty");
    drop(port); // the scene opens the pty by its path, as it would /dev/ttyUSB0
    let path = bus.client_path().display().to_string();
    let scene = |sensors: &str| {
        format!(
            "title = \"pty hand\"\n[sensors.fingertip]\nosr = 1024\n{sensors}[controller]\n\
             preset = \"grasp\"\n[hand]\nmodel = \"mx28\"\nids = [1, 2]\nserial_port = \"{path}\"\n\
             reply_timeout_ms = 250\n[experiment.grasp]\nobjects = [\"cube\"]\nhold_s = 0.3\n"
        )
    };
    // Real servos, no sensor buses named: refused (the simulated pad is never pressed by a
    // real grasp), and nothing reached the servos.
    let e = run_text(&scene("")).expect_err("a hardware hand needs its fingertip's buses");
    assert!(
        matches!(
            e,
            RunError::Device {
                device: "sensors.fingertip",
                ..
            }
        ) && e.to_string().contains("i2c_buses"),
        "{e}"
    );
    untouched(&bus, &[1, 2]);
    // Buses that cannot be opened: the error names the device and the path, before any servo
    // command.
    let e = run_text(&scene(
        "i2c_buses = [\"/dev/i2c-99\", \"/dev/i2c-98\", \"/dev/i2c-97\"]\n",
    ))
    .expect_err("no such bus");
    assert!(
        matches!(e, RunError::Open { device: "sensors.fingertip", ref path, .. } if path == "/dev/i2c-99"),
        "{e:?}"
    );
    untouched(&bus, &[1, 2]);
}

#[test]
fn a_missing_i2c_bus_is_a_cannot_open_error() {
    let text = "title = \"real tip\"\n[sensors.fingertip]\nosr = 4096\n\
                i2c_buses = [\"/dev/i2c-99\", \"/dev/i2c-98\", \"/dev/i2c-97\"]\n\
                [experiment.readout]\nframes = 10\n";
    match run_text(text) {
        Err(e @ RunError::Open { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.starts_with("cannot open sensors.fingertip at /dev/i2c-99"),
                "{msg}"
            );
        }
        other => panic!("expected an open error, got {other:?}"),
    }
    let pad = "title = \"real pad\"\n[sensors.imu_pad]\ni2c_bus = \"/dev/i2c-99\"\n\
               [sensors.fingertip]\nosr = 4096\n[experiment.readout]\nframes = 10\n";
    assert!(
        matches!(run_text(pad), Err(RunError::Open { device: "sensors.imu_pad", ref path, .. }) if path == "/dev/i2c-99")
    );
}

#[test]
fn a_missing_serial_port_is_a_cannot_open_error() {
    let text = "title = \"real hand\"\n[sensors.fingertip]\nosr = 1024\n[controller]\npreset = \"grasp\"\n\
                [hand]\nmodel = \"mx28\"\nserial_port = \"/dev/ttyUSB-handstack-none\"\n\
                [experiment.grasp]\nobjects = [\"cube\"]\nhold_s = 1\n";
    let scene = Scene::parse("hw.toml", text).expect("valid scene");
    let hand = scene.file.hand.as_ref().expect("hand").get_ref();
    let e =
        handstack::stack::hand::open(hand, "/dev/ttyUSB-handstack-none").expect_err("no such port");
    assert!(matches!(e, RunError::Open { device: "hand", .. }), "{e:?}");
    assert!(
        e.to_string()
            .starts_with("cannot open hand at /dev/ttyUSB-handstack-none"),
        "{e}"
    );
}

#[test]
fn a_scene_naming_a_started_ur_simulator_moves_it() {
    use ur_bridge::sim::{SimConfig, UrSim};
    let address = Ipv4Addr::new(127, 0, 0, 90);
    let _sim = UrSim::start(SimConfig {
        address,
        ..SimConfig::default()
    })
    .expect("simulator");
    let text = format!(
        "title = \"real arm\"\n[sim]\nseed = 10\n[sensors.imu_pad]\n[estimators.contact]\nlocators = [\"cnn\"]\n\
         [arm]\nmodel = \"ur3\"\nhost = \"{address}\"\n[experiment.tap]\nrounds = 1\n"
    );
    let o = run_text(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(common::value(&o, "tap_count"), 9.0);
    let acc = o.figure("tap_accuracy_pct").expect("figure");
    assert!(acc.label.contains("127.0.0.90"), "{acc:?}");
    assert!(o.figure("tcp_error_max_m").and_then(|f| f.met) == Some(true));
    // A host nobody listens on is an open error naming it.
    let dead = text.replace("127.0.0.90", "127.0.0.91");
    assert!(
        matches!(run_text(&dead), Err(RunError::Open { device: "arm", ref path, .. }) if path == "127.0.0.91")
    );
}

#[test]
fn readout_reads_the_simulated_fingertip_at_rest() {
    let text = "title = \"readout\"\n[sim]\nseed = 3\n[sensors.fingertip]\nosr = 4096\n\
                [experiment.readout]\nframes = 200\n";
    let o = run_text(text).unwrap_or_else(|e| panic!("{e}"));
    // OSR 4096: two conversions of ≤ 9.04 ms per sensor per cycle (datasheet), three sensors
    // read in one scheduler cycle: ~18 ms per frame.
    let period = common::value(&o, "frame_period_ms");
    assert!((17.0..20.0).contains(&period), "{period}");
    for k in 1..=3 {
        let sd = common::value(&o, &format!("sensor{k}_sd_pa"));
        // At rest the model drifts 0.1 hPa/min (3.6 s here: 0.6 Pa) under ±1–2 Pa of noise.
        assert!(sd > 0.0 && sd < 5.0, "sensor {k}: {sd} Pa");
    }
}
