//! Seed 001's underactuated hand behind the simulated Arduino, through the real Firmata client
//! (firmata-host) on the pty: the stepper configured and closing at constant velocity, the
//! eight analog channels reported, checked against hand-sim's own simulation of the same close;
//! soft against hard; `stop` (and a reset of the board after it); the board's process killed.
//!
//! The board runs in wall-clock time, so the closes are short: a 90 mm cylinder (the first
//! touch after about 0.9 s at 10 mm/s of tendon), 2 s in all.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use firmata_host::{Board, ErrorKind, Options, StepperConfig};
use hand_sim::scene::Model;
use hand_sim::underactuated::{Material, Underactuated};
use paper_scenes::devices::hand_board::{
    DIR_PIN, FSR_CHANNELS, HandBoard, HandBoardConfig, POT_CHANNELS, STEP_PIN, STEPPER_DEVICE,
};

/// A boot short enough for tests.
const BOOT: Duration = Duration::from_millis(150);
/// The physics' step, ms, on the board and in the direct simulation alike.
const STEP_MS: f64 = 10.0;
/// The closing speed, steps/s (10 mm/s of tendon at 0.01 mm a step).
const SPEED: f32 = 1000.0;
/// How long a close is recorded, s.
const CLOSE_S: f64 = 2.0;
/// Far beyond what a close reaches: the stepper runs at constant speed throughout.
const FAR: i32 = 100_000;
/// How long anything the test waits for may take.
const TIMEOUT: Duration = Duration::from_secs(5);

fn config(material: Material) -> HandBoardConfig {
    let mut c = HandBoardConfig::new(material);
    c.hand.object.size_mm = 90.0;
    c.hand.step_ms = STEP_MS;
    // Noise-free pins: the agreement is then quantisation and sampling alone.
    c.hand.sensors.noise_lsb = 0.0;
    // The direct simulation's own stepper must not hold before the close ends.
    c.hand.duration_s = 600.0;
    c.hand.approach_timeout_s = 600.0;
    c.hand.closing_speed_mm_s = f64::from(SPEED) * c.hand.stepper_resolution_mm;
    c.seed = 5;
    c.boot_delay = BOOT;
    c
}

/// One analog report: when it arrived since the stepper was told to move, s, and its counts.
type Series = Vec<(f64, u16)>;

/// A board with the hand, opened, its stepper configured for constant speed and all eight
/// channels reporting.
fn open(material: Material) -> (HandBoard, Board) {
    let sim = HandBoard::spawn(config(material)).expect("spawn the hand's board");
    let mut board = Board::open(sim.path(), &Options::default()).expect("open the board");
    assert_eq!(
        board.firmware().map(|f| f.name.as_str()),
        Some("ConfigurableFirmata")
    );
    board
        .stepper_config(STEPPER_DEVICE, &StepperConfig::driver(STEP_PIN, DIR_PIN))
        .unwrap();
    // 0: full speed from the first step (constant velocity, as the paper's open-loop close).
    board.stepper_set_acceleration(STEPPER_DEVICE, 0.0).unwrap();
    board.stepper_set_speed(STEPPER_DEVICE, SPEED).unwrap();
    for ch in FSR_CHANNELS.into_iter().chain(POT_CHANNELS) {
        board.enable_analog(ch).unwrap();
    }
    (sim, board)
}

/// Reads every report of the eight channels until `until` has passed since `t0`.
fn record(board: &mut Board, t0: Instant, until: f64, series: &mut [Series; 8]) {
    let mut last: [Option<Instant>; 8] = [None; 8];
    while t0.elapsed().as_secs_f64() < until {
        board.poll(Duration::from_millis(5)).unwrap();
        for (ch, s) in series.iter_mut().enumerate() {
            if let Some(r) = board.analog(ch as u8) {
                if last[ch] != Some(r.at) && r.at >= t0 {
                    last[ch] = Some(r.at);
                    s.push((r.at.duration_since(t0).as_secs_f64(), r.counts));
                }
            }
        }
    }
}

/// Closes the hand on `material` through the board for [`CLOSE_S`].
fn close(material: Material) -> [Series; 8] {
    let (sim, mut board) = open(material);
    let mut series: [Series; 8] = Default::default();
    let t0 = Instant::now();
    board.stepper_to(STEPPER_DEVICE, FAR).unwrap();
    record(&mut board, t0, CLOSE_S, &mut series);
    assert_eq!(sim.error(), None);
    series
}

