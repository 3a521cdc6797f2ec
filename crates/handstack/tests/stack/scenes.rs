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

/// A parsed scene's experiments.
fn experiments(s: &Scene) -> &handstack::scene::experiment::Experiments {
    s.file.experiment.get_ref()
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
        &[
            "names no hardware (`i2c_buses`, `firmata_port` or `serial_port`)",
            "real devices only",
        ],
    );
    let e = err(&HAND.replace("serial_port = \"/dev/ttyUSB0\"\n", ""));
    says(&e, 7, "hand", &["names no hardware (`serial_port`)"]);
    // An arm needs its host in a node's scene; a scene to run moves it only in a tap-to-move.
    let arm = format!("{HAND}[arm]\nmodel = \"ur3\"\n");
    let e = handstack::scene::NodeScene::parse("bad.toml", &arm).expect_err("no host");
    says(&e, 13, "arm", &["names no hardware (`host`)"]);
    let e = err(&format!("{arm}host = \"192.168.1.10\"\n"));
    says(
        &e,
        13,
        "arm",
        &[
            "no experiment of this scene moves it",
            "[experiment.tap_to_move]",
        ],
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
    // The papers' simulated experiments are not this binary's.
    let e = err(&HAND.replace("[experiment.grasp]", "[experiment.tap]\n[experiment.grasp]"));
    assert!(e.to_string().contains("unknown field `tap`"), "{e}");
}

const SOFTNESS: &str = r#"title = "softness"
[sensors.underactuated]
[estimators.softness]
[hand]
model = "underactuated4"
serial_port = "/dev/ttyACM0"
[experiment.softness]
expect = "hard"
"#;

#[test]
fn the_underactuated_hand_runs_the_softness_experiment_and_nothing_else() {
    let s = Scene::parse("sponge.toml", SOFTNESS).expect("valid");
    let x = experiments(&s).softness.as_ref().expect("softness");
    assert_eq!(x.get_ref().plan().window_s, 14.0);
    assert_eq!(x.get_ref().expected(), Some(hand_traits::Softness::Hard));
    // A servo hand cannot run it, the underactuated hand cannot run the servo grasp loop.
    let servo = SOFTNESS.replace("underactuated4", "mx28");
    says(
        &err(&servo),
        2,
        "sensors.underactuated",
        &["[hand] model = \"underactuated4\""],
    );
    let grasp = format!(
        "{}[sensors.fingertip]\nosr = 1024\ni2c_buses = [\"/dev/i2c-1\", \"/dev/i2c-3\", \
         \"/dev/i2c-4\"]\n[controller]\npreset = \"grasp\"\n[experiment.grasp]\n\
         torque_band = [250, 320]\nhold_s = 30\n",
        SOFTNESS.replace("[experiment.softness]\nexpect = \"hard\"\n", "")
    );
    says(
        &err(&grasp),
        4,
        "hand.model",
        &["servo grasp loop cannot drive"],
    );
    // Its sensors are read through its board: real only with the hand's serial port.
    let no_port = SOFTNESS.replace("serial_port = \"/dev/ttyACM0\"\n", "");
    says(
        &err(&no_port),
        4,
        "hand",
        &["names no hardware (`serial_port`)"],
    );
    // No ROS 2 node for it.
    let e = handstack::scene::NodeScene::parse("bad.toml", SOFTNESS).expect_err("no node");
    says(&e, 4, "hand.model", &["no ROS 2 node"]);
}

