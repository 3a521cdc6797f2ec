//! Each scene's cycle does what its parts do: the same structs the benches time, run over
//! their schedules and checked against the libraries called directly.

use hand_control::control_table::MX_28;
use hand_control::protocol::{Parser, instruction_id, packet_id};
use hand_traits::{GraspPolicy, ImuFrame};
use handstack_benches::contact::{ContactCycle, PRESS_FRAMES, RELEASE_FRAMES, REST_FRAMES};
use handstack_benches::full_hand::FullHandCycle;
use handstack_benches::grasp::{GraspCycle, SERVO_IDS, TARE_FRAMES};
use handstack_benches::softness::SoftnessCycle;
use handstack_benches::tap::{TapCycle, cnn_window};
use handstack_benches::weight::{LOADS_GF, TARE_FRAMES as WEIGHT_TARE, WeightCycle};
use std::collections::BTreeMap;

#[test]
fn weight_estimates_rise_with_the_load() {
    let mut w = WeightCycle::new().expect("weight cycle");
    // The DNN's estimate on the last frame of each hold and of each release (both settled).
    let mut held: BTreeMap<u64, f32> = BTreeMap::new();
    let mut released = Vec::new();
    let (mut last_held, mut last_out) = (None, None);
    for _ in 0..(WEIGHT_TARE + 4 * 80) {
        let out = w.cycle().expect("cycle");
        assert!(out.weight_gf.is_finite());
        let load = w.load_gf();
        if load > 0.0 {
            if let Some(gf) = last_out.take() {
                released.push(gf);
            }
            last_held = Some((load as u64, out.weight_gf));
        } else {
            if let Some((gf, est)) = last_held.take() {
                held.insert(gf, est);
            }
            last_out = Some(out.weight_gf);
        }
    }
    released.extend(last_out);
    let loads: Vec<u64> = LOADS_GF.iter().map(|&g| g as u64).collect();
    assert_eq!(held.keys().copied().collect::<Vec<_>>(), loads);
    let est: Vec<f32> = held.values().copied().collect();
    assert!(
        est.windows(2).all(|p| p[0] < p[1]),
        "not increasing: {held:?}"
    );
    // The first "release" is the tare rest, then one after each of the four holds.
    assert_eq!(released.len(), 5, "{released:?}");
    let rest = released.iter().copied().fold(f32::MIN, f32::max);
    assert!(
        rest < est[0],
        "unloaded {rest} gf ≥ the 50 gf hold's {} gf",
        est[0]
    );
}

#[test]
fn contact_locates_only_pressed_frames_and_rearms_between_presses() {
    let mut c = ContactCycle::new().expect("contact cycle");
    let (mut located, mut presses_seen, mut was_pressed) = (0, 0, false);
    let period = PRESS_FRAMES + RELEASE_FRAMES;
    for n in 0..(REST_FRAMES + 3 * period) {
        let out = c.cycle().expect("cycle");
        let pressed = c.pressed().is_some();
        if pressed && !was_pressed {
            presses_seen += 1;
        }
        was_pressed = pressed;
        if n < REST_FRAMES {
            assert!(
                out.estimate.event.is_none(),
                "arrival before any press (frame {n})"
            );
        }
        if let Some(eq3) = out.eq3 {
            located += 1;
            assert!(eq3.region < 9 && out.ranging.is_some_and(|r| r.region < 9));
            let mlp = out.mlp.expect("the MLP runs with the AoT");
            assert!(mlp.region < 24 && (0.0..=1.0).contains(&mlp.confidence));
        } else {
            assert!(out.mlp.is_none() && out.ranging.is_none());
        }
        // The last frame of each release: back at rest, nothing arrived.
        if n >= REST_FRAMES && (n - REST_FRAMES) % period == period - 1 {
            assert!(out.estimate.event.is_none(), "not re-armed at frame {n}");
        }
    }
    assert_eq!(presses_seen, 3);
    // Every press is detected within a few frames and located until it is released.
    assert!(
        located > 3 * (PRESS_FRAMES - 10),
        "{located} located frames of 3 × {PRESS_FRAMES} pressed"
    );
}