/// hand-sim's own close of the same hand at the same speed: the eight channels' counts (as the
/// board's ADC makes them from the noise-free voltages) every millisecond.
fn direct(material: Material, until_s: f64) -> Vec<[u16; 8]> {
    let c = config(material);
    let mut hand = Underactuated::new(&c.hand, c.seed).unwrap();
    let n = (until_s * 1000.0).ceil() as u64;
    (0..=n)
        .map(|ms| {
            hand.step_to(ms * 1_000_000).unwrap();
            let v = hand.sensor_volts();
            std::array::from_fn(|ch| {
                let v = if ch < 4 { v.force[ch] } else { v.angle[ch - 4] };
                firmata_sim::counts(v as f32)
            })
        })
        .collect()
}

/// The force (N) or angle (degrees) that `counts` on channel `ch` stand for, by hand-sim's
/// inverse sensor laws from the volts the client computes.
fn decode(material: Material, ch: usize, counts: u16) -> f64 {
    let c = config(material);
    let s = c.hand.sensors;
    let volts = f64::from(counts) / 1023.0 * s.adc.vref_v;
    if ch < 4 {
        s.fsr.force_from_volts(volts, s.adc.vref_v)
    } else {
        s.pot.angle_from_volts(volts, s.adc.vref_v).to_degrees()
    }
}

/// How much earlier than its arrival (since the move was sent) a report may show the close, s.
/// A report can only be late: the board samples before the client stamps it, and the stepper
/// starts after the client sent the move. Nominally that is the 2 ms the move command takes on
/// the line, the ≤ 5 ms a burst of eight reports takes back at 57 600 baud and the board's 1 ms
/// pass (measured on an idle machine: 5–10 ms in all); the rest is for a loaded one, where
/// either thread may wait for a core (measured: up to 55 ms with three busy loops on two
/// cores). One physics step is added either way: the hand moves in steps, the board's and the
/// direct one on different grids.
const LATE_S: f64 = STEP_MS * 1e-3 + 0.100;
/// How much later than its arrival a report may show the close, s: one physics step and the
/// direct close's whole steps against the board's (a millisecond at 1000 steps/s).
const EARLY_S: f64 = STEP_MS * 1e-3 + 0.002;

struct Agreement {
    /// Reports outside the direct series' range from [`LATE_S`] before to [`EARLY_S`] after
    /// their arrival, ± 1 count (the ADC's quantisation: the board rounds, so a report is the
    /// direct volts' code or a neighbour).
    outside: usize,
    reports: usize,
    /// The largest difference from the direct value at the report's own time: force, N;
    /// angle, degrees.
    max_force_n: f64,
    max_angle_deg: f64,
    /// The same as root mean square.
    rms_force_n: f64,
    rms_angle_deg: f64,
}

/// The least lateness (ms) within which every report lies within the direct series ± 1
/// count (with [`EARLY_S`] on the other side).
fn needed_lateness_ms(series: &[Series; 8], truth: &[[u16; 8]]) -> Option<u32> {
    let at = |t: f64| ((t * 1000.0).round().max(0.0) as usize).min(truth.len() - 1);
    (0..=200).find(|&w| {
        let w = f64::from(w) * 1e-3;
        series.iter().enumerate().all(|(ch, s)| {
            s.iter().all(|&(t, counts)| {
                let range = truth[at(t - w)..=at(t + EARLY_S)].iter().map(|c| c[ch]);
                let (min, max) = range.fold((u16::MAX, 0), |(a, b), c| (a.min(c), b.max(c)));
                counts + 1 >= min && counts <= max + 1
            })
        })
    })
}

fn agreement(material: Material, series: &[Series; 8], truth: &[[u16; 8]]) -> Agreement {
    let mut a = Agreement {
        outside: 0,
        reports: 0,
        max_force_n: 0.0,
        max_angle_deg: 0.0,
        rms_force_n: 0.0,
        rms_angle_deg: 0.0,
    };
    let (mut nf, mut na) = (0usize, 0usize);
    let at = |t: f64| ((t * 1000.0).round().max(0.0) as usize).min(truth.len() - 1);
    for (ch, s) in series.iter().enumerate() {
        for &(t, counts) in s {
            let (lo, hi) = (at(t - LATE_S), at(t + EARLY_S));
            let range = truth[lo..=hi].iter().map(|c| c[ch]);
            let (min, max) = range.fold((u16::MAX, 0), |(a, b), c| (a.min(c), b.max(c)));
            a.reports += 1;
            if counts + 1 < min || counts > max + 1 {
                a.outside += 1;
                eprintln!("{material:?} A{ch} at {t:.3} s: {counts}, direct {min}…{max}");
            }
            let d = (decode(material, ch, counts) - decode(material, ch, truth[at(t)][ch])).abs();
            if ch < 4 {
                a.max_force_n = a.max_force_n.max(d);
                a.rms_force_n += d * d;
                nf += 1;
            } else {
                a.max_angle_deg = a.max_angle_deg.max(d);
                a.rms_angle_deg += d * d;
                na += 1;
            }
        }
    }
    a.rms_force_n = (a.rms_force_n / nf.max(1) as f64).sqrt();
    a.rms_angle_deg = (a.rms_angle_deg / na.max(1) as f64).sqrt();
    a
}

