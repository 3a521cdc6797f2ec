//! Naming real hardware really opens it: a grasp scene (its `serial_port` the pty of a running
//! `dxl-sim`, its own process) reads its pressure frames from the fingertip buses it names (here a
//! substitute platform's: MS5611 chip models, nothing else behind them) and fails before any
//! servo command when they are missing or cannot be opened; a scene whose `host` is a started
//! UR controller simulator connects to it; a pad on a named bus is read through the driver; a
//! missing I2C bus, serial port or host is a typed "cannot open …" error naming the path.

use crate::process::{DxlSim, SIM_REPLY_TIMEOUT_MS};
use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
use embedded_hal::delay::DelayNs;
use hand_control::control_table::MX_28;
use hand_control::grasp_loop::LoopClock;
use handstack::progress::Quiet;
use handstack::runs::{RunContext, run};
use handstack::scene::{Scene, SceneError};
use handstack::stack::platform::{I2cBus, Platform};
use handstack::{Plot, RunError};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

fn run_text(text: &str) -> Result<handstack::Outcome, RunError> {
    let scene = Scene::parse("hw.toml", text)?;
    run(&scene, &RunContext::new(&Quiet))
}

/// The hardware grasp scene for the servos on the pty at `path`, with `sensors` (the
/// fingertip's buses) and a hold of `hold_s`.
fn grasp_scene(path: &str, sensors: &str, hold_s: f64) -> String {
    format!(
        "title = \"pty hand\"\n[sensors.fingertip]\nosr = 1024\n{sensors}[controller]\n\
         preset = \"grasp\"\n[hand]\nmodel = \"mx28\"\nids = [1, 2]\nserial_port = \"{path}\"\n\
         reply_timeout_ms = {SIM_REPLY_TIMEOUT_MS}\n[experiment.grasp]\ntorque_band = [250, 320]\nhold_s = {hold_s}\n"
    )
}

/// A substitute platform: its I2C buses `sub-0` … `sub-2` each hold an MS5611 chip model (no
/// noise) at 1000 mbar that is pressed by `k + 1` mbar from `PRESS_NS` on, all on one simulated
/// clock that is also the platform's delay and loop clock. It counts the conversions its chips
/// run, so a test sees the frames came from here. Its bus `pad` holds an ICM-20789 chip model
/// (no noise) reading [`PAD_TRUTH`].
struct Substitute {
    clock: SimClock,
    conversions: Arc<AtomicUsize>,
}

/// When the substitute pad is pressed, ns (after the loop's 10 tare cycles).
const PRESS_NS: u64 = 300_000_000;

/// What the substitute pad's chip measures: 1 g on z, a slow turn about x, 1000 hPa.
const PAD_TRUTH: ([f32; 3], [f32; 3], f64) = ([0.0, 0.0, 9.806_65], [0.1, 0.0, 0.0], 100_000.0);

impl Platform for Substitute {
    fn open_i2c(&self, path: &str) -> Result<I2cBus, String> {
        if path == "pad" {
            let (accel, gyro, pa) = PAD_TRUTH;
            let chip = imu_icm20789::sim::ChipModel::new(
                imu_icm20789::sim::Truth::constant(accel, gyro, pa),
                1,
            )
            .with_clock(self.clock.clone())
            .with_noise(imu_icm20789::sim::SimNoise::NONE);
            return Ok(I2cBus::new(chip));
        }
        let k = ["sub-0", "sub-1", "sub-2"]
            .iter()
            .position(|p| *p == path)
            .ok_or_else(|| format!("no substitute bus {path}"))?;
        let conversions = Arc::clone(&self.conversions);
        let env = move |t_ns: u64| {
            conversions.fetch_add(1, Ordering::Relaxed);
            let press = if t_ns >= PRESS_NS {
                k as f64 + 1.0
            } else {
                0.0
            };
            Conditions {
                pressure_mbar: 1000.0 + press,
                temperature_celsius: 25.0,
            }
        };
        Ok(I2cBus::new(
            Ms5611Sim::new(env, self.clock.clone()).with_noise(false),
        ))
    }

    fn delay(&self) -> Box<dyn DelayNs + Send> {
        Box::new(self.clock.delay())
    }

    fn clock(&self) -> Box<dyn LoopClock + Send> {
        Box::new(self.clock.clone())
    }
}

