//! The seed corpora: valid inputs for each target, from the repository's fixtures, the
//! trained models, the protocols' documented byte vectors and exchanges captured from the
//! simulators (`cargo xtask fuzz --seed`
//! writes them to `fuzz/seeds/TARGET/`).

use std::path::Path;
use std::time::Duration;

use dxl_sim::{SimConfig, answer_bytes};
use hand_control::control_table::MX_28;
use hand_control::protocol::{encode, instruction_id as ins, packet_id};

use crate::dxl::IDS;
use crate::files::FILE_SEPARATOR;

/// One seed: a file name and its bytes.
pub type Seed = (String, Vec<u8>);

/// Lines of a CSV a seed keeps: its comment lines, its header and this many rows.
const CSV_ROWS: usize = 24;

/// The seeds of target `name`, read from the repository at `root`.
///
/// # Errors
/// A fixture that cannot be read.
pub fn seeds(root: &Path, name: &str) -> std::io::Result<Vec<Seed>> {
    Ok(match name {
        "dxl_status" => dxl_status(),
        "dxl_sim" => requests()
            .into_iter()
            .map(|(n, wire)| (n, [&[16u8][..], &wire].concat()))
            .collect(),
        "firmata" => firmata(),
        "fingertip_link" => fingertip_link(),
        "ur_rtde" => ur_rtde(),
        "ur_dashboard" => ur_dashboard(),
        "ur_script" => ur_script(),
        "fis" => files_with(&root.join("fixtures/fuzzy"), "fis", &[])?,
        "fll" => files_with(&root.join("fixtures/fuzzy"), "fll", &[])?,
        "scene" => {
            let mut s = files_with(&root.join("fixtures/scenes"), "toml", &[])?;
            s.extend(files_with(
                &root.join("crates/handstack/tests/stack/scenes"),
                "toml",
                &[],
            )?);
            s
        }
        "model" => models(root)?,
        "dataset" => datasets(root)?,
        "cdr" => cdr(),
        _ => Vec::new(),
    })
}

/// Every file in `dir` ending in `.ext`, each behind `prefix`.
fn files_with(dir: &Path, ext: &str, prefix: &[u8]) -> std::io::Result<Vec<Seed>> {
    let mut out = Vec::new();
    if !dir.is_dir() {
        return Ok(out);
    }
    let mut paths: Vec<_> = std::fs::read_dir(dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    paths.sort();
    for p in paths {
        if p.extension().and_then(|e| e.to_str()) == Some(ext) {
            let stem = p.file_stem().and_then(|s| s.to_str()).unwrap_or("file");
            out.push((stem.to_owned(), [prefix, &std::fs::read(&p)?].concat()));
        }
    }
    Ok(out)
}

/// One instruction packet: ID, instruction, parameters.
type Request<'a> = (u8, u8, &'a [u8]);

