//! `paper-scenes`: run the papers' scene files (`paper-scenes run SCENE... [--json] [--report
//! PATH]`) on the handstack stack, simulated devices behind the real interfaces. Training the
//! committed models and the speed / accuracy trade are `papers train MODEL` and `papers trade`.

use clap::{Parser, Subcommand};
use handstack::progress::Bars;
use paper_scenes::runs::RunContext;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The papers' scenes on the handstack stack.
#[derive(Parser)]
#[command(name = "paper-scenes", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build the stack each scene file names and run its experiments.
    Run {
        /// Scene files (fixtures/scenes/*.toml).
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Print the outcomes as JSON on stdout (no progress, no table).
        #[arg(long)]
        json: bool,
        /// Also write the HTML report of the outcomes here.
        #[arg(long, value_name = "PATH")]
        report: Option<PathBuf>,
    },
    /// Seed 001's underactuated hand behind a simulated Arduino Mega running
    /// ConfigurableFirmata on a pty: prints the pty's path, then takes lines on stdin: `hold
    /// soft|moderate|hard` puts another object in the open hand (answered `holding …`).
    /// Serves until SIGINT / SIGTERM. Stepper 0 on D2 (STEP) / D3 (DIR) pulls the tendon,
    /// 0.01 mm a step; A0–A3 are the fingers' FSR dividers, A4–A7 their distal potentiometers.
    HandBoard(HandBoardArgs),
    /// Seed 000's grasp rig as two devices on ptys, in real time: the hand's MX-28 (ID 1) on a
    /// Protocol 2.0 servo bus, and the fingertip's three MS5611 behind a TCA9548A (channels
    /// 0–2) on a simulated Arduino Mega running ConfigurableFirmata; the servo closing on a
    /// Table 5 object presses the fingertip. Prints both ports as a scene names them, serves
    /// until SIGINT / SIGTERM, then prints what the hand was left doing.
    GraspRig(GraspRigArgs),
    /// Seed 000's weighing rig: the fingertip's three MS5611 behind a TCA9548A (channels 0–2)
    /// on a simulated Arduino Mega running ConfigurableFirmata on a pty. Prints the port as a
    /// scene names it, then takes lines on stdin: `place G` rests G gf on the whole pad
    /// (answered `placed G gf`), `clear` lifts it. Serves until stdin closes or SIGINT /
    /// SIGTERM.
    FingertipBoard(FingertipBoardCommand),
    /// Seed 002's tactile pad: the ICM-20789 under Ecoflex on a simulated Arduino Mega running
    /// ConfigurableFirmata on a pty. Prints the port as a scene names it, then takes lines on
    /// stdin: `tap R` taps region R (0–8) now, as the paper's UR3 tapped it (answered `tapping
    /// region R …`). Serves until stdin closes or SIGINT / SIGTERM.
    PadBoard(PadBoardArgs),
    /// Run a scene's stack (or one part: pad, arm, fingertip or hand) on its simulated devices
    /// as ROS 2 nodes on Zenoh, until stdin closes.
    #[cfg(feature = "cell")]
    Node {
        #[command(flatten)]
        node: handstack::cell::cli::NodeCommand,
        /// Read the simulated device this many times faster than real time.
        #[arg(long, default_value_t = 1.0)]
        sim_speed: f64,
    },
    /// Start a Zenoh router, the nodes a cell file names (each a `paper-scenes node` process)
    /// and the coordinator of seed 002's tap-to-move across them.
    #[cfg(feature = "cell")]
    Cell(handstack::cell::cli::CellCommand),
}

/// `paper-scenes hand-board`'s options.
#[derive(clap::Args)]
struct HandBoardArgs {
    /// The object's softness: soft (sponge), moderate (silicone rubber) or hard (wood).
    #[arg(long, value_enum, default_value_t = Softness::Moderate)]
    object: Softness,
    /// The object's shape.
    #[arg(long, value_enum, default_value_t = Shape::Cylinder)]
    shape: Shape,
    /// The object's size, mm (seed 001 Table 1: 65, 80 or 90; 0 for an empty grasp).
    #[arg(long, default_value_t = 80.0)]
    size_mm: f64,
    /// The seed of the object's pose and the sensors' spread.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// From the port opening to the version report, ms (bootloader and setup()).
    #[arg(long = "boot-ms", default_value_t = 1600)]
    boot_ms: u64,
    /// Another hand: the seed of its build (its FSRs read forces higher and its potentiometers
    /// sit a few degrees off; hand-sim's `other_hand`), on which the built-in softness net
    /// misclassifies objects. Absent: the hand the net was trained on.
    #[arg(long)]
    build: Option<u64>,
    /// The physics' quasi-static step, ms.
    #[arg(long = "step-ms", default_value_t = 10.0)]
    step_ms: f64,
    /// Read noise at the analog pins, LSB (σ).
    #[arg(long = "noise-lsb", default_value_t = 0.5)]
    noise_lsb: f64,
}

