//! Fuzz targets for every parser the stack feeds bytes it did not make: a device's replies, a
//! client's requests to our simulators, files users write, models and datasets on disk, and
//! payloads from the network.
//!
//! Each target is a plain function of a byte slice. `fuzz/` (a cargo-fuzz project, its own
//! workspace) wraps each in `fuzz_target!` and `cargo xtask fuzz TARGET` runs it under
//! libFuzzer; the corpus replay test (`tests/corpora.rs`, in `cargo xtask test`) runs the same
//! functions over the committed corpora, so a finding stays fixed once its input is committed.
//!
//! A target panics only when the code under test does (a crash) or when one of its oracles
//! fails: the property it checks beyond "no panic" (named in each target's docs).
//!
//! ```
//! let t = handstack_fuzz::target("fll").unwrap();
//! (t.run)(b"Engine: e\nInputVariable: x\n  range: 0 1\n");
//! ```

pub mod dxl;
pub mod files;
pub mod network;
pub mod seeds;
pub mod ur;

/// One fuzz target.
#[derive(Debug, Clone, Copy)]
pub struct Target {
    /// Its name: the `fuzz/fuzz_targets/NAME.rs` file and the `fuzz/corpus/NAME/` folder.
    pub name: &'static str,
    /// What it feeds the bytes to.
    pub about: &'static str,
    /// The target.
    pub run: fn(&[u8]),
}

/// Every target, in the order `docs/reliability.md` lists them.
pub const TARGETS: [Target; 11] = [
    Target {
        name: "dxl_status",
        about: "Protocol 2.0 framing and the driver's status-packet checks (hand-control)",
        run: dxl::status,
    },
    Target {
        name: "dxl_sim",
        about: "the simulated servo bus's request handling (hand-control `sim`)",
        run: dxl::sim,
    },
    Target {
        name: "ur_rtde",
        about: "the UR simulator's RTDE server (ur-bridge `sim`, port 30004)",
        run: ur::rtde,
    },
    Target {
        name: "ur_dashboard",
        about: "the UR simulator's dashboard server (ur-bridge `sim`, port 29999)",
        run: ur::dashboard,
    },
    Target {
        name: "ur_script",
        about: "the UR simulator's script intake (ur-bridge `sim`, port 30003)",
        run: ur::script,
    },
    Target {
        name: "fis",
        about: "MATLAB .fis import, evaluation and re-export (fuzzy-mamdani)",
        run: files::fis,
    },
    Target {
        name: "fll",
        about: "fuzzylite .fll import, evaluation and re-export (fuzzy-mamdani)",
        run: files::fll,
    },
    Target {
        name: "scene",
        about: "scene TOML parsing and validation, and the error text (handstack)",
        run: files::scene,
    },
    Target {
        name: "model",
        about: "safetensors model loading and one forward pass (tactile-nets)",
        run: files::model,
    },
    Target {
        name: "dataset",
        about: "the datasets' CSV readers (paper-experiments)",
        run: files::dataset,
    },
    Target {
        name: "cdr",
        about: "CDR message payloads and rmw_zenoh attachments (hand-zenoh)",
        run: network::cdr,
    },
];

/// The target called `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}

/// The longest input a target looks at; longer ones are cut (libFuzzer's `-max_len` is set to
/// the longest seed, and a model file is the longest).
pub const MAX_INPUT: usize = 1 << 20;

/// `data` cut to [`MAX_INPUT`].
fn bounded(data: &[u8]) -> &[u8] {
    &data[..data.len().min(MAX_INPUT)]
}