/// Requests a client sends the MX-28 bus, one seed each (broadcast and unicast).
fn requests() -> Vec<Seed> {
    let t = &MX_28;
    let at = |r: &hand_control::control_table::Register| r.address.to_le_bytes();
    let (pos, pos_n) = (at(&t.present_position), u16::from(t.present_position.width));
    let read_pos = [&pos[..], &pos_n.to_le_bytes()].concat();
    let mut torque_on = at(&t.torque_enable).to_vec();
    torque_on.push(1);
    let goal = [&at(&t.goal_position)[..], &2048_i32.to_le_bytes()].concat();
    let mut sync_read = read_pos.clone();
    sync_read.extend_from_slice(&IDS);
    let mut sync_write = [&at(&t.goal_position)[..], &4_u16.to_le_bytes()].concat();
    for id in IDS {
        sync_write.push(id);
        sync_write.extend_from_slice(&1024_i32.to_le_bytes());
    }
    let mut bulk_read = Vec::new();
    for id in IDS {
        bulk_read.push(id);
        bulk_read.extend_from_slice(&read_pos);
    }
    let frames: [(&str, &[Request<'_>]); 9] = [
        ("ping_broadcast", &[(packet_id::BROADCAST, ins::PING, &[])]),
        ("read_position", &[(1, ins::READ, &read_pos)]),
        ("torque_on", &[(2, ins::WRITE, &torque_on)]),
        (
            "reg_write_action",
            &[
                (3, ins::REG_WRITE, &goal),
                (packet_id::BROADCAST, ins::ACTION, &[]),
            ],
        ),
        (
            "sync_read",
            &[(packet_id::BROADCAST, ins::SYNC_READ, &sync_read)],
        ),
        (
            "sync_write",
            &[
                (2, ins::WRITE, &torque_on),
                (packet_id::BROADCAST, ins::SYNC_WRITE, &sync_write),
            ],
        ),
        (
            "bulk_read",
            &[(packet_id::BROADCAST, ins::BULK_READ, &bulk_read)],
        ),
        ("reboot", &[(1, ins::REBOOT, &[])]),
        ("factory_reset", &[(2, ins::FACTORY_RESET, &[0x02])]),
    ];
    frames
        .iter()
        .map(|(name, frames)| {
            let mut wire = Vec::new();
            for (id, instruction, params) in *frames {
                encode(&mut wire, *id, *instruction, params);
            }
            ((*name).to_owned(), wire)
        })
        .collect()
}

/// The simulated bus's answers to [`requests`] (a capture of the bus's side), as the
/// replies the driver decodes: `[chunk, expect, count, bytes…]`.
fn dxl_status() -> Vec<Seed> {
    requests()
        .into_iter()
        .filter_map(|(name, wire)| {
            let answers = answer_bytes(
                &SimConfig::with_ids(&IDS),
                &wire,
                wire.len(),
                Duration::from_millis(100),
            );
            // The data bytes per answer: the first status packet's LEN − 4 (instruction,
            // error, CRC).
            let len = usize::from(u16::from_le_bytes([*answers.get(5)?, *answers.get(6)?]));
            let count = u8::try_from(len.checked_sub(4)?).ok()?;
            let frames = answers
                .windows(4)
                .filter(|w| *w == hand_control::protocol::HEADER)
                .count();
            let expect = u8::try_from(frames.clamp(1, 3) - 1).ok()?;
            Some((name, [&[7, expect, count][..], &answers].concat()))
        })
        .collect()
}

/// Every trained model's weights file, behind the byte that picks its kind.
fn models(root: &Path) -> std::io::Result<Vec<Seed>> {
    let models = root.join("crates/tactile-nets/models");
    let mut out = Vec::new();
    for (kind, dir) in ["contact_mlp", "contact_cnn", "force_dnn", "softness"]
        .iter()
        .enumerate()
    {
        let kind = u8::try_from(kind).unwrap_or(0);
        let mut files = files_with(&models.join(dir), "safetensors", &[kind])?;
        // Up to two layouts per kind of network, one file each: a file as long as one already
        // taken has its layout (the contact CNN's 1.2 mm net is the paper net's).
        let mut sizes = Vec::new();
        files.retain(|(_, b)| {
            let new = !sizes.contains(&b.len());
            sizes.push(b.len());
            new
        });
        files.truncate(2);
        out.extend(files.into_iter().map(|(n, b)| (format!("{dir}-{n}"), b)));
    }
    Ok(out)
}

/// The head of a CSV: its comments, its header and [`CSV_ROWS`] rows (all rows of the first
/// `keys` values of column 0 when `keys` is given).
fn csv_head(text: &str, keys: Option<usize>) -> String {
    let mut out = String::new();
    let mut rows = 0;
    let mut seen: Vec<&str> = Vec::new();
    let mut header = false;
    for line in text.lines() {
        if line.starts_with('#') || !header {
            header |= !line.starts_with('#');
            out.push_str(line);
            out.push('\n');
            continue;
        }
        let key = line.split(',').next().unwrap_or("");
        let keep = match keys {
            Some(k) => {
                if !seen.contains(&key) {
                    seen.push(key);
                }
                seen.len() <= k
            }
            None => rows < CSV_ROWS,
        };
        if !keep {
            break;
        }
        rows += 1;
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// Small datasets cut from the committed ones, behind the byte that picks the reader.
fn datasets(root: &Path) -> std::io::Result<Vec<Seed>> {
    let d = root.join("fixtures/datasets");
    let read = |p: &str| std::fs::read_to_string(d.join(p));
    let sep = char::from(FILE_SEPARATOR);
    let taps = csv_head(&read("fingertip/taps.csv")?, Some(2));
    let series = csv_head(&read("fingertip/series.csv")?, Some(2));
    let grasps = csv_head(&read("underactuated/grasps.csv")?, Some(2));
    let samples = csv_head(&read("underactuated/train.csv")?, Some(2));
    Ok(vec![
        (
            "fingertip".into(),
            format!("\0{taps}{sep}{series}").into_bytes(),
        ),
        (
            "imu_pad".into(),
            format!("\u{1}{}", csv_head(&read("imu_pad/taps.csv")?, Some(2))).into_bytes(),
        ),
        (
            "underactuated".into(),
            format!("\u{2}{grasps}{sep}{samples}").into_bytes(),
        ),
        (
            "weights".into(),
            format!(
                "\u{3}{}",
                csv_head(&read("fingertip/weights.csv")?, Some(1))
            )
            .into_bytes(),
        ),
    ])
}

/// One message of each type a node decodes, and an attachment, behind the byte that picks it.
fn cdr() -> Vec<Seed> {
    use hand_zenoh::attachment::Attachment;
    use hand_zenoh::msg::Message;
    use hand_zenoh::msg::geometry_msgs::{PoseStamped, WrenchStamped};
    use hand_zenoh::msg::handstack_msgs::{
        ContactArray, GraspState, GripperCommand, PressureFrame, SensorInfo,
    };
    use hand_zenoh::msg::sensor_msgs::{Imu, JointState};
    use hand_zenoh::msg::std_srvs::{TriggerRequest, TriggerResponse};

    fn one<M: Message + Default>(kind: u8) -> Seed {
        (
            M::NAME.replace('/', "_"),
            [&[kind][..], &M::default().to_cdr()].concat(),
        )
    }
    let mut frame = PressureFrame {
        pressure_pa: vec![101_325.0; 3],
        ..PressureFrame::default()
    };
    frame.header.frame_id = "hand0/finger0".into();
    let joints = JointState {
        name: vec!["finger0".into(), "finger1".into()],
        position: vec![0.5, 1.0],
        ..JointState::default()
    };
    let attachment = Attachment {
        sequence_number: 7,
        source_timestamp: 1_700_000_000_000_000_000,
        source_gid: [0xAB; 16],
    };
    vec![
        (
            "pressure_frame_3".into(),
            [&[0u8][..], &frame.to_cdr()].concat(),
        ),
        one::<ContactArray>(1),
        one::<SensorInfo>(2),
        one::<GraspState>(3),
        one::<GripperCommand>(4),
        one::<WrenchStamped>(5),
        one::<Imu>(6),
        (
            "joint_state_2".into(),
            [&[7u8][..], &joints.to_cdr()].concat(),
        ),
        one::<PoseStamped>(8),
        one::<TriggerRequest>(9),
        one::<TriggerResponse>(10),
        (
            "attachment".into(),
            [&[11u8][..], &attachment.encode()].concat(),
        ),
    ]
}

/// A ur_rtde session's packages as its client sends them: version, controller version, an
/// output recipe, an input recipe, start, input data, pause.
fn ur_rtde() -> Vec<Seed> {
    use ur_sim::fuzzing::{
        DATA_PACKAGE, GET_URCONTROL_VERSION, PAUSE, REQUEST_PROTOCOL_VERSION, SETUP_INPUTS,
        SETUP_OUTPUTS, START, package,
    };
    let mut outputs = 125.0_f64.to_be_bytes().to_vec();
    outputs.extend_from_slice(b"timestamp,actual_q,actual_TCP_pose,output_int_register_0");
    let mut data = vec![1];
    data.extend_from_slice(&7_i32.to_be_bytes());
    data.extend_from_slice(&0.5_f64.to_be_bytes());
    let session: [(u8, &[u8]); 7] = [
        (REQUEST_PROTOCOL_VERSION, &2_u16.to_be_bytes()),
        (GET_URCONTROL_VERSION, &[]),
        (SETUP_OUTPUTS, &outputs),
        (
            SETUP_INPUTS,
            b"input_int_register_0,input_double_register_0",
        ),
        (START, &[]),
        (DATA_PACKAGE, &data),
        (PAUSE, &[]),
    ];
    let mut wire = Vec::new();
    for (kind, payload) in session {
        wire.extend(package(kind, payload).unwrap_or_default());
    }
    vec![("session".into(), wire)]
}

/// Dashboard commands a client sends (Universal Robots' dashboard server command list).
fn ur_dashboard() -> Vec<Seed> {
    let lines = "PolyscopeVersion\nrobotmode\nsafetystatus\npower on\nbrake release\n\
                 unlock protective stop\nplay\nprogramState\nrunning\nstop\n\
                 addToLog fuzz\nget robot model\nquit\n";
    vec![("session".into(), lines.as_bytes().to_vec())]
}

/// A script as ur_rtde sends it: the shape the controller recognises as its control script
/// (register offset 0), then a script it does not run.
fn ur_script() -> Vec<Seed> {
    let control = "def rtde_control():\n# HEADER_BEGIN\n    global reg_offset_float = # float register offset\n0\n    global reg_offset_int = # int register offset\n0\n    def signal_ready():\n    end\n    def process_cmd(cmd):\n    end\nend\n";
    vec![
        ("rtde_control".into(), control.as_bytes().to_vec()),
        (
            "other".into(),
            b"def other():\n  movej([0,0,0,0,0,0])\nend\n".to_vec(),
        ),
    ]
}

/// The byte vectors of firmata-host's tests (`tests/it/vectors.rs`, `tests/it/parser.rs`:
/// protocol.md, i2c.md and AccelStepperFirmata's reports, and streams cut, interleaved and
/// garbled), the reports its encoders make, and sessions of the simulated Arduino
/// (firmata-sim) answering a host, one seed each, read in chunks of 5 bytes: `[5, bytes…]`.
/// A fingertip's line: frames at rest and in contact, a fault frame, noise with sync bytes
/// before a frame, a flipped bit, a lost byte.
fn fingertip_link() -> Vec<Seed> {
    use fingertip_link::Frame;
    let rest = |seq: u8| Frame {
        seq,
        t_us: u32::from(seq) * 6180,
        pressure_pa: [101_320, 101_290, 101_340],
        tared: true,
        force_gf: Some(0.4),
        torque_raw: 0,
        ..Frame::default()
    };
    let pressed = Frame {
        in_contact: true,
        pressure_pa: [102_110, 101_560, 101_400],
        force_gf: Some(48.7),
        grid_cell: Some(3),
        pad_cell: Some(6),
        torque_raw: 655,
        ..rest(3)
    };
    let line: Vec<u8> = [rest(1), rest(2), pressed, Frame::fault(24_720, 4)]
        .iter()
        .flat_map(Frame::encode)
        .collect();
    let mut noisy = vec![0xA5, 0x00, 0xA5, 0xA5, 0x13];
    noisy.extend_from_slice(&line);
    let mut flipped = line.clone();
    flipped[fingertip_link::LEN + 12] ^= 0x10;
    let mut lost = line.clone();
    lost.remove(fingertip_link::LEN + 5);
    [
        ("frames", line),
        ("noise-then-frames", noisy),
        ("flipped-bit", flipped),
        ("lost-byte", lost),
    ]
    .into_iter()
    .map(|(n, b)| (n.to_owned(), b))
    .collect()
}

fn firmata() -> Vec<Seed> {
    use firmata_host::parser::SYSEX_CAPACITY;
    use firmata_host::protocol as p;

    fn with(f: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
        let mut out = Vec::new();
        f(&mut out);
        out
    }
    let firmware = with(|o| p::encode_firmware_report(o, 2, 5, "StandardFirmata"));
    let i2c_reply = with(|o| p::encode_i2c_reply(o, 0x77, 0xA2, &[0x9C, 0xBF]));
    let mut interleaved = vec![0xE0, 0x10, 0x02, 0x91, 0x01, 0x00];
    p::encode_i2c_reply(&mut interleaved, 0x68, 0x75, &[0x03]);
    interleaved.extend_from_slice(&[0xE1, 0x7F, 0x07]);
    let mut overlong = vec![p::START_SYSEX, p::STRING_DATA];
    overlong.extend(std::iter::repeat_n(0x41, SYSEX_CAPACITY + 10));
    overlong.extend_from_slice(&[p::END_SYSEX, 0xF9, 2, 6]);
    let host = with(|o| {
        p::encode_version_query(o);
        p::encode_sysex_query(o, p::CAPABILITY_QUERY);
        p::encode_set_pin_mode(o, 13, firmata_host::PinMode::Output);
        p::encode_set_digital_pin_value(o, 13, true);
        p::encode_report_analog(o, 2, true);
        p::encode_sampling_interval(o, 19);
        p::encode_i2c_write(o, 0x77, &[0x1E]);
    });
    let mut seeds: Vec<(&str, Vec<u8>)> = vec![
        ("analog", vec![0xE0, 0x7F, 0x07]),
        ("digital", vec![0x92, 0x05, 0x01]),
        ("version", with(|o| p::encode_version_report(o, 2, 6))),
        ("firmware", firmware.clone()),
        (
            "capabilities_uno_a0",
            vec![
                0xF0, 0x6C, 0x7F, 0x7F, 0x00, 0x01, 0x0B, 0x01, 0x01, 0x01, 0x02, 0x0A, 0x04, 0x0E,
                0x7F, 0xF7,
            ],
        ),
        (
            "analog_mapping",
            vec![0xF0, 0x6A, 0x7F, 0x7F, 0x00, 0x01, 0xF7],
        ),
        ("pin_state", vec![0xF0, 0x6E, 13, 0x01, 0x01, 0xF7]),
        ("i2c_reply", i2c_reply.clone()),
        (
            "stepper_position",
            with(|o| p::encode_stepper_position(o, 0, 123_456_789, false)),
        ),
        (
            "stepper_move_complete",
            with(|o| p::encode_stepper_position(o, 1, -2000, true)),
        ),
        (
            "multistepper_complete",
            vec![
                0xF0,
                p::ACCELSTEPPER_DATA,
                p::MULTISTEPPER_MOVE_COMPLETE,
                0x00,
                0xF7,
            ],
        ),
        (
            "string",
            with(|o| p::encode_string(o, "I2C: Too few bytes received")),
        ),
        ("other_sysex", vec![0xF0, 0x61, 0x01, 0xF7]),
        ("interleaved", interleaved),
        ("cut_sysex", vec![0xF0, 0x6C, 0x00, 0x01, 0xE2, 0x05, 0x00]),
        ("cut_analog", vec![0xE0, 0x05, 0xF9, 2, 5]),
        ("cut_firmware", firmware[..firmware.len() - 5].to_vec()),
        ("empty_sysex", vec![0xF0, 0xF7]),
        (
            "stray_and_unknown",
            vec![0x42, 0xF2, 0xA5, 0x01, 0xF9, 2, 6],
        ),
        (
            "i2c_reply_odd",
            vec![0xF0, 0x77, 0x68, 0x00, 0x75, 0x00, 0x03, 0xF7],
        ),
        ("i2c_reply_garbled", {
            let mut r = i2c_reply;
            r[3] = 0x02; // the address's second byte
            r
        }),
        ("overlong", overlong),
        ("host_requests", host),
    ];
    let sessions = firmata_sessions();
    seeds.extend(sessions.iter().map(|(n, b)| (*n, b.clone())));
    seeds
        .into_iter()
        .map(|(name, bytes)| (name.to_owned(), [&[5u8][..], &bytes].concat()))
        .collect()
}

/// The simulated Arduino's answers to a host (a capture of the board's side): its start-up
/// reports, the queries' answers on an Uno and a Mega 2560, analog reporting, I2C register
/// reads (answered, and not), a stepper's move; and the start-up as a host at twice the
/// board's baud rate hears it.
fn firmata_sessions() -> Vec<(&'static str, Vec<u8>)> {
    use firmata_host::StepperConfig;
    use firmata_host::protocol as p;
    use firmata_sim::{BoardKind, ConstantVolts, Firmware, FirmwareKind, SimConfig};

    /// A board that has booted; its start-up reports and its answers to `host` at 10 ms,
    /// then `ticks` passes of its loop 10 ms apart.
    fn session(
        kind: FirmwareKind,
        board: BoardKind,
        host: impl FnOnce(&mut Vec<u8>),
        ticks: u32,
    ) -> Vec<u8> {
        let mut fw = Firmware::new(kind, board);
        let mut bus = SimConfig::default().bus;
        let mut volts = ConstantVolts::new(&[(0, 1.25), (1, 3.3)]);
        let mut out = Vec::new();
        fw.boot_report(&mut out);
        let mut sent = Vec::new();
        host(&mut sent);
        fw.receive(
            &sent,
            Duration::from_millis(10),
            &mut bus,
            &mut volts,
            &mut out,
        );
        for k in 1..=ticks {
            fw.tick(
                Duration::from_millis(10 + 10 * u64::from(k)),
                &mut bus,
                &mut volts,
                &mut out,
            );
        }
        out
    }
    let queries = |o: &mut Vec<u8>| {
        p::encode_version_query(o);
        for id in [
            p::REPORT_FIRMWARE,
            p::CAPABILITY_QUERY,
            p::ANALOG_MAPPING_QUERY,
        ] {
            p::encode_sysex_query(o, id);
        }
        o.extend_from_slice(&[p::START_SYSEX, p::PIN_STATE_QUERY, 13, p::END_SYSEX]);
        // An ID the sketch does not handle: ConfigurableFirmata answers with a string.
        p::encode_sysex_query(o, 0x61);
    };
    let (configurable, standard) = (FirmwareKind::Configurable, FirmwareKind::Standard);
    let boot = session(configurable, BoardKind::Uno, |_| {}, 0);
    let mut sessions = vec![
        ("sim_boot", boot.clone()),
        (
            "sim_queries_uno",
            session(configurable, BoardKind::Uno, queries, 0),
        ),
        (
            "sim_queries_mega",
            session(standard, BoardKind::Mega2560, queries, 0),
        ),
        (
            "sim_analog",
            session(
                standard,
                BoardKind::Uno,
                |o| {
                    p::encode_sampling_interval(o, 10);
                    p::encode_report_analog(o, 0, true);
                    p::encode_report_analog(o, 1, true);
                    p::encode_set_pin_mode(o, 2, firmata_host::PinMode::Input);
                    p::encode_report_digital(o, 0, true);
                },
                5,
            ),
        ),
        (
            "sim_i2c",
            session(
                configurable,
                BoardKind::Uno,
                |o| {
                    p::encode_i2c_config(o, 0);
                    // Fingertip 0 behind the mux, then its PROM word 1 (a fixed value).
                    p::encode_i2c_write(o, firmata_sim::MUX_ADDRESS, &[0x01]);
                    let read = p::I2C_MODE_READ_ONCE | p::I2C_AUTO_RESTART;
                    p::encode_i2c_request(o, firmata_sim::MS5611_ADDRESS, read, &[0xA2, 2]);
                    // The ICM-20789's WHO_AM_I, and a device that is not there.
                    p::encode_i2c_request(o, 0x68, read, &[0x75, 1]);
                    p::encode_i2c_request(o, 0x50, read, &[0x00, 2]);
                },
                0,
            ),
        ),
        (
            "sim_stepper",
            session(
                configurable,
                BoardKind::Uno,
                |o| {
                    let config = StepperConfig::driver(2, 3);
                    let config = [config.interface_byte(), 2, 3, 0];
                    p::encode_stepper(o, p::ACCELSTEPPER_CONFIG, 0, &config);
                    let speed = p::encode_custom_float(2000.0).unwrap_or_default();
                    p::encode_stepper(o, p::ACCELSTEPPER_SET_SPEED, 0, &speed);
                    let to = p::encode_stepper_i32(-40).unwrap_or_default();
                    p::encode_stepper(o, p::ACCELSTEPPER_TO, 0, &to);
                    p::encode_stepper(o, p::ACCELSTEPPER_REPORT_POSITION, 0, &[]);
                },
                4,
            ),
        ),
    ];
    sessions.push((
        "sim_boot_at_115200",
        firmata_sim::uart::resample(&boot, 57_600, 115_200),
    ));
    sessions
}