/// `paper-scenes grasp-rig`'s options.
#[derive(clap::Args)]
struct GraspRigArgs {
    /// The Table 5 object: cube, cylinder, cone, ellipsoid, paper-cup or scroll-tissue.
    #[arg(long, default_value = "cylinder")]
    object: String,
    #[command(flatten)]
    board: FingertipBoardArgs,
}

/// `paper-scenes pad-board`'s options.
#[derive(clap::Args)]
struct PadBoardArgs {
    /// The seed of the chip's noise and the taps' rows and errors.
    #[arg(long, default_value_t = 10)]
    seed: u64,
    /// The board's baud rate.
    #[arg(long, default_value_t = 115_200)]
    baud: u32,
    /// From the board's port opening to its version report, ms.
    #[arg(long = "boot-ms", default_value_t = 1600)]
    boot_ms: u64,
    /// Another pad: the seed of its build (its chip up to a row off, its tilt per newton
    /// scaled), on which the built-in contact CNN misplaces taps. Absent: the paper's pad.
    #[arg(long)]
    skin: Option<u64>,
}

/// The fingertip board's options (`paper-scenes fingertip-board`, `grasp-rig`).
#[derive(clap::Args)]
struct FingertipBoardArgs {
    /// The seed of the fingertip sensors' baselines and noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The fingertip board's baud rate.
    #[arg(long, default_value_t = 115_200)]
    baud: u32,
    /// From the board's port opening to its version report, ms.
    #[arg(long = "boot-ms", default_value_t = 1600)]
    boot_ms: u64,
}

