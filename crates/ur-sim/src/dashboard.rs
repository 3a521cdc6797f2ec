//! The dashboard server (port 29999): one command a line, one answer a line, in PolyScope's
//! wording (Universal Robots' "Dashboard Server CB-Series" command list).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;

use super::Shared;
use ur_bridge::status::{robot_mode, safety_mode};

fn mode_name(mode: i32) -> &'static str {
    match mode {
        robot_mode::NO_CONTROLLER => "NO_CONTROLLER",
        robot_mode::DISCONNECTED => "DISCONNECTED",
        robot_mode::CONFIRM_SAFETY => "CONFIRM_SAFETY",
        robot_mode::BOOTING => "BOOTING",
        robot_mode::POWER_OFF => "POWER_OFF",
        robot_mode::POWER_ON => "POWER_ON",
        robot_mode::IDLE => "IDLE",
        robot_mode::BACKDRIVE => "BACKDRIVE",
        _ => "RUNNING",
    }
}

fn safety_name(mode: i32) -> &'static str {
    match mode {
        safety_mode::PROTECTIVE_STOP => "PROTECTIVE_STOP",
        safety_mode::REDUCED => "REDUCED",
        _ => "NORMAL",
    }
}

/// The answer to one command line.
fn answer(shared: &Shared, line: &str) -> Option<String> {
    let cmd = line.trim();
    let mut c = shared.lock();
    let (major, minor, bugfix, build) = shared.config.controller_version;
    Some(match cmd {
        "PolyscopeVersion" => format!("URSoftware {major}.{minor}.{bugfix}.{build} (simulated)"),
        "robotmode" => format!("Robotmode: {}", mode_name(c.robot_mode)),
        "safetymode" => format!("Safetymode: {}", safety_name(c.safety_mode)),
        "safetystatus" => format!("Safetystatus: {}", safety_name(c.safety_mode)),
        "power on" => {
            c.power_on();
            "Powering on".into()
        }
        "power off" => {
            c.power_off();
            "Powering off".into()
        }
        "brake release" => {
            c.brake_release();
            "Brake releasing".into()
        }
        "unlock protective stop" => {
            if c.unlock_protective_stop() {
                "Protective stop releasing".into()
            } else {
                "Cannot unlock protective stop: robot is not protective stopped".into()
            }
        }
        "close safety popup" => "closing safety popup".into(),
        "close popup" => "closing popup".into(),
        "play" => {
            if c.play() {
                "Starting program".into()
            } else {
                "Failed to execute: play".into()
            }
        }
        "stop" => {
            c.stop_program();
            "Stopped".into()
        }
        "pause" => "Failed to execute: pause".into(),
        "running" => format!(
            "Program running: {}",
            c.runtime_state == ur_bridge::status::runtime_state::PLAYING
        ),
        "programState" => {
            let state = match c.runtime_state {
                ur_bridge::status::runtime_state::PLAYING => "PLAYING",
                ur_bridge::status::runtime_state::PAUSED => "PAUSED",
                _ => "STOPPED",
            };
            format!("{state} {}", c.program_name())
        }
        "get loaded program" => "No program loaded".into(),
        "is in remote control" => "true".into(),
        "isProgramSaved" => "true".into(),
        "get robot model" => "UR3".into(),
        "get serial number" => "20235500001".into(),
        "quit" => return None,
        other if other.starts_with("addToLog ") => "Added log message".into(),
        other => format!("could not understand: '{other}'"),
    })
}

/// The longest command line served; PolyScope's commands are a few dozen bytes. A longer line
/// (or garbage without newlines) ends the connection instead of growing a buffer.
pub(crate) const MAX_LINE_BYTES: usize = 4096;

/// Serves one dashboard connection until it closes, `quit` or the simulator stops.
pub(crate) fn serve(shared: &Shared, stream: TcpStream) -> std::io::Result<()> {
    let out = stream.try_clone()?;
    serve_io(shared, BufReader::new(stream), out, |_| {})
}

/// The dashboard over any byte stream (a socket, or a fuzzer's bytes); `after_line` runs after
/// each answered line.
pub(crate) fn serve_io(
    shared: &Shared,
    mut input: impl BufRead,
    mut out: impl Write,
    mut after_line: impl FnMut(&Shared),
) -> std::io::Result<()> {
    out.write_all(b"Connected: Universal Robots Dashboard Server\n")?;
    let mut line = Vec::new();
    loop {
        line.clear();
        let limit = (MAX_LINE_BYTES + 1) as u64;
        let n = (&mut input).take(limit).read_until(b'\n', &mut line)?;
        if n == 0 || shared.stopped() {
            break;
        }
        if !line.ends_with(b"\n") && line.len() > MAX_LINE_BYTES {
            out.write_all(
                format!("could not understand: a line over {MAX_LINE_BYTES} bytes\nDisconnected\n")
                    .as_bytes(),
            )?;
            break;
        }
        // Bytes that are not UTF-8 are answered like any unknown command, not fatal.
        let text = String::from_utf8_lossy(&line);
        match answer(shared, &text) {
            Some(reply) => out.write_all(format!("{reply}\n").as_bytes())?,
            None => {
                out.write_all(b"Disconnected\n")?;
                break;
            }
        }
        after_line(shared);
    }
    Ok(())
}
