//! A pad node on a tapped pad (feature `cell`): `handstack node`'s pad part
//! (`handstack::cell::real::run_node`, what the binary runs on real devices), opened through
//! a substitute platform whose I2C bus `pad` holds an ICM-20789 chip model reading hand-sim's
//! tapped pad, locates each tap with the built-in contact CNN and publishes it on
//! `/pad0/tactile/contact`, read here by a subscriber on the router's loopback endpoint. The
//! node reads 30 frames a second of wall time, as on a real pad; the chip's time moves one
//! frame period per frame (and by each conversion's delay within it), so what the pad measured
//! does not depend on how late the machine runs the node.

use embedded_hal::delay::DelayNs;
use hand_control::grasp_loop::LoopClock;
use hand_sim::imu_pad::tap::{PadTruth, RealisedTap};
use hand_sim::imu_pad::{ImuPadConfig, TapSpec, TapTiming};
use hand_zenoh::config::SessionConfig;
use hand_zenoh::msg::handstack_msgs::ContactArray;
use hand_zenoh::node::{Node, NodeOptions, Router};
use handstack::cell::file::Part;
use handstack::cell::{NodeArgs, Stop};
use handstack::scene::NodeScene;
use handstack::stack::platform::{I2cBus, Platform};
use imu_icm20789::sim::{ChipModel, SimClock};
use rand::SeedableRng;
use std::time::{Duration, Instant};

/// One tap per region 0…8 (column `r % 3 + 1`, a row of its row group the pressure trigger
/// sees: docs/arm.md), 1.2 mm deep as in the paper's real-time test (§IV-B).
fn taps() -> Vec<TapSpec> {
    (0..9u8)
        .map(|r| TapSpec {
            column: r % 3 + 1,
            row: [8, 12, 19][usize::from(r / 3)],
            depth_mm: 1.2,
        })
        .collect()
}

/// The pad's timing: hand-sim's tap motion (0.25 s press, 0.6 s hold, 0.25 s release), a tap
/// every 2 s instead of 3 (the window and the next baseline fit in 1.6 s), the first at 3 s.
fn timing() -> TapTiming {
    TapTiming {
        start_s: 3.0,
        tap_s: 2.0,
        ..TapTiming::default()
    }
}

/// The chip model's simulated time: each frame's stamp (the pad reads the clock once per
/// frame) starts the next frame period; delays advance it within the frame.
#[derive(Clone)]
struct Framed {
    sim: SimClock,
}

/// The pad's frame period at handstack's pad rate, ns.
const FRAME_NS: u64 = (1e9 / handstack::stack::pad::FRAME_RATE_HZ) as u64;

impl LoopClock for Framed {
    fn now_us(&mut self) -> u64 {
        self.sim
            .advance_to_ns(self.sim.now_ns().div_ceil(FRAME_NS) * FRAME_NS);
        self.sim.now_us()
    }

    fn wait_until_us(&mut self, t_us: u64) {
        self.sim.advance_to_ns(t_us.saturating_mul(1000));
    }
}

impl DelayNs for Framed {
    fn delay_ns(&mut self, ns: u32) {
        self.sim.advance_ns(u64::from(ns));
    }
}

/// The substitute platform: bus `pad` is the tapped pad's chip model.
struct TappedPad {
    time: Framed,
    truth: PadTruth,
}

impl Platform for TappedPad {
    fn open_i2c(&self, path: &str) -> Result<I2cBus, String> {
        if path != "pad" {
            return Err(format!("no substitute bus {path}"));
        }
        let truth = self.truth.clone();
        let chip =
            ChipModel::new(move |t_us| truth.state(t_us), 7).with_clock(self.time.sim.clone());
        Ok(I2cBus::new(chip))
    }

    fn delay(&self) -> Box<dyn DelayNs + Send> {
        Box::new(self.time.clone())
    }

    fn clock(&self) -> Box<dyn LoopClock + Send> {
        Box::new(self.time.clone())
    }
}

#[test]
fn a_pad_node_with_the_cnn_publishes_where_each_tap_landed() {
    let config = ImuPadConfig {
        timing: timing(),
        taps: taps(),
        ..ImuPadConfig::default()
    };
    let curve = config
        .mechanics
        .curve()
        .expect("hand-sim's force-depth curve");
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let realised: Vec<RealisedTap> = config
        .taps
        .iter()
        .enumerate()
        .map(|(i, spec)| RealisedTap::realise(spec, i, &config, &curve, &mut rng))
        .collect::<Result<_, _>>()
        .expect("realised taps");
    let platform = TappedPad {
        time: Framed {
            sim: SimClock::new(),
        },
        truth: PadTruth::new(realised, &config),
    };
    let scene = NodeScene::parse(
        "pad.toml",
        "title = \"pad\"\n[sensors.imu_pad]\ni2c_bus = \"pad\"\n\
         [estimators.contact]\nlocators = [\"cnn\"]\n",
    )
    .expect("a valid pad scene");

    let (_router, endpoint) = Router::open_on_loopback().expect("the router");
    let mut options = NodeOptions::new("/cell", "listener");
    options.session = SessionConfig::peer(&endpoint);
    let listener = Node::open(options).expect("the listener");
    let mut contacts = listener
        .subscription::<ContactArray>("/pad0/tactile/contact", 64)
        .expect("the subscription");
    let stop = Stop::new();
    let args = NodeArgs {
        part: Part::Pad,
        namespace: "/pad0".into(),
        connect: endpoint.clone(),
        domain_id: 0,
        humble: false,
    };
    let (regions, report) = std::thread::scope(|s| {
        let node = s.spawn(|| handstack::cell::real::run_node(&scene, &args, &stop, &platform));
        let mut regions = Vec::new();
        // The last tap is located 3 + 9 · 2 s of pad time in: 630 frames, 21 s at 30 frames a
        // second; the bound leaves a loaded machine room to run late.
        let deadline = Instant::now() + Duration::from_secs(120);
        while regions.len() < 9 && Instant::now() < deadline && !node.is_finished() {
            if let Some(m) = contacts
                .recv_timeout(Duration::from_millis(500))
                .expect("the subscription")
            {
                regions.extend(m.message.contacts.iter().map(|c| (c.region, c.regions)));
            }
        }
        stop.set();
        let report = node.join().expect("the node thread");
        (regions, report)
    });
    let report = report.unwrap_or_else(|e| panic!("the pad node: {e}"));
    println!("pad node: {report}; located {regions:?}");
    assert_eq!(
        regions.len(),
        9,
        "one contact per tap: {regions:?} ({report})"
    );
    assert!(regions.iter().all(|&(_, n)| n == 9));
    // The paper CNN with its windows where its training windows sat located 85 of 90 taps
    // (docs/arm.md); centred on the trigger, 10 of 90.
    let right = regions
        .iter()
        .enumerate()
        .filter(|&(i, &(r, _))| usize::from(r) == i)
        .count();
    assert!(right >= 7, "{right} of 9 taps in their region: {regions:?}");
    // The chip model's windows read like the dataset's the CNN was trained on.
    assert!(
        report.contains("(0 outside the locator's range)"),
        "{report}"
    );
}
