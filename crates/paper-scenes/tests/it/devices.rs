//! A paper scene's devices: real where the scene names the hardware, simulated behind the real
//! interface otherwise. A scene whose `host` is a started UR controller simulator moves that
//! arm through ur_rtde (a dead host is a "cannot open" error naming it); the readout reads the
//! simulated fingertip's chip models through the real MS5611 driver.

use crate::common;

use handstack::RunError;
use handstack::progress::Quiet;
use paper_scenes::Error;
use paper_scenes::runs::{RunContext, run};
use paper_scenes::scene::PaperScene;
use std::net::Ipv4Addr;

fn run_text(text: &str) -> Result<handstack::Outcome, Error> {
    let scene = PaperScene::parse("devices.toml", text)?;
    run(&scene, &RunContext::new(&Quiet))
}

#[test]
fn a_scene_naming_a_started_ur_simulator_moves_it() {
    use ur_sim::{SimConfig, UrSim};
    let address = Ipv4Addr::new(127, 0, 0, 90);
    let sim = UrSim::start(SimConfig {
        address,
        ..SimConfig::default()
    })
    .expect("simulator");
    let text = format!(
        "title = \"real arm\"\n[sim]\nseed = 10\n[sensors.imu_pad]\n[estimators.contact]\nlocators = [\"cnn\"]\n\
         [arm]\nmodel = \"ur3\"\nhost = \"{address}\"\n[experiment.tap]\ntaps_per_region = 1\n"
    );
    let o = run_text(&text).unwrap_or_else(|e| panic!("{e}; simulator log {:?}", sim.log()));
    assert_eq!(common::value(&o, "tap_count"), 9.0);
    let acc = o.figure("tap_accuracy_pct").expect("figure");
    assert!(acc.label.contains("127.0.0.90"), "{acc:?}");
    assert!(o.figure("tcp_error_max_m").and_then(|f| f.met) == Some(true));
    common::script_uploaded_once(&sim);
    // A host nobody listens on is an open error naming it.
    let dead = text.replace("127.0.0.90", "127.0.0.91");
    assert!(
        matches!(run_text(&dead), Err(Error::Run(RunError::Open { device: "arm", ref path, .. })) if path == "127.0.0.91")
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

#[test]
fn a_real_hand_never_grasps_from_a_simulated_fingertip() {
    let text = "title = \"mixed\"\n[sensors.fingertip]\nosr = 1024\n[controller]\npreset = \"grasp\"\n\
                [hand]\nmodel = \"mx28\"\nserial_port = \"/dev/ttyUSB-handstack-none\"\n\
                [experiment.grasp]\nobjects = [\"cube\"]\nhold_s = 1\n";
    let e = PaperScene::parse("mixed.toml", text).expect_err("refused");
    assert_eq!(e.key(), Some("experiment.grasp"), "{e}");
    assert!(e.to_string().contains("from a simulated fingertip"), "{e}");
}

/// A paper scene's real pad (handstack's) is read as its simulated one (hand-sim's, which
/// recorded the datasets the contact CNN learned): the same IMU settings and frame rate.
#[test]
fn a_real_pad_is_read_as_the_simulated_one() {
    use hand_sim::imu_pad::{IMU_SETTINGS, ImuPadConfig};
    use handstack::stack::pad;
    assert_eq!(pad::IMU_SETTINGS, IMU_SETTINGS);
    assert_eq!(pad::FRAME_RATE_HZ, ImuPadConfig::default().sample_rate_hz);
}