#[test]
fn a_hardware_grasp_reads_its_frames_from_the_buses_it_names_and_drives_the_servos() {
    let bus = ServoBus::start();
    let text = grasp_scene(
        &bus.path,
        "i2c_buses = [\"sub-0\", \"sub-1\", \"sub-2\"]\n",
        1.0,
    );
    let scene = Scene::parse("hw.toml", &text).expect("valid scene");
    let conversions = Arc::new(AtomicUsize::new(0));
    let cx = RunContext::new(&Quiet).with_platform(Substitute {
        clock: SimClock::new(),
        conversions: Arc::clone(&conversions),
    });
    let o = run(&scene, &cx).unwrap_or_else(|e| panic!("{e}"));
    // The loop's pressure is the substitute's press: a mean rise of (1 + 2 + 3) / 3 mbar =
    // 200 Pa once pressed (the compensation rounds to 1 Pa), nothing before.
    let Some(Plot::Lines { lines, .. }) = o
        .plots
        .iter()
        .find(|p| matches!(p, Plot::Lines { title, .. } if title.contains("pressure rise")))
    else {
        panic!("no pressure plot")
    };
    let points = &lines[0].points;
    // Every frame the loop read is three conversions or more on the substitute buses.
    let n = conversions.load(Ordering::Relaxed);
    assert!(
        n >= 3 * points.len(),
        "{n} conversions for {} frames",
        points.len()
    );
    let (before, after): (Vec<_>, Vec<_>) = points.iter().partition(|(t, _)| *t < 0.29);
    assert!(before.len() >= 15 && after.len() >= 60, "{points:?}");
    assert!(before.iter().all(|(_, p)| p.abs() <= 1.0), "{before:?}");
    let pressed = &after[after.len() / 2..];
    assert!(
        pressed.iter().all(|(_, p)| (p - 200.0).abs() <= 1.0),
        "{pressed:?}"
    );
    // And the controller acted on it over Protocol 2.0: both servos hold a Goal PWM the loop
    // (or its release) wrote, no longer the power-on value; the run ended with the default
    // end action, release then torque off.
    // Read back after the torque off, a broadcast nothing answers: the servos execute what
    // arrives on the bus in order.
    for (id, (on, pwm)) in [1, 2].into_iter().zip(bus.torque_and_goal_pwm()) {
        assert!(!on, "servo {id} torque left on");
        assert_ne!(pwm, MX_28.effort_limit.default, "servo {id} Goal PWM");
    }
    assert!(
        o.notes
            .iter()
            .any(|n| n.starts_with("hand ") && n.ends_with("then torque off")),
        "{:?}",
        o.notes
    );
}

/// The servo bus of these scenes ([`DxlSim`]), read back as Torque Enable and Goal PWM.
struct ServoBus(DxlSim);

impl std::ops::Deref for ServoBus {
    type Target = DxlSim;
    fn deref(&self) -> &DxlSim {
        &self.0
    }
}

impl ServoBus {
    fn start() -> ServoBus {
        ServoBus(DxlSim::start(&[]))
    }

    /// Each servo's Torque Enable (on?) and Goal PWM.
    fn torque_and_goal_pwm(&self) -> Vec<(bool, i32)> {
        self.read_back(MX_28.torque_enable.address, MX_28.goal_effort.address)
            .into_iter()
            .map(|(on, pwm)| (on != 0, pwm))
            .collect()
    }

    /// The servos have had no command: torque off, Goal PWM at its power-on value.
    fn untouched(&self) {
        for (id, (on, pwm)) in [1, 2].into_iter().zip(self.torque_and_goal_pwm()) {
            assert!(!on, "servo {id} torque");
            assert_eq!(pwm, MX_28.effort_limit.default, "servo {id} Goal PWM");
        }
    }
}

#[test]
fn a_hardware_grasp_never_reads_a_simulated_fingertip_and_fails_before_any_servo_command() {
    let bus = ServoBus::start();
    let scene = |sensors: &str| grasp_scene(&bus.path, sensors, 0.3);
    // Real servos, no sensor buses named: refused as a scene error (this binary has no
    // simulated fingertip to fall back on), and nothing reached the servos.
    let e = run_text(&scene("")).expect_err("a hardware hand needs its fingertip's buses");
    assert!(
        matches!(
            e,
            RunError::Scene(SceneError::Invalid { ref key, .. }) if key == "sensors.fingertip"
        ) && e.to_string().contains("i2c_buses"),
        "{e}"
    );
    bus.untouched();
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
    bus.untouched();
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
    let pad = handstack::stack::pad::open(
        &handstack::stack::platform::LinuxPlatform::new(),
        "/dev/i2c-99",
        imu_icm20789::BaroMode::LowNoise,
    )
    .map(drop)
    .expect_err("no such bus");
    assert!(
        matches!(pad, RunError::Open { device: "sensors.imu_pad", ref path, .. } if path == "/dev/i2c-99"),
        "{pad}"
    );
}