/// `paper-scenes fingertip-board`'s options.
#[derive(clap::Args)]
struct FingertipBoardCommand {
    #[command(flatten)]
    board: FingertipBoardArgs,
    /// Another fingertip: the seed of its skin (its response and sensor gains differ from the
    /// fingertip the built-in models were trained on). Absent: that fingertip.
    #[arg(long)]
    skin: Option<u64>,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum Softness {
    Soft,
    Moderate,
    Hard,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum Shape {
    Rectangular,
    Cylinder,
    Sphere,
}

fn hand_board(args: &HandBoardArgs) -> ExitCode {
    use hand_sim::underactuated::Shape as S;
    use paper_scenes::devices::hand_board::{HandBoard, HandBoardConfig};
    let stop = handstack::stop::signal_stop();
    let mut config = HandBoardConfig::new(material(args.object));
    config.hand.object.shape = match args.shape {
        Shape::Rectangular => S::Rectangular,
        Shape::Cylinder => S::Cylinder,
        Shape::Sphere => S::Sphere,
    };
    config.hand.object.size_mm = args.size_mm;
    config.hand.step_ms = args.step_ms;
    config.hand.sensors.noise_lsb = args.noise_lsb;
    if let Some(build) = args.build {
        config.hand = config.hand.other_hand(build);
    }
    config.seed = args.seed;
    config.boot_delay = std::time::Duration::from_millis(args.boot_ms);
    let board = match HandBoard::spawn(config) {
        Ok(board) => board,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(handstack::summary::ExitStatus::exit_code(&e).max(1));
        }
    };
    println!("{}", board.path().display());
    // A test or script waits for this line through a pipe: it must not sit in a buffer.
    let _ = std::io::Write::flush(&mut std::io::stdout());
    let commands = handstack::prompt::Prompter::stdin();
    loop {
        match commands.answer(&stop) {
            Ok(line) => {
                let object = match line.split_whitespace().collect::<Vec<_>>()[..] {
                    ["hold", class] => <Softness as clap::ValueEnum>::from_str(class, false).ok(),
                    [] => continue,
                    _ => None,
                };
                match object.map(|o| (o, board.hold(material(o)))) {
                    Some((_, Ok(()))) => println!("holding {}", line.trim_start()[4..].trim()),
                    Some((_, Err(e))) => eprintln!("error: {e}"),
                    None => {
                        eprintln!("error: \"{line}\": `hold soft`, `hold moderate` or `hold hard`")
                    }
                }
                let _ = std::io::Write::flush(&mut std::io::stdout());
            }
            // Without commands the board serves until a signal.
            Err(handstack::prompt::Unanswered::Closed) => {
                while !stop.is_set() {
                    std::thread::sleep(std::time::Duration::from_millis(20));
                }
                break;
            }
            Err(handstack::prompt::Unanswered::Stopped(_)) => break,
        }
    }
    // What the hand was left doing, for whoever ran it (a test reads this line back).
    let truth = board.truth();
    let stepper = board
        .board()
        .stepper(paper_scenes::devices::hand_board::STEPPER_DEVICE);
    println!(
        "left: stepper {}, tendon {:.2} mm ({} steps turned), tension {:.2} N",
        stepper.map_or_else(
            || "not configured".to_owned(),
            |s| format!(
                "position={} running={} enabled={}",
                s.position, s.running, s.enabled
            )
        ),
        truth.travel_m * 1e3,
        truth.shaft_steps,
        truth.tension_n
    );
    drop(board);
    ExitCode::SUCCESS
}

fn fingertip_board(cmd: &FingertipBoardCommand) -> ExitCode {
    use paper_scenes::devices::fingertip_board::{FingertipBoard, FingertipBoardConfig};
    let stop = handstack::stop::signal_stop();
    let args = &cmd.board;
    let config = FingertipBoardConfig {
        seed: args.seed,
        baud: args.baud,
        boot_delay: std::time::Duration::from_millis(args.boot_ms),
        skin: cmd.skin,
    };
    let rig = match FingertipBoard::spawn(&config) {
        Ok(rig) => rig,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(handstack::summary::ExitStatus::exit_code(&e).max(1));
        }
    };
    println!(
        "firmata_port = \"{}\"   # [sensors.fingertip]: three MS5611 behind a TCA9548A, {} baud",
        rig.path().display(),
        args.baud
    );
    let _ = std::io::Write::flush(&mut std::io::stdout());
    let commands = handstack::prompt::Prompter::stdin();
    while let Ok(line) = commands.answer(&stop) {
        let gf = match line.split_whitespace().collect::<Vec<_>>()[..] {
            ["place", g] => g.parse::<f64>().ok().filter(|g| g.is_finite() && *g >= 0.0),
            ["clear"] => Some(0.0),
            [] => continue,
            _ => None,
        };
        match gf.map(|g| (g, rig.place_gf(g))) {
            Some((g, Ok(()))) => println!("placed {g} gf"),
            Some((_, Err(e))) => eprintln!("error: {e}"),
            None => eprintln!("error: \"{line}\": `place G` (gf, 0 or more) or `clear`"),
        }
        let _ = std::io::Write::flush(&mut std::io::stdout());
    }
    println!("left: {} gf on the pad", rig.placed_gf());
    ExitCode::SUCCESS
}

fn pad_board(args: &PadBoardArgs) -> ExitCode {
    use paper_scenes::devices::pad_board::{PadBoard, PadBoardConfig};
    let stop = handstack::stop::signal_stop();
    let config = PadBoardConfig {
        seed: args.seed,
        baud: args.baud,
        boot_delay: std::time::Duration::from_millis(args.boot_ms),
        skin: args.skin,
    };
    let pad = match PadBoard::spawn(&config) {
        Ok(pad) => pad,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(handstack::summary::ExitStatus::exit_code(&e).max(1));
        }
    };
    println!(
        "firmata_port = \"{}\"   # [sensors.imu_pad]: the ICM-20789, {} baud",
        pad.path().display(),
        args.baud
    );
    let _ = std::io::Write::flush(&mut std::io::stdout());
    let commands = handstack::prompt::Prompter::stdin();
    while let Ok(line) = commands.answer(&stop) {
        let region = match line.split_whitespace().collect::<Vec<_>>()[..] {
            ["tap", r] => r.parse::<u8>().ok(),
            [] => continue,
            _ => None,
        };
        match region.map(|r| (r, pad.tap(r))) {
            Some((r, Ok(t))) => println!(
                "tapping region {r} (column {}, row {}, {:.2} N)",
                t.position.column(),
                t.position.row(),
                t.force_n
            ),
            Some((_, Err(e))) => eprintln!("error: {e}"),
            None => eprintln!("error: \"{line}\": `tap R` (a region, 0…8)"),
        }
        let _ = std::io::Write::flush(&mut std::io::stdout());
    }
    println!("left: {} taps made", pad.taps().len());
    ExitCode::SUCCESS
}

