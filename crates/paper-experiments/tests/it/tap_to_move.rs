//! The tap-to-move run (`paper_experiments::tap_run`) with the stand-in locator, one round of 9
//! taps: every trigger inside its tap, the scheduled region moved to, the final TCP within
//! 0.1 mm of its grid pose. (The CNN's own figures come from `cargo xtask demo tap-to-move`.)

use paper_experiments::tap_run as run;

use hand_sim::imu_pad::TapSpec;
use hand_traits::{Contact, ContactLocator};
use handstack::tap_to_move::TapToMoveConfig;
use run::Window;
use ur_sim::TimeScale;

/// Answers the scheduled regions in order: a stand-in for the CNN that measures no recognition.
struct Scheduled {
    regions: Vec<u16>,
    next: usize,
    /// The tap whose contact it reports outside its range.
    outside: Option<usize>,
}

impl Scheduled {
    /// The regions of `taps`, in order.
    fn new(taps: &[TapSpec]) -> Result<Self, String> {
        let regions = taps
            .iter()
            .map(|t| {
                t.position()
                    .map(|p| u16::from(p.region()))
                    .map_err(|e| e.to_string())
            })
            .collect::<Result<_, _>>()?;
        Ok(Self {
            regions,
            next: 0,
            outside: None,
        })
    }
}

impl ContactLocator for Scheduled {
    type Input = Window;
    type Error = &'static str;
    fn locate(&mut self, _: &Window) -> Result<Contact, &'static str> {
        let region = *self
            .regions
            .get(self.next)
            .ok_or("more taps than scheduled")?;
        self.next += 1;
        Ok(Contact {
            region,
            regions: 9,
            confidence: 1.0,
            in_range: self.outside != Some(self.next - 1),
        })
    }
}

/// One round of 9 taps, one per region, on the UR simulator at 127.0.0.`octet` with the
/// stand-in locator (tap `outside` reported outside its range): the run's 9 rows.
fn one_round(octet: u8, outside: Option<usize>) -> Vec<run::Row> {
    let taps = run::schedule(run::PAD_SEED, 1);
    let mut locator = Scheduled::new(&taps).unwrap();
    locator.outside = outside;
    let rows = run::run(
        octet,
        TimeScale::new(run::TIME_SCALE).unwrap(),
        taps,
        TapToMoveConfig::default(),
        &mut locator,
        run::window,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(rows.len(), 9);
    rows
}

#[test]
fn every_region_moves_the_arm_to_its_grid_pose() {
    let rows = one_round(21, None);
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(usize::from(r.region), k, "one tap per region, in order");
        assert_eq!(r.located, r.region);
        assert!(
            r.trigger_in_tap,
            "region {k}: trigger {} s after the press began",
            r.trigger_after_press_s
        );
        // The trigger is the first of the window's last 19 frames: 18 frame periods at 30 Hz.
        assert!((r.window_s - 18.0 / 30.0).abs() < 1e-3, "{}", r.window_s);
        assert!(r.tcp_error_m < 1e-4, "region {k}: {} m", r.tcp_error_m);
    }
    println!(
        "{}",
        run::markdown(
            &rows,
            "stand-in (scheduled regions)",
            "trigger-centred",
            TimeScale::new(run::TIME_SCALE).unwrap()
        )
    );
}

/// A contact located from a window outside the locator's range is reported, not acted on: the
/// arm stays at home for that tap and moves for the others.
#[test]
fn a_contact_outside_the_locators_range_leaves_the_arm_at_home() {
    let rows = one_round(22, Some(4));
    for (k, r) in rows.iter().enumerate() {
        if k == 4 {
            // At home, centimetres from region 4's grid pose; no move was timed.
            assert!(r.tcp_error_m > 0.01, "region 4: {} m", r.tcp_error_m);
            assert_eq!(r.move_s, 0.0);
        } else {
            assert!(r.tcp_error_m < 1e-4, "region {k}: {} m", r.tcp_error_m);
        }
    }
}