#[test]
fn a_softness_run_grasps_objects_in_turn_with_a_net_built_in_or_beside_the_scene() {
    let objects = SOFTNESS.replace(
        "expect = \"hard\"",
        "objects = [\"soft\", \"hard\", \"soft\"]",
    );
    let s = Scene::parse("objects.toml", &objects).expect("valid");
    let x = experiments(&s).softness.as_ref().expect("softness");
    use hand_traits::Softness::{Hard, Soft};
    assert_eq!(x.get_ref().objects(), [Soft, Hard, Soft]);
    assert!(s.softness.is_none());
    assert_eq!(
        s.softness_net().flat(),
        tactile_nets::pretrained::SOFTNESS.flat()
    );
    says(
        &err(&objects.replace("\"hard\"", "\"squishy\"")),
        8,
        "experiment.softness.objects",
        &["is \"squishy\"", "\"soft\", \"moderate\" or \"hard\""],
    );
    says(
        &err(&objects.replace("objects = [\"soft\", \"hard\", \"soft\"]", "objects = []")),
        8,
        "experiment.softness.objects",
        &["is empty"],
    );
    says(
        &err(&format!("{objects}expect = \"hard\"\n")),
        8,
        "experiment.softness.objects",
        &["is given with `expect`"],
    );
    // A weights file of the user's own hand, beside the scene.
    let dir = std::env::temp_dir().join(format!("handstack-scene-soft-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let mut flat = tactile_nets::pretrained::SOFTNESS.flat();
    flat[0] += 0.5;
    let mine = tactile_nets::softness::SoftnessNet::from_flat(
        &flat,
        *tactile_nets::pretrained::SOFTNESS.scale(),
    )
    .expect("a net");
    mine.save(&dir.join("my-hand.safetensors"), serde_json::json!({}))
        .expect("saved");
    let own = objects.replace(
        "[estimators.softness]\n",
        "[estimators.softness]\nweights = \"my-hand.safetensors\"\n",
    );
    let s = Scene::parse(&dir.join("own.toml").display().to_string(), &own).expect("valid");
    assert_eq!(s.softness_net().flat(), flat);
    // Not beside this scene: read relative to the scene, and the error says why.
    says(
        &err(&own),
        4,
        "estimators.softness.weights",
        &[
            "cannot be used",
            "my-hand.safetensors",
            "handstack train softness",
        ],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_underactuated_hands_keys_are_checked_where_they_are_written() {
    let with = |extra: &str| SOFTNESS.replace("[experiment", &format!("{extra}[experiment"));
    says(
        &err(&SOFTNESS.replace("\"hard\"", "\"squishy\"")),
        8,
        "experiment.softness.expect",
        &["\"soft\", \"moderate\" or \"hard\""],
    );
    says(
        &err(&with("wiring = { pot_channels = [3, 5, 6, 7] }\n")),
        7,
        "hand.wiring",
        &["analog channel A3 is wired twice"],
    );
    says(
        &err(&with("ids = [1, 2, 3]\n")),
        4,
        "hand.ids",
        &["a servo hand's key"],
    );
    says(&err(&with("baud = 2000000\n")), 7, "hand.baud", &["57600"]);
    says(
        &err(&with("closing_speed_mm_s = 0\n")
            .replace(
                "expect = \"hard\"\n",
                "expect = \"hard\"\nclosing_speed_mm_s = 0\n",
            )
            .replace("closing_speed_mm_s = 0\n[experiment", "[experiment")),
        9,
        "experiment.softness.closing_speed_mm_s",
        &["0.1…20"],
    );
    let cal = SOFTNESS.replace(
        "[sensors.underactuated]\n",
        "[sensors.underactuated]\nfsr = { exponent = -1 }\n",
    );
    says(&err(&cal), 2, "sensors.underactuated", &["exponent"]);
    // A servo hand's table takes none of the underactuated hand's keys.
    says(
        &err(&HAND.replace(
            "serial_port = \"/dev/ttyUSB0\"\n",
            "serial_port = \"/dev/ttyUSB0\"\ndrive = { mm_per_step = 0.02 }\n",
        )),
        7,
        "hand.drive",
        &["underactuated hand's key"],
    );
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

const WEIGHT: &str = r#"title = "weights on my fingertip"
[sensors.fingertip]
osr = 4096
firmata_port = "/dev/ttyACM0"
[estimators.force]
model = "sim"
[experiment.weight]
weights_gf = [0, 50, 100]
tolerance_gf = 1.5
"#;

#[test]
fn a_weight_series_needs_the_fingertip_and_a_force_dnn_and_checks_its_keys() {
    let s = Scene::parse("weights.toml", WEIGHT).expect("valid");
    let w = s.file.experiment.get_ref().weight.as_ref().expect("weight");
    let plan = w.get_ref().plan();
    assert_eq!(plan.weights_gf, [0.0, 50.0, 100.0]);
    assert_eq!(
        (plan.tolerance_gf, plan.settle_s, plan.average_s),
        (1.5, 1.0, 1.0)
    );
    // Without weights: Table 1's thirteen.
    let table1 =
        Scene::parse("t.toml", &WEIGHT.replace("weights_gf = [0, 50, 100]\n", "")).expect("valid");
    let w = experiments(&table1).weight.as_ref().expect("weight");
    assert_eq!(
        w.get_ref().plan().weights_gf,
        handstack::scene::experiment::TABLE1_WEIGHTS_GF
    );
    says(
        &err(&WEIGHT.replace("[estimators.force]\nmodel = \"sim\"\n", "")),
        5,
        "experiment.weight",
        &["needs the fingertip and a force DNN", "[estimators.force]"],
    );
    says(
        &err(&WEIGHT.replace("[0, 50, 100]", "[0, -5, 100]")),
        8,
        "experiment.weight.weights_gf",
        &["holds -5", "1…50 weights, each 0…1000 gf"],
    );
    says(
        &err(&WEIGHT.replace("[0, 50, 100]", "[]")),
        8,
        "experiment.weight.weights_gf",
        &["has 0 weights"],
    );
    says(
        &err(&WEIGHT.replace("tolerance_gf = 1.5", "tolerance_gf = 0")),
        9,
        "experiment.weight.tolerance_gf",
        &["is 0", "0.01…100"],
    );
    says(
        &err(&format!("{WEIGHT}average_s = 0\n")),
        10,
        "experiment.weight.average_s",
        &["0.1…30"],
    );
    says(
        &err(&format!("{WEIGHT}grams = 5\n")),
        10,
        "grams",
        &["unknown field `grams`", "`weights_gf`"],
    );
}

/// `[estimators.force]` names a built-in model or a weights file beside the scene, not both
/// and not neither; a file it cannot use is refused where it is named, with why.
#[test]
fn a_force_dnn_is_built_in_or_a_weights_file_beside_the_scene() {
    let s = Scene::parse("weights.toml", WEIGHT).expect("valid");
    assert!(matches!(
        s.force,
        Some(handstack::scene::force::ForceNet::BuiltIn(
            handstack::scene::parts::ForceModel::Sim
        ))
    ));
    assert!(
        !s.file
            .experiment
            .get_ref()
            .weight
            .as_ref()
            .expect("weight")
            .get_ref()
            .plan()
            .tare_each_weight
    );
    let dir = std::env::temp_dir().join(format!("handstack-scene-weights-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    tactile_nets::pretrained::force_dnn(handstack::scene::parts::ForceModel::Table1)
        .expect("built-in")
        .save(&dir.join("mine.safetensors"))
        .expect("saved");
    let own = WEIGHT.replace("model = \"sim\"", "weights = \"mine.safetensors\"");
    let s = Scene::parse(&dir.join("own.toml").display().to_string(), &own).expect("valid");
    match &s.force {
        Some(handstack::scene::force::ForceNet::File { path, dnn }) => {
            assert_eq!(path, &dir.join("mine.safetensors"));
            assert_eq!(dnn.range_gf(), [0.0, 200.0]);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(s.force_model(), None);
    // Not beside this scene: the file is read relative to the scene, and the error says why.
    says(
        &err(&own),
        6,
        "estimators.force.weights",
        &[
            "cannot be used",
            "mine.safetensors",
            "relative to the scene file",
        ],
    );
    std::fs::write(dir.join("junk.safetensors"), b"not weights").expect("junk");
    let junk = own.replace("mine.safetensors", "junk.safetensors");
    let e = Scene::parse(&dir.join("junk.toml").display().to_string(), &junk).expect_err("junk");
    assert_eq!(e.key(), Some("estimators.force.weights"), "{e}");
    says(
        &err(&WEIGHT.replace("model = \"sim\"", "model = \"sim\"\nweights = \"x\"")),
        5,
        "estimators.force",
        &["names both a built-in `model` and a `weights` file"],
    );
    says(
        &err(&WEIGHT.replace("model = \"sim\"\n", "")),
        5,
        "estimators.force",
        &["names no force DNN", "`weights = \"FILE\"`"],
    );
    let each =
        Scene::parse("t.toml", &format!("{WEIGHT}tare_each_weight = true\n")).expect("valid");
    let w = experiments(&each).weight.as_ref().expect("weight");
    assert!(w.get_ref().plan().tare_each_weight);
    let _ = std::fs::remove_dir_all(&dir);
}

const TAPS: &str = r#"title = "taps that move my arm"
[sensors.imu_pad]
firmata_port = "/dev/ttyACM0"
[estimators.contact]
locators = ["cnn"]
[arm]
model = "ur3"
host = "192.168.1.10"
[experiment.tap_to_move]
regions = [0, 4, 8]
"#;

#[test]
fn a_contact_cnn_is_built_in_or_a_weights_file_beside_the_scene() {
    let s = Scene::parse("taps.toml", TAPS).expect("valid");
    assert!(s.cnn.is_none());
    let builtin = s.contact_cnn().expect("the built-in CNN");
    assert_eq!(builtin.trigger_offset(), Some(16));
    let dir = std::env::temp_dir().join(format!("handstack-scene-cnn-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let mine = builtin.clone().with_trigger_offset(12).expect("an offset");
    mine.save(&dir.join("my-pad.safetensors")).expect("saved");
    let own = TAPS.replace(
        "locators = [\"cnn\"]\n",
        "locators = [\"cnn\"]\ncnn_weights = \"my-pad.safetensors\"\n",
    );
    let s = Scene::parse(&dir.join("own.toml").display().to_string(), &own).expect("valid");
    assert_eq!(s.cnn.as_ref().and_then(|c| c.trigger_offset()), Some(12));
    assert_eq!(
        s.contact_cnn().expect("the file").trigger_offset(),
        Some(12)
    );
    // The pad node reads it too.
    let node =
        handstack::scene::NodeScene::parse(&dir.join("own.toml").display().to_string(), &own)
            .expect("a node scene");
    assert_eq!(
        node.contact_cnn().expect("the file").trigger_offset(),
        Some(12)
    );
    // Not beside this scene: read relative to the scene, and the error says why.
    says(
        &err(&own),
        6,
        "estimators.contact.cnn_weights",
        &[
            "cannot be used",
            "my-pad.safetensors",
            "handstack train contact-cnn",
        ],
    );
    // A force DNN's file is not a contact CNN.
    tactile_nets::pretrained::force_dnn(handstack::scene::parts::ForceModel::Sim)
        .expect("built-in")
        .save(&dir.join("force.safetensors"))
        .expect("saved");
    let wrong = own.replace("my-pad.safetensors", "force.safetensors");
    let e = Scene::parse(&dir.join("wrong.toml").display().to_string(), &wrong)
        .expect_err("a force DNN");
    assert_eq!(e.key(), Some("estimators.contact.cnn_weights"), "{e}");
    // Weights for a CNN the scene does not run.
    let fingertip = TOUCHES.replace(
        "[experiment.contact]",
        "[estimators.contact]\nlocators = [\"aot\"]\ncnn_weights = \"my-pad.safetensors\"\n\
         [experiment.contact]",
    );
    let e = err(&fingertip);
    says(
        &e,
        7,
        "estimators.contact.cnn_weights",
        &["names a contact CNN the scene does not run"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn tap_to_move_needs_the_pad_the_cnn_and_the_arm_and_checks_its_regions() {
    let s = Scene::parse("taps.toml", TAPS).expect("valid");
    let t = experiments(&s).tap_to_move.as_ref().expect("taps");
    assert_eq!(t.get_ref().regions(), [0, 4, 8]);
    assert_eq!(t.get_ref().wait_s(), 30.0);
    let all = Scene::parse("t.toml", &TAPS.replace("regions = [0, 4, 8]\n", "")).expect("valid");
    let t = experiments(&all).tap_to_move.as_ref().expect("taps");
    assert_eq!(t.get_ref().regions(), (0..9).collect::<Vec<u8>>());
    says(
        &err(&TAPS.replace("[arm]\nmodel = \"ur3\"\nhost = \"192.168.1.10\"\n", "")),
        6,
        "experiment.tap_to_move",
        &["needs the ICM-20789 pad, the contact CNN and the arm"],
    );
    says(
        &err(&TAPS.replace("[0, 4, 8]", "[0, 9]")),
        10,
        "experiment.tap_to_move.regions",
        &["holds 9", "1…90 regions, each 0…8"],
    );
    says(
        &err(&format!("{TAPS}wait_s = 0.5\n")),
        11,
        "experiment.tap_to_move.wait_s",
        &["1…600"],
    );
    // Without the experiment, the arm moves for nothing: refused.
    let idle = TAPS.replace(
        "[experiment.tap_to_move]\nregions = [0, 4, 8]\n",
        "[experiment.readout]\nframes = 10\n",
    );
    says(
        &err(&idle),
        6,
        "arm",
        &["no experiment of this scene moves it"],
    );
}

const TOUCHES: &str = r#"title = "where my fingertip is touched"
[sensors.fingertip]
osr = 1024
serial_port = "/dev/ttyUSB0"
[experiment.contact]
cells = [[1, 1], [4, 6]]
"#;

#[test]
fn contact_needs_the_fingertips_microcontroller_and_checks_its_cells() {
    use handstack::scene::parts::FingertipWiring;
    let s = Scene::parse("touches.toml", TOUCHES).expect("valid");
    let c = experiments(&s).contact.as_ref().expect("contact");
    assert_eq!(c.get_ref().cells(), [(1, 1), (4, 6)]);
    assert_eq!(c.get_ref().wait_s(), 30.0);
    let tip = s.file.sensors.fingertip.as_ref().expect("tip").get_ref();
    assert_eq!(
        tip.wiring(),
        Some(FingertipWiring::Mcu {
            port: "/dev/ttyUSB0",
            baud: fingertip_link::BAUD
        })
    );
    let all =
        Scene::parse("t.toml", &TOUCHES.replace("cells = [[1, 1], [4, 6]]\n", "")).expect("valid");
    let c = experiments(&all).contact.as_ref().expect("contact");
    assert_eq!(c.get_ref().cells().len(), 24);
    assert_eq!(c.get_ref().cells()[7], (2, 2));
    // The chips read by this computer: too slow for arrival times.
    says(
        &err(&TOUCHES.replace(
            "serial_port = \"/dev/ttyUSB0\"",
            "firmata_port = \"/dev/ttyACM0\"",
        )),
        5,
        "experiment.contact",
        &["needs the fingertip's microcontroller", "`serial_port`"],
    );
    says(
        &err(&TOUCHES.replace("[4, 6]", "[5, 1]")),
        6,
        "experiment.contact.cells",
        &["holds [5, 1]", "row 1…4 and column 1…6"],
    );
    says(
        &err(&TOUCHES.replace("[[1, 1], [4, 6]]", "[]")),
        6,
        "experiment.contact.cells",
        &["has 0 cells"],
    );
    says(
        &err(&format!("{TOUCHES}wait_s = 0\n")),
        7,
        "experiment.contact.wait_s",
        &["1…600"],
    );
    // One wiring: the board reads the chips, or this computer does.
    says(
        &err(&TOUCHES.replace(
            "osr = 1024\n",
            "osr = 1024\nfirmata_port = \"/dev/ttyACM0\"\n",
        )),
        5,
        "sensors.fingertip.serial_port",
        &["beside the chips' own wiring"],
    );
    says(
        &err(&TOUCHES.replace("osr = 1024\n", "osr = 1024\nbaud = 0\n")),
        4,
        "sensors.fingertip.baud",
        &["is 0", "460800"],
    );
    let without = TOUCHES.replace(
        "serial_port = \"/dev/ttyUSB0\"\n",
        "firmata_port = \"/dev/ttyACM0\"\nbaud = 115200\n",
    );
    says(
        &err(&without.replace(
            "[experiment.contact]\ncells = [[1, 1], [4, 6]]\n",
            "[experiment.readout]\nframes = 5\n",
        )),
        5,
        "sensors.fingertip.baud",
        &["without `serial_port`"],
    );
}

#[test]
fn a_contact_mlp_of_ones_own_is_a_weights_file_beside_the_scene() {
    let s = Scene::parse("touches.toml", TOUCHES).expect("valid");
    assert!(s.mlp.is_none(), "the board's own MLP by default");
    let dir = std::env::temp_dir().join(format!("handstack-scene-mlp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    tactile_nets::pretrained::contact_mlp(1024)
        .expect("built-in")
        .save(&dir.join("my-tip.safetensors"))
        .expect("saved");
    let own = TOUCHES.replace(
        "[experiment.contact]",
        "[estimators.contact]\nlocators = [\"mlp\"]\nmlp_weights = \"my-tip.safetensors\"\n\
         [experiment.contact]",
    );
    let s = Scene::parse(&dir.join("own.toml").display().to_string(), &own).expect("valid");
    assert_eq!(s.mlp.as_ref().map(|m| m.catalogue().len()), Some(68));
    // Not beside this scene: read relative to the scene, and the error says why.
    says(
        &err(&own),
        7,
        "estimators.contact.mlp_weights",
        &[
            "cannot be used",
            "my-tip.safetensors",
            "handstack train contact-mlp",
        ],
    );
    // A contact CNN's file is not a contact MLP.
    tactile_nets::pretrained::contact_cnn(tactile_nets::contact_cnn::Variant::Paper)
        .expect("built-in")
        .save(&dir.join("cnn.safetensors"))
        .expect("saved");
    let wrong = own.replace("my-tip.safetensors", "cnn.safetensors");
    let e = Scene::parse(&dir.join("wrong.toml").display().to_string(), &wrong).expect_err("a CNN");
    assert_eq!(e.key(), Some("estimators.contact.mlp_weights"), "{e}");
    // Weights for an MLP the scene does not run.
    let e = err(&own.replace("locators = [\"mlp\"]", "locators = [\"aot\"]"));
    says(
        &e,
        7,
        "estimators.contact.mlp_weights",
        &["names a contact MLP the scene does not run"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
