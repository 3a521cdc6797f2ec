//! Files users write or download: fuzzy engines, scenes, model weights, datasets.

use fuzzy_mamdani::{Engine, FileError, from_fis, from_fll, to_fis, to_fll};
use handstack::scene::Scene;
use paper_experiments::data::{fingertip, imu_pad, underactuated, weights};
use tactile_nets::contact_cnn::{ContactCnn, WINDOW_VALUES};
use tactile_nets::contact_mlp::{ContactMlp, N_FEATURES};
use tactile_nets::force_dnn::ForceDnn;
use tactile_nets::io::TensorFile;
use tactile_nets::softness::{N_VARIABLES, SoftnessNet};

/// The bytes as text, or `None` where they are not UTF-8 (every reader here takes `&str`; a
/// caller turns bytes into text first and gets that error there).
fn text(data: &[u8]) -> Option<&str> {
    std::str::from_utf8(crate::bounded(data)).ok()
}

/// Evaluates `engine` at each input's lower bound, middle and upper bound, and just outside.
///
/// Oracle: an answer is finite, or the output's declared default.
fn evaluate(engine: &Engine<f64>) {
    let mut scratch = engine.scratch();
    let n = engine.inputs().len();
    for k in 0..5 {
        let x: Vec<f64> = engine
            .inputs()
            .iter()
            .map(|v| match k {
                0 => v.min,
                1 => v.max,
                2 => v.min / 2.0 + v.max / 2.0,
                3 => v.min - (v.max - v.min),
                _ => v.max + 1.0,
            })
            .collect();
        debug_assert_eq!(x.len(), n);
        if let Ok(out) = engine.evaluate(&mut scratch, &x) {
            for (y, var) in out.iter().zip(engine.outputs()) {
                let default = var.default.is_some_and(|d| d.to_bits() == y.to_bits());
                assert!(y.is_finite() || default, "{} = {y}", var.name);
            }
        }
    }
}

/// Import, evaluation and export of one format.
///
/// Oracle: what the crate exports, it imports again.
fn engine_file(
    data: &[u8],
    import: fn(&str) -> Result<Engine<f64>, FileError>,
    export: fn(&Engine<f64>) -> Result<String, FileError>,
) {
    let Some(text) = text(data) else {
        return;
    };
    let Ok(engine) = import(text) else {
        return;
    };
    evaluate(&engine);
    if let Ok(written) = export(&engine) {
        if let Err(e) = import(&written) {
            panic!("exported text does not import: {e}\n{written}");
        }
    }
}

/// MATLAB `.fis`.
pub fn fis(data: &[u8]) {
    engine_file(data, from_fis::<f64>, to_fis::<f64>);
}

/// fuzzylite `.fll`.
pub fn fll(data: &[u8]) {
    engine_file(data, from_fll::<f64>, to_fll::<f64>);
}

/// A `handstack` scene file, and its error text.
///
/// Oracle: an error names the file once and, for a position, within the text.
pub fn scene(data: &[u8]) {
    let Some(text) = text(data) else {
        return;
    };
    if let Err(e) = Scene::parse("fuzz.toml", text) {
        let shown = e.to_string();
        assert!(!shown.is_empty());
    }
}

/// A weights file of one of the four models (the first byte picks which), then one forward
/// pass on a fixed input.
pub fn model(data: &[u8]) {
    let data = crate::bounded(data);
    let [kind, bytes @ ..] = data else {
        return;
    };
    match kind % 4 {
        0 => {
            if let Ok(m) = TensorFile::parse_with("fuzz", bytes, ContactMlp::from_file) {
                let _ = m.predict(&[0.5; N_FEATURES]);
            }
        }
        1 => {
            if let Ok(m) = TensorFile::parse_with("fuzz", bytes, ContactCnn::from_file) {
                let _ = m.predict(&[0.25; WINDOW_VALUES]);
            }
        }
        2 => {
            if let Ok(m) = TensorFile::parse_with("fuzz", bytes, ForceDnn::from_file) {
                let _ = m.estimate_gf(&[1.0, 2.0, 3.0]);
            }
        }
        _ => {
            if let Ok(m) = TensorFile::parse_with("fuzz", bytes, SoftnessNet::from_file) {
                let _ = m.predict(&[0.5; 4 * N_VARIABLES]);
            }
        }
    }
}

/// The byte that separates the two files of a two-file dataset in one input.
pub const FILE_SEPARATOR: u8 = 0;

/// One of the datasets (the first byte picks which reader); two-file datasets take their
/// files separated by [`FILE_SEPARATOR`].
pub fn dataset(data: &[u8]) {
    let data = crate::bounded(data);
    let [kind, rest @ ..] = data else {
        return;
    };
    let Some(text) = text(rest) else {
        return;
    };
    let mut files = text.splitn(2, char::from(FILE_SEPARATOR));
    let (first, second) = (files.next().unwrap_or(""), files.next().unwrap_or(""));
    match kind % 4 {
        0 => drop(fingertip::parse(first, second)),
        1 => drop(imu_pad::parse(text)),
        2 => drop(underactuated::parse(first, &[second])),
        _ => drop(weights::parse_series(text)),
    }
}
