//! The orchestrator: for each configuration (hands × mode) a free port on 127.0.0.1, then the
//! router, the sink, the pad and one process per hand as children of this one; the sink's
//! window; each child's CPU time (`/proc/<pid>/stat`, utime + stime) read when the window
//! starts and when it ends; the children stopped (stdin closed, killed after a bounded wait).
//! Prints one JSON document: every run, each configuration summarised over the rounds
//! (medians), and the overhead of `rmw` over `bare` per hand count.

use crate::Error;
use crate::args::Args;
use crate::topics::{FINGERTIPS, HAND_HZ, PAD_HZ};
use serde_json::{Value, json};
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long the router may take to listen.
const ROUTER_UP: Duration = Duration::from_secs(20);
/// How long a stopped child may take to exit before it is killed.
const EXIT_GRACE: Duration = Duration::from_secs(5);

/// A child and the lines it prints.
struct Proc {
    role: String,
    child: Child,
    lines: Option<mpsc::Receiver<String>>,
}

impl Proc {
    fn spawn(exe: &Path, args: &[String], role: &str, read: bool) -> Result<Proc, Error> {
        let mut child = Command::new(exe)
            .args(args)
            .stdin(Stdio::piped())
            .stdout(if read { Stdio::piped() } else { Stdio::null() })
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(|e| format!("{role}: {e}"))?;
        let lines = child.stdout.take().map(|out| {
            let (tx, rx) = mpsc::channel();
            std::thread::spawn(move || {
                for line in BufReader::new(out).lines() {
                    let Ok(line) = line else { break };
                    if tx.send(line).is_err() {
                        break;
                    }
                }
            });
            rx
        });
        Ok(Proc {
            role: role.to_owned(),
            child,
            lines,
        })
    }

    /// The next JSON line whose `event` is `event`, within `timeout`.
    fn expect(&self, event: &str, timeout: Duration) -> Result<Value, Error> {
        let rx = self.lines.as_ref().ok_or("no stdout to read")?;
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline
                .checked_duration_since(Instant::now())
                .ok_or_else(|| format!("{}: no {event} within {timeout:?}", self.role))?;
            match rx.recv_timeout(left) {
                Ok(line) => {
                    let v: Value = serde_json::from_str(&line)
                        .map_err(|e| format!("{}: {line}: {e}", self.role))?;
                    if v["event"] == event {
                        return Ok(v);
                    }
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(format!("{}: exited before {event}", self.role).into());
                }
            }
        }
    }

    /// utime + stime so far, in clock ticks.
    fn cpu_ticks(&self) -> Option<u64> {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.child.id())).ok()?;
        // The command name may hold spaces: the fields that follow it come after its `)`.
        let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
        let utime: u64 = fields.get(11)?.parse().ok()?;
        let stime: u64 = fields.get(12)?.parse().ok()?;
        Some(utime + stime)
    }
}

/// Closes every child's stdin, then waits for each up to [`EXIT_GRACE`] (all together) and
/// kills those still running.
fn stop_all(procs: &mut [Proc]) {
    for p in procs.iter_mut() {
        drop(p.child.stdin.take());
    }
    let deadline = Instant::now() + EXIT_GRACE;
    for p in procs.iter_mut() {
        loop {
            match p.child.try_wait() {
                Ok(Some(_)) | Err(_) => break,
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(10));
                }
                Ok(None) => {
                    eprintln!("cell_latency: {} did not exit: killed", p.role);
                    let _ = p.child.kill();
                    let _ = p.child.wait();
                    break;
                }
            }
        }
    }
}

/// Clock ticks per second (`getconf CLK_TCK`; 100 when that fails).
fn clock_ticks() -> f64 {
    Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(100.0)
}

fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()))
        .unwrap_or(f64::NAN)
}

struct Run<'a> {
    exe: &'a Path,
    hands: usize,
    bare: bool,
    seconds: f64,
    discovery_s: f64,
    ticks_per_s: f64,
}