fn grasp_rig(args: &GraspRigArgs) -> ExitCode {
    use paper_scenes::devices::grasp_board::{GraspBoard, GraspBoardConfig};
    let stop = handstack::stop::signal_stop();
    let name = args.object.replace('-', "_");
    let Some(object) = hand_sim::grasp::ObjectKind::from_name(&name) else {
        eprintln!(
            "error: --object {}: one of cube, cylinder, cone, ellipsoid, paper-cup, scroll-tissue",
            args.object
        );
        return ExitCode::from(2);
    };
    let config = GraspBoardConfig {
        seed: args.board.seed,
        baud: args.board.baud,
        boot_delay: std::time::Duration::from_millis(args.board.boot_ms),
        ..GraspBoardConfig::new(object)
    };
    let mut rig = match GraspBoard::spawn(&config) {
        Ok(rig) => rig,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(handstack::summary::ExitStatus::exit_code(&e).max(1));
        }
    };
    println!(
        "serial_port = \"{}\"    # [hand]: the MX-28, ID 1, 1 000 000 baud",
        rig.servo_path().display()
    );
    println!(
        "firmata_port = \"{}\"   # [sensors.fingertip]: three MS5611 behind a TCA9548A, {} baud",
        rig.board_path().display(),
        args.board.baud
    );
    let _ = std::io::Write::flush(&mut std::io::stdout());
    while !stop.is_set() {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // What the hand was left doing, for whoever ran it (a test reads this line back), once the
    // bus has read the client's last bytes.
    if let Err(e) = rig.sync() {
        eprintln!("error: {e}");
    }
    match rig.state() {
        Some(s) => println!(
            "left: torque {}, position {:.3} rad, grip force {:.2} N, object {}",
            if s.torque_enabled { "on" } else { "off" },
            s.position_rad,
            s.grip_force_n,
            if s.dropped {
                "dropped"
            } else if s.damaged {
                "crushed"
            } else {
                "intact"
            }
        ),
        None => println!("left: the servo is not on the bus"),
    }
    if let Some(e) = rig.error() {
        eprintln!("error: the pad's physics: {e}");
    }
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::HandBoard(args) => hand_board(&args),
        Command::GraspRig(args) => grasp_rig(&args),
        Command::FingertipBoard(args) => fingertip_board(&args),
        Command::PadBoard(args) => pad_board(&args),
        Command::Run {
            scenes,
            json,
            report,
        } => run(&scenes, json, report.as_deref()),
        #[cfg(feature = "cell")]
        Command::Node { node, sim_speed } => node.main(
            || {
                let scene = paper_scenes::scene::PaperScene::load(&node.scene)?;
                Ok(handstack::cell::scene_parts(&scene))
            },
            |args, stop| {
                let scene = paper_scenes::scene::PaperScene::load(&node.scene)?;
                let progress = handstack::progress::Quiet;
                let cx = RunContext::new(&progress);
                paper_scenes::cell::run_node(&scene, args, sim_speed, &cx, stop)
            },
        ),
        #[cfg(feature = "cell")]
        Command::Cell(cmd) => cmd.main(paper_scenes::cell::outcome),
    }
}

fn run(scenes: &[PathBuf], json: bool, report: Option<&Path>) -> ExitCode {
    let bars = Bars::new(!json);
    let mut cx = RunContext::new(&bars);
    cx.stack.stop = handstack::stop::signal_stop();
    let runs = handstack::summary::run_each(scenes, json, &bars, &cx.stop, |path| {
        paper_scenes::run_file(path, &cx)
    });
    let mut code = runs.exit_code;
    if let Some(out) = report {
        let failures: Vec<_> = runs
            .failures
            .into_iter()
            .map(|(scene, error)| paper_scenes::report::Failed { scene, error })
            .collect();
        let points = cx.root.join(paper_scenes::report::TRADE_POINTS);
        match paper_scenes::report::write_html(&runs.outcomes, &failures, Some(&points), out) {
            Ok(()) => eprintln!("report: {}", out.display()),
            Err(e) => {
                eprintln!("error: report: {e}");
                code = code.max(1);
            }
        }
    }
    ExitCode::from(code)
}

/// The material of an object of class `s` (seed 001 Table 1).
fn material(s: Softness) -> hand_sim::underactuated::Material {
    use hand_sim::underactuated::Material;
    match s {
        Softness::Soft => Material::Sponge,
        Softness::Moderate => Material::SiliconeRubber,
        Softness::Hard => Material::Wood,
    }
}
