//! Heap blocks allocated per control cycle, after warm-up, for every scene (dhat's counting
//! global allocator, as `crates/fuzzy-mamdani/tests/zero_alloc.rs`). One test, scenes in turn:
//! the allocator is global, so parallel tests would count each other's blocks.
//!
//! Target zero for every scene. The contact MLP is counted on its own as well: it decodes into a
//! fixed buffer with a streaming log-sum-exp, so its outputs, log-likelihoods and their softmax
//! take no block per call.
//!
//! It also reports each scene's peak heap: the binary runs itself once per scene
//! (`HANDSTACK_PEAK_SCENE`), so dhat's peak is that scene's alone — building it (models,
//! simulated devices) and running it.

use handstack_benches::CycleError;
use handstack_benches::contact::ContactCycle;
use handstack_benches::full_hand::FullHandCycle;
use handstack_benches::grasp::GraspCycle;
use handstack_benches::softness::SoftnessCycle;
use handstack_benches::tap::TapCycle;
use handstack_benches::weight::WeightCycle;

const WARM_UP: usize = 200;
const CYCLES: usize = 500;

/// Blocks allocated by `CYCLES` cycles after `WARM_UP` of them.
fn blocks(mut cycle: impl FnMut() -> Result<(), CycleError>) -> u64 {
    for _ in 0..WARM_UP {
        cycle().expect("warm-up cycle");
    }
    let before = dhat::HeapStats::get().total_blocks;
    for _ in 0..CYCLES {
        cycle().expect("cycle");
    }
    dhat::HeapStats::get().total_blocks - before
}

fn cycles_allocate_nothing_in_steady_state() {
    let _profiler = dhat::Profiler::builder().testing().build();
    let mut weight = WeightCycle::new().expect("weight");
    let mut grasp = GraspCycle::new().expect("grasp");
    let mut softness = SoftnessCycle::new().expect("softness");
    let mut tap = TapCycle::new().expect("tap");
    let mut contact = ContactCycle::new().expect("contact");
    let mut full = FullHandCycle::new().expect("full hand");
    // Contact, stage by stage: the MLP's blocks counted apart from the rest of the cycle.
    for _ in 0..WARM_UP {
        contact.cycle().expect("warm-up cycle");
    }
    let (mut mlp_calls, mut mlp_blocks) = (0, 0);
    let start = dhat::HeapStats::get().total_blocks;
    for _ in 0..CYCLES {
        let frame = contact.decode().expect("frame");
        let e = contact.estimate(&frame);
        if let (Some(event), Some(reading)) = (e.event, e.reading) {
            contact.aot(&event).expect("arrived");
            let before = dhat::HeapStats::get().total_blocks;
            contact.mlp(&reading).expect("finite");
            mlp_blocks += dhat::HeapStats::get().total_blocks - before;
            mlp_calls += 1;
        }
    }
    let contact_rest = dhat::HeapStats::get().total_blocks - start - mlp_blocks;
    for _ in 0..WARM_UP {
        full.cycle().expect("warm-up cycle");
    }
    let mut full_mlp_calls = 0;
    let start = dhat::HeapStats::get().total_blocks;
    for _ in 0..CYCLES {
        let (d, _) = full.cycle().expect("cycle");
        full_mlp_calls += u64::from(d.mlp.is_some());
    }
    let full_blocks = dhat::HeapStats::get().total_blocks - start;
    let counts = [
        ("weight", blocks(|| weight.cycle().map(drop))),
        ("grasp", blocks(|| grasp.cycle().map(drop))),
        ("softness", blocks(|| softness.cycle().map(drop))),
        ("tap", blocks(|| tap.cycle().map(drop))),
        ("contact without the MLP", contact_rest),
    ];
    for (scene, n) in counts {
        println!("{scene}: {n} blocks in {CYCLES} cycles");
    }
    println!("contact MLP: {mlp_blocks} blocks in {mlp_calls} calls");
    println!("full_hand: {full_blocks} blocks in {CYCLES} cycles, {full_mlp_calls} MLP calls");
    for (scene, n) in counts {
        assert_eq!(n, 0, "{scene}: {n} blocks in {CYCLES} cycles after warm-up");
    }
    assert!(
        mlp_calls > 0,
        "the schedule presses the pad: the MLP must run"
    );
    assert_eq!(
        mlp_blocks, 0,
        "contact MLP: {mlp_blocks} blocks in {mlp_calls} calls"
    );
    assert!(full_mlp_calls > 0, "the full hand runs the MLP too");
    assert_eq!(
        full_blocks, 0,
        "full hand: {full_blocks} blocks in {CYCLES} cycles"
    );
}

/// The scenes whose peak heap is reported.
const SCENES: [&str; 6] = ["weight", "contact", "grasp", "softness", "tap", "full_hand"];

/// Child mode: build `scene`, run it, print dhat's peak (bytes, blocks) and what stays live.
fn peak_of(scene: &str) {
    let _profiler = dhat::Profiler::builder().testing().build();
    let mut cycle: Box<dyn FnMut() -> Result<(), CycleError>> = match scene {
        "weight" => {
            let mut c = WeightCycle::new().expect("weight");
            Box::new(move || c.cycle().map(drop))
        }
        "contact" => {
            let mut c = ContactCycle::new().expect("contact");
            Box::new(move || c.cycle().map(drop))
        }
        "grasp" => {
            let mut c = GraspCycle::new().expect("grasp");
            Box::new(move || c.cycle().map(drop))
        }
        "softness" => {
            let mut c = SoftnessCycle::new().expect("softness");
            Box::new(move || c.cycle().map(drop))
        }
        "tap" => {
            let mut c = TapCycle::new().expect("tap");
            Box::new(move || c.cycle().map(drop))
        }
        _ => {
            let mut c = FullHandCycle::new().expect("full hand");
            Box::new(move || c.cycle().map(drop))
        }
    };
    blocks(&mut cycle);
    let stats = dhat::HeapStats::get();
    println!(
        "peak {} {} {}",
        stats.max_bytes, stats.max_blocks, stats.curr_bytes
    );
}

/// Each scene's peak heap, from one child process per scene.
fn peak_heap_per_scene() {
    let exe = std::env::current_exe().expect("own path");
    println!("| scene | peak heap | peak blocks | live after {CYCLES} cycles |");
    for scene in SCENES {
        let out = std::process::Command::new(&exe)
            .env("HANDSTACK_PEAK_SCENE", scene)
            .output()
            .expect("child runs");
        assert!(
            out.status.success(),
            "{scene}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        let v: Vec<usize> = text
            .lines()
            .find_map(|l| l.strip_prefix("peak "))
            .map(|l| l.split(' ').filter_map(|x| x.parse().ok()).collect())
            .unwrap_or_default();
        assert_eq!(v.len(), 3, "{scene}: {text}");
        // Every scene holds a model or a simulated device on the heap, and its peak bounds it.
        assert!(v[0] > 0 && v[2] > 0 && v[2] <= v[0], "{scene}: {v:?}");
        println!(
            "| {scene} | {:.1} KiB | {} | {:.1} KiB |",
            v[0] as f64 / 1024.0,
            v[1],
            v[2] as f64 / 1024.0
        );
    }
}

/// The checks in turn; in a per-scene child (`HANDSTACK_PEAK_SCENE`), that scene's peak only.
pub(crate) fn run() {
    if let Ok(scene) = std::env::var("HANDSTACK_PEAK_SCENE") {
        peak_of(&scene);
        return;
    }
    cycles_allocate_nothing_in_steady_state();
    println!("cycles_allocate_nothing_in_steady_state: ok");
    peak_heap_per_scene();
}