impl Run<'_> {
    fn mode(&self) -> &'static str {
        if self.bare { "bare" } else { "rmw" }
    }

    fn measure(&self, procs: &mut Vec<Proc>) -> Result<Value, Error> {
        let endpoint = hand_zenoh::config::free_loopback_endpoint()?;
        let cap = format!("{}", self.seconds + self.discovery_s + 30.0);
        let with_mode = |mut a: Vec<String>| {
            if self.bare {
                a.push("--bare".into());
            }
            a
        };
        let s = |x: &str| x.to_owned();
        let load_before = load_average();
        procs.push(Proc::spawn(
            self.exe,
            &[
                s("router"),
                s("--listen"),
                endpoint.clone(),
                s("--seconds"),
                cap.clone(),
            ],
            "router",
            true,
        )?);
        procs[0].expect("listening", ROUTER_UP)?;
        let sink_args = with_mode(vec![
            s("sink"),
            s("--connect"),
            endpoint.clone(),
            s("--hands"),
            self.hands.to_string(),
            s("--pad"),
            s("--seconds"),
            self.seconds.to_string(),
            s("--discovery-timeout"),
            self.discovery_s.to_string(),
        ]);
        procs.push(Proc::spawn(self.exe, &sink_args, "sink", true)?);
        let pad_args = with_mode(vec![
            s("pad"),
            s("--connect"),
            endpoint.clone(),
            s("--seconds"),
            cap.clone(),
        ]);
        procs.push(Proc::spawn(self.exe, &pad_args, "pad", false)?);
        for k in 0..self.hands {
            let hand_args = with_mode(vec![
                s("hands"),
                s("--first"),
                k.to_string(),
                s("--count"),
                s("1"),
                s("--connect"),
                endpoint.clone(),
                s("--seconds"),
                cap.clone(),
            ]);
            procs.push(Proc::spawn(
                self.exe,
                &hand_args,
                &format!("hand{k}"),
                false,
            )?);
        }
        let measuring = procs[1].expect(
            "measuring",
            Duration::from_secs_f64(self.discovery_s + 10.0),
        )?;
        let t0 = Instant::now();
        let ticks0: Vec<Option<u64>> = procs.iter().map(Proc::cpu_ticks).collect();
        procs[1].expect("done", Duration::from_secs_f64(self.seconds + 10.0))?;
        let ticks1: Vec<Option<u64>> = procs.iter().map(Proc::cpu_ticks).collect();
        let wall = t0.elapsed().as_secs_f64();
        let result = procs[1].expect("result", Duration::from_secs(10))?;
        let load_after = load_average();
        let cpu: Vec<f64> = ticks0
            .iter()
            .zip(&ticks1)
            .map(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => 100.0 * (b - a) as f64 / self.ticks_per_s / wall,
                _ => f64::NAN,
            })
            .collect();
        let hand_cpu = &cpu[3..];
        let hands_mean = hand_cpu.iter().sum::<f64>() / hand_cpu.len().max(1) as f64;
        let hands_max = hand_cpu.iter().copied().fold(f64::NAN, f64::max);
        let mut out = result;
        out["mode"] = json!(self.mode());
        out["expected_rate_hz"] =
            json!(self.hands as f64 * FINGERTIPS as f64 * HAND_HZ + 2.0 * PAD_HZ);
        out["discovery_s"] = measuring["discovery_s"].clone();
        out["cpu_wall_s"] = json!(wall);
        out["cpu_percent"] = json!({
            "router": cpu[0],
            "sink": cpu[1],
            "pad": cpu[2],
            "hand_mean": hands_mean,
            "hand_max": hands_max,
            "total": cpu.iter().sum::<f64>(),
        });
        out["load_average"] = json!([load_before, load_after]);
        out.as_object_mut().map(|o| o.remove("event"));
        Ok(out)
    }
}

fn list<T: std::str::FromStr>(args: &Args<'_>, name: &str, default: &str) -> Result<Vec<T>, Error> {
    args.value(name)
        .unwrap_or(default)
        .split(',')
        .map(|x| {
            x.trim()
                .parse()
                .map_err(|_| format!("{name}: {x} is not a valid value").into())
        })
        .collect()
}

/// The median of `v` (the mean of the middle two for an even count); NaN when empty.
fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

/// One configuration over its rounds: medians of p50, p99 and CPU, the largest max, sums of
/// samples and losses.
fn summarise(hands: usize, mode: &str, runs: &[&Value]) -> Value {
    let num = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    let med = |k: &str| median(runs.iter().map(|r| num(r, k)).collect());
    let sum = |k: &str| runs.iter().filter_map(|r| r[k].as_u64()).sum::<u64>();
    let cpu = |k: &str| median(runs.iter().map(|r| num(&r["cpu_percent"], k)).collect());
    let errors: Vec<Value> = runs
        .iter()
        .flat_map(|r| r["errors"].as_array().cloned().unwrap_or_default())
        .collect();
    json!({
        "hands": hands,
        "mode": mode,
        "rounds": runs.len(),
        "topics": hands * FINGERTIPS + 2,
        "expected_rate_hz": hands as f64 * FINGERTIPS as f64 * HAND_HZ + 2.0 * PAD_HZ,
        "samples": sum("samples"),
        "rate_hz": med("rate_hz"),
        "p50_us": med("p50_us"),
        "p99_us": med("p99_us"),
        "max_us": runs.iter().map(|r| num(r, "max_us")).fold(f64::NAN, f64::max),
        "lost": sum("lost"),
        "malformed": sum("malformed"),
        "discovery_s": runs.iter().map(|r| num(r, "discovery_s")).fold(f64::NAN, f64::max),
        "cpu_percent": {
            "router": cpu("router"),
            "sink": cpu("sink"),
            "pad": cpu("pad"),
            "hand_mean": cpu("hand_mean"),
            "hand_max": cpu("hand_max"),
            "total": cpu("total"),
        },
        "errors": errors,
    })
}