#[test]
fn a_real_pad_is_read_through_the_driver_from_the_bus_it_names() {
    use hand_traits::TactileSource;
    let clock = SimClock::new();
    let platform = Substitute {
        clock: clock.clone(),
        conversions: Arc::default(),
    };
    let mut pad = handstack::stack::pad::open(&platform, "pad", imu_icm20789::BaroMode::LowNoise)
        .expect("the substitute pad");
    let (accel, gyro, pa) = PAD_TRUTH;
    let mut last_t = None;
    for _ in 0..5 {
        let f = pad.read_frame().expect("a frame");
        // ±2 g: 16 384 counts per g; ±250 °/s: 131 counts per °/s (datasheet Tables 1–2).
        for k in 0..3 {
            assert!((f.accel_mps2[k] - accel[k]).abs() < 2e-3, "{f:?}");
            assert!((f.gyro_rps[k] - gyro[k]).abs() < 2e-4, "{f:?}");
        }
        let p = f.pressure_pa.expect("a pressure each frame");
        assert!((f64::from(p) - pa).abs() < 1.0, "{f:?}");
        // Each frame waits out a Low Noise conversion on the platform's clock.
        assert!(last_t.is_none_or(|t| f.t_us > t), "{f:?}");
        last_t = Some(f.t_us);
    }
    let conversion_ns = u64::from(imu_icm20789::BaroMode::LowNoise.conversion_time_max_us()) * 1000;
    assert!(
        clock.now_ns() >= 5 * conversion_ns,
        "5 conversions in {} ns",
        clock.now_ns()
    );
}

#[test]
fn servos_of_another_model_than_the_scenes_are_refused_before_any_command() {
    let bus = ServoBus::start();
    let path = bus.path.clone();
    let text = grasp_scene(
        &path,
        "i2c_buses = [\"sub-0\", \"sub-1\", \"sub-2\"]\n",
        1.0,
    )
    .replace("model = \"mx28\"", "model = \"xm430\"");
    let scene = Scene::parse("hw.toml", &text).expect("valid scene");
    let hand = scene.file.hand.as_ref().expect("hand").get_ref();
    let e = handstack::stack::hand::open(hand, &path).expect_err("MX-28s, not XM430s");
    assert_eq!(
        e.to_string(),
        format!(
            "cannot open hand at {path}: the servos are MX-28(2.0), the scene names `xm430` \
             (XM430-W350)"
        )
    );
    bus.untouched();
}

#[test]
fn a_missing_serial_port_is_a_cannot_open_error() {
    let text = grasp_scene(
        "/dev/ttyUSB-handstack-none",
        "i2c_buses = [\"sub-0\", \"sub-1\", \"sub-2\"]\n",
        1.0,
    );
    let scene = Scene::parse("hw.toml", &text).expect("valid scene");
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
fn a_scene_naming_a_started_ur_simulator_connects_to_it() {
    use handstack::scene::NodeScene;
    // The workspace's `ur-sim` binary, as a user's CI runs it.
    let address = "127.0.0.90";
    let _sim = crate::process::UrSim::start(address);
    let text = format!(
        "title = \"real arm\"\n[sensors.fingertip]\nosr = 256\n\
         i2c_buses = [\"sub-0\", \"sub-1\", \"sub-2\"]\n[arm]\nmodel = \"ur3\"\n\
         host = \"{address}\"\n[experiment.readout]\nframes = 5\n"
    );
    // `handstack run` moves an arm only in a tap-to-move: an [arm] without one is a scene error,
    // not a silent connection.
    let e = Scene::parse("hw.toml", &text).expect_err("an arm no experiment moves");
    assert_eq!(e.key(), Some("arm"), "{e}");
    assert!(
        e.to_string().contains("handstack node SCENE --part arm"),
        "{e}"
    );
    // A node's scene opens it: every device first, the arm by its host.
    let substitute = || Substitute {
        clock: SimClock::new(),
        conversions: Arc::new(AtomicUsize::new(0)),
    };
    let open = |text: &str| {
        let scene = NodeScene::parse("hw.toml", text)?;
        handstack::stack::check_real_devices(&scene, &substitute())
    };
    open(&text).unwrap_or_else(|e| panic!("{e}"));
    // A host nobody listens on is an open error naming it.
    let dead = text.replace("127.0.0.90", "127.0.0.91");
    assert!(
        matches!(open(&dead), Err(RunError::Open { device: "arm", ref path, .. }) if path == "127.0.0.91")
    );
}
