//! The `paper-scenes` binary: `run SCENE --json` prints the outcomes as JSON on stdout; a bad scene
//! exits non-zero with the error (file:line:col, key, allowed values) on stderr.

use crate::common;

use std::process::Command;

fn paper_scenes() -> Command {
    Command::new(env!("CARGO_BIN_EXE_paper-scenes"))
}

#[test]
fn json_prints_the_outcomes() {
    let out = paper_scenes()
        .args(["run", "--json"])
        .arg(common::scene_path("weight-estimation"))
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    let o = &v[0];
    assert_eq!(o["scene"], "weight-estimation");
    assert!(o["figures"].as_array().is_some_and(|f| !f.is_empty()));
    assert_eq!(o["plots"][0]["kind"], "lines");
}

#[test]
fn a_bad_scene_exits_non_zero_and_says_why() {
    let dir = std::env::temp_dir().join(format!("handstack-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "title = \"x\"\n[sensors.fingertip]\nosr = 300\n[experiment.readout]\nframes = 5\n",
    )
    .expect("write");
    let out = paper_scenes().arg("run").arg(&bad).output().expect("runs");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    // The file once, then line:col (not `error: bad.toml: bad.toml:3:7: …`).
    let line = format!(
        "error: {}:3:7: `sensors.fingertip.osr` is 300, an OSR the MS5611 does not have; \
         allowed: 256, 512, 1024, 2048, 4096",
        bad.display()
    );
    assert!(err.lines().any(|l| l == line), "{err}");
    assert_eq!(err.matches(&*bad.display().to_string()).count(), 1, "{err}");
    assert!(out.stdout.is_empty() || !String::from_utf8_lossy(&out.stdout).contains("figure"));
}