#[test]
fn grasp_cycle_sends_the_fuzzy_effort_as_two_sync_writes() {
    let mut g = GraspCycle::new().expect("grasp cycle");
    let mut reference = g.reference_policy();
    let band = g.config().band;
    let (target, goal) = (g.config().target_pressure_pa, g.config().goal_rad);
    let mut efforts = Vec::new();
    for n in 0..(TARE_FRAMES + 4 * 50) {
        let out = g.cycle().expect("cycle");
        if n < TARE_FRAMES {
            assert!(
                out.packets.is_empty() && out.command.is_none(),
                "frame {n} while taring"
            );
            continue;
        }
        let est = out.estimate.expect("tared");
        let cmd = out.command.expect("command");
        let (expected, _) = band.clamp(reference.effort(&est.observation(target)).expect("finite"));
        assert_eq!(cmd.effort, expected);
        assert_eq!(cmd.position_rad, goal);
        let pwm = MX_28.effort_raw(cmd.effort.fraction());
        let goals = out.goals.clone().expect("goals");
        assert_eq!(goals.effort, pwm);
        let mut p = Parser::default();
        p.push(out.packets);
        for (reg, value) in [
            (MX_28.goal_effort, pwm),
            (MX_28.goal_position, goals.position),
        ] {
            let pkt = p.next_packet().expect("a packet").expect("valid CRC");
            assert_eq!(
                (pkt.id, pkt.instruction),
                (packet_id::BROADCAST, instruction_id::SYNC_WRITE)
            );
            let w = usize::from(reg.width);
            let mut want = reg.address.to_le_bytes().to_vec();
            want.extend_from_slice(&u16::from(reg.width).to_le_bytes());
            for id in SERVO_IDS {
                want.push(id);
                want.extend_from_slice(&reg.encode(value)[..w]);
            }
            assert_eq!(pkt.params, want);
        }
        assert!(p.next_packet().is_none());
        efforts.push(pwm);
    }
    // The presses drive the pressure through the target: the effort is not constant.
    let (lo, hi) = (efforts.iter().min(), efforts.iter().max());
    assert!(lo < hi, "effort stuck at {lo:?}");
}

#[test]
fn softness_cycle_ends_each_grasp_with_the_class_of_its_whole_series() {
    let mut s = SoftnessCycle::new().expect("softness cycle");
    let mut series: BTreeMap<usize, Vec<f32>> = BTreeMap::new();
    let mut last = BTreeMap::new();
    for _ in 0..s.reads_per_round() {
        let out = s.cycle().expect("cycle");
        series.entry(out.read.grasp).or_default().extend(out.sample);
        last.insert(out.read.grasp, out.class);
    }
    assert_eq!(series.len(), 3, "one grasp per material");
    for (grasp, values) in &series {
        assert_eq!(values.len() % 8, 0);
        assert!(values.len() / 8 >= 140, "14 s at 10 Hz");
        assert_eq!(
            last[grasp],
            s.net().predict(values).expect("finite"),
            "grasp {grasp}"
        );
    }
}

#[test]
fn tap_cycle_classifies_the_last_38_frames_and_targets_their_grid_pose() {
    let mut t = TapCycle::new().expect("tap cycle");
    let mut frames: Vec<ImuFrame> = Vec::new();
    let mut regions = BTreeMap::new();
    // Nine 3 s taps at 30 Hz from 0.5 s.
    for n in 0..(9 * 90 + 30) {
        let out = t.cycle().expect("cycle");
        frames.push(out.frame);
        if n < 37 {
            assert!(out.prediction.is_none());
            continue;
        }
        let window = cnn_window(&frames[frames.len() - 38..]).expect("38 frames");
        let p = t.cnn().predict(&window).expect("finite");
        assert_eq!(out.prediction, Some(p));
        assert_eq!(
            out.pose.as_ref(),
            Some(t.grid().pose(u16::from(p.region)).expect("region"))
        );
        *regions.entry(p.region).or_insert(0) += 1;
    }
    // The taps move round the pad: the CNN names more than one region.
    assert!(regions.len() > 1, "{regions:?}");
}

#[test]
fn full_hand_runs_every_part_in_one_cycle() {
    let mut f = FullHandCycle::new().expect("full hand");
    for n in 0..300u64 {
        let (d, c) = f.cycle().expect("cycle");
        assert!(d.weight_gf.is_finite());
        if n >= TARE_FRAMES {
            assert!(d.command.is_some());
            assert_eq!(c.servo_bytes, GraspCycle::WIRE_LEN);
        }
        if n >= 37 {
            assert!(d.region.is_some() && c.pose.is_some());
        }
    }
}