#[test]
fn a_close_through_firmata_agrees_with_hand_sim_and_soft_differs_from_hard() {
    let mut finals = Vec::new();
    for material in [Material::Sponge, Material::Wood] {
        let series = close(material);
        let truth = direct(material, CLOSE_S + 0.1);
        // Every channel reported all along (19 ms sampling: ~100 reports in 2 s).
        for (ch, s) in series.iter().enumerate() {
            assert!(s.len() > 80, "{material:?} A{ch}: {} reports", s.len());
        }
        let a = agreement(material, &series, &truth);
        eprintln!(
            "{material:?}: {} reports, {} outside; force max {:.3} N rms {:.3} N; angle max \
             {:.2}° rms {:.2}°; every report within ±1 count of the direct close up to {:?} ms \
             before it arrived",
            a.reports,
            a.outside,
            a.max_force_n,
            a.rms_force_n,
            a.max_angle_deg,
            a.rms_angle_deg,
            needed_lateness_ms(&series, &truth),
        );
        assert_eq!(
            a.outside, 0,
            "{material:?}: reports outside the direct close"
        );
        // The close touched: every finger's force and distal angle rose.
        for (ch, s) in series.iter().enumerate() {
            let (first, last) = (s.first().unwrap().1, s.last().unwrap().1);
            assert!(last > first + 5, "{material:?} A{ch}: {first} → {last}");
        }
        finals.push(std::array::from_fn::<f64, 8, _>(|ch| {
            decode(material, ch, series[ch].last().unwrap().1)
        }));
    }
    let (soft, hard) = (finals[0], finals[1]);
    eprintln!("after {CLOSE_S} s — sponge: {soft:.2?}; wood: {hard:.2?}");
    // Seed 001 §4 (Figure 9): the hard object's force is much higher, the soft one lets the
    // fingers wrap further.
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
    assert!(
        mean(&hard[..4]) > 2.0 * mean(&soft[..4]),
        "force: soft {soft:?}, hard {hard:?}"
    );
    assert!(
        mean(&soft[4..]) > mean(&hard[4..]) + 2.0,
        "angle: soft {soft:?}, hard {hard:?}"
    );
}

#[test]
fn stop_stops_the_stepper_and_the_fingers() {
    let (sim, mut board) = open(Material::Wood);
    let mut before: [Series; 8] = Default::default();
    let t0 = Instant::now();
    board.stepper_to(STEPPER_DEVICE, FAR).unwrap();
    // Past the first touch (wood: no creep to move the fingers once the tendon holds).
    record(&mut board, t0, 1.4, &mut before);
    let stopped = board.stepper_stop(STEPPER_DEVICE).unwrap();
    assert!((1000..2500).contains(&stopped), "{stopped}");
    let truth = sim.truth();
    // Closing up to the stop: the distal angles were rising.
    for ch in POT_CHANNELS {
        let s = &before[usize::from(ch)];
        let (first, last) = (s.first().unwrap().1, s.last().unwrap().1);
        assert!(last > first + 5, "A{ch}: {first} → {last}");
    }
    // After it: 0.3 s of reports, every channel still.
    let mut after: [Series; 8] = Default::default();
    let t1 = Instant::now();
    record(&mut board, t1, 0.3, &mut after);
    for (ch, s) in after.iter().enumerate() {
        assert!(s.len() > 10, "A{ch}: {} reports", s.len());
        assert!(
            s.iter().all(|&(_, c)| c == s[0].1),
            "A{ch} moved after the stop: {s:?}"
        );
    }
    assert_eq!(board.stepper_position(STEPPER_DEVICE).unwrap(), stopped);
    let later = sim.truth();
    assert_eq!(later.shaft_steps, i64::from(stopped));
    // The quasi-static solve goes on each step: the same state to its tolerance.
    for (a, b) in later.fingers.iter().zip(&truth.fingers) {
        assert!((a.distal_rad - b.distal_rad).abs() < 1e-9, "{a:?} vs {b:?}");
        assert!(
            (a.proximal_rad - b.proximal_rad).abs() < 1e-9,
            "{a:?} vs {b:?}"
        );
        assert!(
            (a.distal_force_n - b.distal_force_n).abs() < 1e-6,
            "{a:?} vs {b:?}"
        );
    }
    assert!(later.now_ns > truth.now_ns, "the hand's clock went on");

    // Closing the port and opening it again resets the board (the Arduino's reset on open):
    // AccelStepper forgets its stepper, the tendon holds the fingers where they were.
    let held: Vec<u16> = after.iter().map(|s| s[0].1).collect();
    drop(board);
    let deadline = Instant::now() + TIMEOUT;
    while sim.board().port_open() {
        assert!(Instant::now() < deadline, "the board never saw the close");
        std::thread::yield_now();
    }
    let mut board = Board::open(sim.path(), &Options::default()).unwrap();
    assert_eq!(sim.board().boots(), 2);
    for (ch, &counts) in held.iter().enumerate() {
        assert_eq!(
            board.enable_analog(ch as u8).unwrap().counts,
            counts,
            "A{ch}"
        );
    }
    assert_eq!(sim.truth().shaft_steps, i64::from(stopped));
}

