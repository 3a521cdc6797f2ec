//! Bad scene files: each error names the file, the line and column, the key and what is
//! allowed; nothing panics.

use handstack::scene::SceneError;
use paper_scenes::scene::PaperScene as Scene;

const GOOD: &str = r#"title = "ok"
[sensors.fingertip]
osr = 4096
[estimators.force]
model = "sim"
[experiment.weight]
"#;

fn err(text: &str) -> SceneError {
    match Scene::parse("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Asserts the message holds every one of `parts` and the error sits on `line`.
fn names(e: &SceneError, line: usize, parts: &[&str]) {
    let msg = e.to_string();
    assert!(msg.starts_with(&format!("bad.toml:{line}:")), "{msg}");
    assert_eq!(e.location().map(|l| l.line), Some(line), "{msg}");
    for p in parts {
        assert!(msg.contains(p), "{msg:?} lacks {p:?}");
    }
}

#[test]
fn the_good_scene_parses() {
    let s = Scene::parse("dir/good.toml", GOOD).expect("valid");
    assert_eq!(s.name, "good");
    assert_eq!(s.sim.fingertip.as_ref().map(|f| f.osr), Some(4096));
}

#[test]
fn unknown_sensor_lists_the_known_ones() {
    let e = err(&GOOD.replace(
        "[sensors.fingertip]\nosr = 4096",
        "[sensors.bmp280]\nosr = 4096",
    ));
    names(
        &e,
        2,
        &[
            "unknown field `bmp280`",
            "fingertip",
            "imu_pad",
            "underactuated",
        ],
    );
    assert_eq!(e.key(), Some("bmp280"));
}

#[test]
fn unknown_key_is_named() {
    let e = err(&GOOD.replace("osr = 4096", "osr = 4096\noversampling = 2"));
    names(
        &e,
        4,
        &[
            "unknown field `oversampling`",
            "osr",
            "i2c_buses",
            "address",
        ],
    );
}

#[test]
fn missing_field_is_named() {
    let e = err(&GOOD.replace("title = \"ok\"\n", ""));
    names(&e, 1, &["missing field `title`"]);
    let e = err(&format!("{GOOD}[estimators.contact]\n"));
    names(&e, 7, &["missing field `locators`"]);
    assert_eq!(e.key(), Some("locators"));
    // A force DNN is a built-in `model` or a `weights` file: neither is said so.
    let e = err(&GOOD.replace("model = \"sim\"", ""));
    names(
        &e,
        4,
        &[
            "`estimators.force` names no force DNN",
            "weights = \"FILE\"",
        ],
    );
}

#[test]
fn wrong_type_says_what_was_expected() {
    let e = err(&GOOD.replace("osr = 4096", "osr = \"high\""));
    names(
        &e,
        3,
        &[
            "`sensors.fingertip.osr` is the string \"high\"",
            "allowed: a whole number",
        ],
    );
    let e = err(&GOOD.replace("model = \"sim\"", "model = \"huge\""));
    names(&e, 5, &["unknown variant `huge`", "table1", "sim"]);
}

#[test]
fn out_of_range_osr_lists_the_ratios() {
    let e = err(&GOOD.replace("osr = 4096", "osr = 8192"));
    names(
        &e,
        3,
        &[
            "`sensors.fingertip.osr` is 8192",
            "256, 512, 1024, 2048, 4096",
        ],
    );
    assert!(matches!(e.location(), Some(l) if l.column == 7), "{e}");
    // The exact text a user reads: the file once, line:col, the key, what is allowed; the same
    // through the run's error (not the file twice).
    let text = "bad.toml:3:7: `sensors.fingertip.osr` is 8192, an OSR the MS5611 does not have; \
                allowed: 256, 512, 1024, 2048, 4096";
    assert_eq!(e.to_string(), text);
    assert_eq!(paper_scenes::Error::from(e).to_string(), text);
}

#[test]
fn impossible_combinations_are_named() {
    // A CNN locator without the ICM-20789 pad.
    let e = err(&format!(
        "{GOOD}[estimators.contact]\nlocators = [\"aot\", \"cnn\"]\n"
    ));
    names(
        &e,
        8,
        &[
            "`estimators.contact.locators` names \"cnn\" without its sensor",
            "[sensors.imu_pad]",
        ],
    );
    // A grasp controller without a hand.
    let e = err(&format!("{GOOD}[controller]\npreset = \"grasp\"\n"));
    names(
        &e,
        7,
        &[
            "`controller` is a grasp controller without a hand",
            "[hand]",
        ],
    );
    // A softness classifier without the underactuated hand.
    let e = err(&format!("{GOOD}[estimators.softness]\n"));
    names(&e, 7, &["`estimators.softness`", "[sensors.underactuated]"]);
    // The force DNN without the fingertip it reads.
    let e = err(&GOOD.replace("[sensors.fingertip]\nosr = 4096\n", ""));
    names(
        &e,
        2,
        &["`estimators.force` needs the fingertip's pressures"],
    );
    // A sensor knob repeated in the physics table.
    let e = err(&format!(
        "{GOOD}[sim]\nseed = 1\n[sim.fingertip]\nosr = 256\n"
    ));
    names(
        &e,
        10,
        &[
            "`sim.fingertip.osr` repeats a sensor knob",
            "[sensors.fingertip]",
        ],
    );
    // Three MS5611 need three buses.
    let e = err(&GOOD.replace("osr = 4096", "osr = 4096\ni2c_buses = [\"/dev/i2c-1\"]"));
    names(
        &e,
        4,
        &[
            "`sensors.fingertip.i2c_buses` names 1 buses",
            "three device paths",
        ],
    );
    // No experiment at all.
    let e = err(&GOOD.replace("[experiment.weight]\n", "[experiment]\n"));
    names(&e, 6, &["`experiment` names no experiment"]);
}

#[test]
fn an_unreadable_file_is_a_read_error() {
    let e = Scene::load(std::path::Path::new("/nonexistent/scene.toml")).expect_err("no file");
    assert!(matches!(e, SceneError::Read { .. }));
    // The file first, once, as the other scene errors name it.
    let text = e.to_string();
    assert!(
        text.starts_with("/nonexistent/scene.toml: cannot read: "),
        "{text}"
    );
    assert_eq!(text.matches("/nonexistent/scene.toml").count(), 1, "{text}");
}

const TAP: &str = r#"title = "tap"
[sim]
seed = 10
[sim.arm]
time_scale = 10
[sensors.imu_pad]
pressure_mode = "LowNoise"
[estimators.contact]
locators = ["cnn"]
[arm]
model = "ur3"
[experiment.tap]
taps_per_region = 10
"#;

#[test]
fn sim_arm_sets_the_simulated_controllers_time_scale() {
    let s = Scene::parse("tap.toml", TAP).expect("valid");
    assert_eq!(s.arm_sim.time_scale.factor(), 10.0);
    assert_eq!(s.sim.seed, 10, "hand-sim still reads the rest of [sim]");
    // Without [sim.arm] the simulated controller runs in real time.
    let s =
        Scene::parse("tap.toml", &TAP.replace("[sim.arm]\ntime_scale = 10\n", "")).expect("valid");
    assert_eq!(s.arm_sim.time_scale.factor(), 1.0);
}

#[test]
fn bad_sim_arm_and_tap_counts_name_the_key() {
    let e = err(&TAP.replace("time_scale = 10", "time_scale = 0"));
    names(&e, 5, &["`sim.arm.time_scale`", "finite and positive"]);
    let e = err(&TAP.replace("time_scale = 10", "time_scale = 10\nspeed = 2"));
    names(&e, 6, &["speed"]);
    // A host is a real controller: nothing to simulate.
    let e = err(&TAP.replace(
        "model = \"ur3\"",
        "model = \"ur3\"\nhost = \"192.168.1.10\"",
    ));
    names(
        &e,
        4,
        &["`sim.arm` simulates an arm the scene reaches at a host"],
    );
    let e = err(&TAP.replace("taps_per_region = 10", "taps_per_region = 0"));
    names(&e, 13, &["`experiment.tap.taps_per_region` is 0", "1…100"]);
    // Unknown keys of [sim] itself are still refused by hand-sim's table.
    let e = err(&TAP.replace("seed = 10", "seed = 10\nsede = 3"));
    names(&e, 4, &["sede"]);
}
