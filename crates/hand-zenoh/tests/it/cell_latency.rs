//! The cell measurement (`examples/cell_latency`, `cargo xtask cell-doc`) cannot rot: its
//! orchestrator runs one hand over this crate's nodes for 2 s on loopback and must see every
//! frame arrive, none lost, at a sane latency. `cargo test` builds the examples before it runs
//! the tests; the example sits beside this test's binary, in `target/<profile>/examples/`.

use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

fn example() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's own path");
    // target/<profile>/deps/it-<hash> → target/<profile>/examples/cell_latency
    let profile_dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("the test binary sits in target/<profile>/deps");
    let path = profile_dir
        .join("examples")
        .join(format!("cell_latency{}", std::env::consts::EXE_SUFFIX));
    assert!(
        path.exists(),
        "{} is missing: `cargo test -p hand-zenoh` builds it (a `--test` filter does not; \
         `cargo build --example cell_latency` with the same profile does)",
        path.display()
    );
    path
}

#[test]
fn one_hand_for_two_seconds_arrives_whole() {
    let out = Command::new(example())
        .args(["--hands", "1", "--modes", "rmw", "--seconds", "2"])
        .output()
        .expect("run the cell_latency example");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "cell_latency failed ({}): {text}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    let runs = doc["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 1, "{text}");
    let run = &runs[0];
    assert_eq!(run["mode"], "rmw");
    assert_eq!(run["hands"], 1);
    assert_eq!(run["topics"], 5, "3 fingertips and the pad's 2 topics");
    assert!(run["samples"].as_u64() > Some(0), "{run}");
    let p50 = run["p50_us"].as_f64().expect("p50");
    assert!(
        p50.is_finite() && p50 > 0.0 && p50 < 50_000.0,
        "p50 {p50} µs"
    );
    assert_eq!(run["lost"], 0, "{run}");
    assert_eq!(run["malformed"], 0, "{run}");
    assert_eq!(run["silent_topics"], 0, "{run}");
}