/// Sends SIGKILL to a process we started when dropped (a no-op once it has ended).
struct KillOnDrop(std::process::Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn the_board_process_killed_is_a_disconnected_error() {
    let child = Command::new(env!("CARGO_BIN_EXE_paper-scenes"))
        .args(["hand-board", "--object", "hard", "--boot-ms", "150"])
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn paper-scenes hand-board");
    let mut child = KillOnDrop(child);
    let stdout = child.0.stdout.take().expect("piped");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx.recv_timeout(Duration::from_secs(20)).expect("the pty");
    let path = line.trim_end();
    let mut board = Board::open(path, &Options::default()).unwrap();
    board
        .stepper_config(STEPPER_DEVICE, &StepperConfig::driver(STEP_PIN, DIR_PIN))
        .unwrap();
    board.stepper_set_speed(STEPPER_DEVICE, SPEED).unwrap();
    board.stepper_to(STEPPER_DEVICE, FAR).unwrap();
    board.enable_analog(POT_CHANNELS[0]).unwrap();
    child.0.kill().expect("SIGKILL");
    let _ = child.0.wait();
    let deadline = Instant::now() + TIMEOUT;
    let e = loop {
        match board.wait_analog(POT_CHANNELS[0], Duration::from_secs(2)) {
            Ok(_) => assert!(Instant::now() < deadline, "reports after the kill"),
            Err(e) => break e,
        }
    };
    assert!(matches!(e.kind, ErrorKind::Disconnected), "{e}");
    assert!(e.to_string().contains(path), "{e}");
}

/// `paper-scenes hand-board` takes `hold CLASS` lines as a user swaps objects: another object
/// in the open hand, refused while the tendon is pulled; a class it does not know, refused.
#[test]
fn the_board_process_swaps_objects_only_in_the_open_hand() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_paper-scenes"))
        .args(["hand-board", "--object", "soft", "--boot-ms", "150"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn paper-scenes hand-board");
    let mut stdin = child.stdin.take().expect("piped");
    let stdout = child.stdout.take().expect("piped");
    let stderr = child.stderr.take().expect("piped");
    let child = KillOnDrop(child);
    let lines = |from: Box<dyn std::io::Read + Send>| {
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            for l in BufReader::new(from).lines().map_while(Result::ok) {
                let _ = tx.send(l);
            }
        });
        rx
    };
    let (out, err) = (lines(Box::new(stdout)), lines(Box::new(stderr)));
    let next = |rx: &mpsc::Receiver<String>| {
        rx.recv_timeout(Duration::from_secs(20))
            .expect("a line in time")
    };
    let path = next(&out);
    let mut say = |line: &str| {
        use std::io::Write;
        writeln!(stdin, "{line}").expect("written");
        stdin.flush().expect("sent");
    };
    say("hold hard");
    assert_eq!(next(&out), "holding hard");
    say("hold squishy");
    assert!(next(&err).contains("`hold soft`, `hold moderate` or `hold hard`"));
    // Closed on the hard object: it cannot be taken out.
    let mut board = Board::open(path.trim_end(), &Options::default()).expect("open");
    board
        .stepper_config(STEPPER_DEVICE, &StepperConfig::driver(STEP_PIN, DIR_PIN))
        .unwrap();
    board.stepper_set_speed(STEPPER_DEVICE, SPEED).unwrap();
    let mark = board.mark();
    board.stepper_to(STEPPER_DEVICE, 200).unwrap();
    board
        .wait_stepper_complete(STEPPER_DEVICE, mark, TIMEOUT)
        .expect("moved");
    say("hold soft");
    let e = next(&err);
    assert!(
        e.contains("the hand is closed (200 steps of tendon pulled)"),
        "{e}"
    );
    // Opened again, it takes the soft one.
    let mark = board.mark();
    board.stepper_to(STEPPER_DEVICE, 0).unwrap();
    board
        .wait_stepper_complete(STEPPER_DEVICE, mark, TIMEOUT)
        .expect("moved");
    say("hold soft");
    assert_eq!(next(&out), "holding soft");
    drop(child);
}
