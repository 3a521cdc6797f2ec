//! What a `handstack` scene may name: every device with its hardware, no simulated
//! environment, a torque band the servos accept; each refusal names the file, line, key and
//! what is allowed. The parts' own checks (ranges, estimators with their sensors) are shared
//! with the papers' scenes and tested there on the papers' files.

use handstack::scene::{Scene, SceneError};

const HAND: &str = r#"title = "bench hand"
[sensors.fingertip]
osr = 1024
i2c_buses = ["/dev/i2c-1", "/dev/i2c-3", "/dev/i2c-4"]
[controller]
preset = "grasp"
[hand]
model = "mx28"
serial_port = "/dev/ttyUSB0"
[experiment.grasp]
torque_band = [250, 320]
hold_s = 30
"#;

fn err(text: &str) -> SceneError {
    match Scene::parse("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

fn says(e: &SceneError, line: usize, key: &str, parts: &[&str]) {
    let msg = e.to_string();
    assert!(msg.starts_with(&format!("bad.toml:{line}:")), "{msg}");
    assert_eq!(e.key(), Some(key), "{msg}");
    for p in parts {
        assert!(msg.contains(p), "{msg:?} lacks {p:?}");
    }
}

#[test]
fn a_users_hand_scene_parses() {
    let s = Scene::parse("dir/bench-hand.toml", HAND).expect("valid");
    assert_eq!(s.name, "bench-hand");
    let g = s.file.experiment.get_ref().grasp.as_ref().expect("grasp");
    assert_eq!(*g.get_ref().torque_band.get_ref(), [250, 320]);
}

#[test]
fn a_device_without_its_hardware_is_refused() {
    let e = err(&HAND.replace(
        "i2c_buses = [\"/dev/i2c-1\", \"/dev/i2c-3\", \"/dev/i2c-4\"]\n",
        "",
    ));
    says(
        &e,
        2,
        "sensors.fingertip",
        &["names no hardware (`i2c_buses`)", "real devices only"],
    );
    let e = err(&HAND.replace("serial_port = \"/dev/ttyUSB0\"\n", ""));
    says(&e, 7, "hand", &["names no hardware (`serial_port`)"]);
    // An arm needs its host in a node's scene; a scene to run has no arm to move at all.
    let arm = format!("{HAND}[arm]\nmodel = \"ur3\"\n");
    let e = handstack::scene::NodeScene::parse("bad.toml", &arm).expect_err("no host");
    says(&e, 13, "arm", &["names no hardware (`host`)"]);
    let e = err(&format!("{arm}host = \"192.168.1.10\"\n"));
    says(
        &e,
        13,
        "arm",
        &["no experiment of `handstack run` moves an arm"],
    );
    // A hand no experiment moves is refused too: a run would power it and leave it so.
    let readout = HAND.replace(
        "[experiment.grasp]\ntorque_band = [250, 320]\nhold_s = 30\n",
        "[experiment.readout]\nframes = 10\n",
    );
    let e = err(&readout);
    says(&e, 7, "hand", &["no experiment of this scene moves it"]);
    let e = err(&format!("{HAND}[sim]\nseed = 1\n"));
    says(&e, 13, "sim", &["simulates an environment", "paper-scenes"]);
}

#[test]
fn a_torque_band_the_servos_cannot_take_is_refused() {
    for band in ["[320, 250]", "[0, 2000]"] {
        let e = err(&HAND.replace("[250, 320]", band));
        says(&e, 11, "experiment.grasp.torque_band", &[band, "≤ 1023"]);
    }
    let e = err(&HAND.replace("hold_s = 30", "hold_s = 0"));
    says(&e, 12, "experiment.grasp.hold_s", &["is 0", "0.1…600 s"]);
    let e = err(&HAND.replace(
        "[experiment.grasp]\ntorque_band = [250, 320]\nhold_s = 30\n",
        "[experiment]\n",
    ));
    says(
        &e,
        10,
        "experiment",
        &[
            "names no experiment",
            "[experiment.grasp], [experiment.readout]",
        ],
    );
    // The papers' experiments are not this binary's.
    let e = err(&HAND.replace(
        "[experiment.grasp]",
        "[experiment.weight]\n[experiment.grasp]",
    ));
    assert!(e.to_string().contains("unknown field `weight`"), "{e}");
}

#[test]
fn a_pad_names_one_bus_or_one_board() {
    use handstack::scene::parts::PadWiring;
    // HAND is 12 lines; the pad's table follows on line 13.
    let pad = |keys: &str| format!("{HAND}[sensors.imu_pad]\n{keys}");
    let wiring = |keys: &str| {
        let s = Scene::parse("ok.toml", &pad(keys)).expect("valid");
        let p = s.file.sensors.imu_pad.expect("the pad").into_inner();
        p.wiring()
            .map(|w| (w.path().to_owned(), matches!(w, PadWiring::Firmata { .. })))
    };
    assert_eq!(
        wiring("i2c_bus = \"/dev/i2c-2\"\n"),
        Some(("/dev/i2c-2".into(), false))
    );
    let s = Scene::parse("ok.toml", &pad("firmata_port = \"/dev/ttyACM0\"\n")).expect("valid");
    let p = s.file.sensors.imu_pad.expect("the pad").into_inner();
    assert_eq!(
        p.wiring(),
        Some(PadWiring::Firmata {
            port: "/dev/ttyACM0",
            baud: 57_600
        })
    );
    let s = Scene::parse(
        "ok.toml",
        &pad("firmata_port = \"/dev/ttyACM0\"\nfirmata_baud = 115200\n"),
    )
    .expect("valid");
    let p = s.file.sensors.imu_pad.expect("the pad").into_inner();
    assert!(matches!(
        p.wiring(),
        Some(PadWiring::Firmata { baud: 115_200, .. })
    ));

    let e = err(&pad(""));
    says(
        &e,
        13,
        "sensors.imu_pad",
        &["names no hardware (`i2c_bus` or `firmata_port`)"],
    );
    let e = err(&pad(
        "i2c_bus = \"/dev/i2c-2\"\nfirmata_port = \"/dev/ttyACM0\"\n",
    ));
    says(
        &e,
        15,
        "sensors.imu_pad.firmata_port",
        &["is named beside `i2c_bus`", "one of `i2c_bus`"],
    );
    let e = err(&pad("i2c_bus = \"/dev/i2c-2\"\nfirmata_baud = 57600\n"));
    says(
        &e,
        15,
        "sensors.imu_pad.firmata_baud",
        &["is named without `firmata_port`"],
    );
    let e = err(&pad(
        "firmata_port = \"/dev/ttyACM0\"\nfirmata_baud = 57000\n",
    ));
    says(
        &e,
        15,
        "sensors.imu_pad.firmata_baud",
        &["is 57000", "57600, 74880, 115200"],
    );
}