/// The orchestrator: `[--seconds 10] [--hands 1,4,16] [--modes rmw,bare] [--rounds 1]
/// [--discovery-timeout 60]`. Each round runs every configuration once, the modes in turn
/// (rmw first in even rounds, bare first in odd ones).
pub(crate) fn run(args: &Args<'_>) -> Result<(), Error> {
    let seconds: f64 = args.parse("--seconds", 10.0)?;
    let discovery_s: f64 = args.parse("--discovery-timeout", 60.0)?;
    let rounds: usize = args.parse("--rounds", 1)?;
    let hand_counts: Vec<usize> = list(args, "--hands", "1,4,16")?;
    let modes: Vec<String> = list(args, "--modes", "rmw,bare")?;
    if let Some(m) = modes.iter().find(|m| *m != "rmw" && *m != "bare") {
        return Err(format!("--modes: {m} is neither rmw nor bare").into());
    }
    let exe = std::env::current_exe()?;
    let ticks_per_s = clock_ticks();
    let mut runs = Vec::new();
    for round in 0..rounds {
        for &hands in &hand_counts {
            let mut order: Vec<&String> = modes.iter().collect();
            if round % 2 == 1 {
                order.reverse();
            }
            for mode in order {
                let run = Run {
                    exe: &exe,
                    hands,
                    bare: mode == "bare",
                    seconds,
                    discovery_s,
                    ticks_per_s,
                };
                eprintln!(
                    "cell_latency: round {}/{rounds}, {hands} hand(s), {mode}: {seconds} s window …",
                    round + 1
                );
                let mut procs = Vec::new();
                let measured = run.measure(&mut procs);
                stop_all(&mut procs);
                let mut v = measured.unwrap_or_else(
                    |e| json!({"hands": hands, "mode": mode, "errors": [e.to_string()]}),
                );
                v["round"] = json!(round);
                eprintln!(
                    "cell_latency: {} samples, p50 {} µs, p99 {} µs, lost {}",
                    v["samples"], v["p50_us"], v["p99_us"], v["lost"]
                );
                runs.push(v);
            }
        }
    }
    let of = |hands: usize, mode: &str| -> Vec<&Value> {
        runs.iter()
            .filter(|r| r["hands"] == hands && r["mode"] == mode)
            .collect()
    };
    let summary: Vec<Value> = hand_counts
        .iter()
        .flat_map(|&h| modes.iter().map(move |m| (h, m)))
        .map(|(h, m)| summarise(h, m, &of(h, m)))
        .collect();
    let find = |hands: usize, mode: &str| {
        summary
            .iter()
            .find(|r| r["hands"] == hands && r["mode"] == mode && r["samples"].as_u64() > Some(0))
    };
    let overhead: Vec<Value> = hand_counts
        .iter()
        .filter_map(|&h| {
            let (r, b) = (find(h, "rmw")?, find(h, "bare")?);
            let ratio = |k: &str| Some(r[k].as_f64()? / b[k].as_f64()?);
            let per_round: Vec<Option<f64>> = (0..rounds)
                .map(|i| {
                    let p50 = |m: &str| {
                        of(h, m)
                            .into_iter()
                            .find(|x| x["round"] == i)
                            .and_then(|x| x["p50_us"].as_f64())
                    };
                    Some(100.0 * (p50("rmw")? / p50("bare")? - 1.0))
                })
                .collect();
            Some(json!({
                "hands": h,
                "p50_ratio": ratio("p50_us"),
                "p50_overhead_percent": ratio("p50_us").map(|x| 100.0 * (x - 1.0)),
                "p50_overhead_percent_per_round": per_round,
                "p99_ratio": ratio("p99_us"),
            }))
        })
        .collect();
    let failed = runs
        .iter()
        .any(|r| r["errors"].as_array().is_some_and(|e| !e.is_empty()));
    let doc = json!({
        "seconds": seconds,
        "rounds": rounds,
        "fingertips_per_hand": FINGERTIPS,
        "hand_hz": HAND_HZ,
        "pad_hz": PAD_HZ,
        "clock_ticks_per_s": ticks_per_s,
        "summary": summary,
        "overhead": overhead,
        "runs": runs,
    });
    println!("{}", serde_json::to_string_pretty(&doc)?);
    if failed {
        Err("a run failed (see its errors)".into())
    } else {
        Ok(())
    }
}
