//! Scene files: TOML that names the parts of a hand stack and the experiment to run on it.
//!
//! A scene's parts (`[sensors.*]`, `[estimators.*]`, `[controller]`, `[hand]`, `[arm]`) are one
//! schema, checked here; what it runs (`[experiment.*]`) is a table the caller chooses: the
//! `handstack` binary's [`Experiments`](experiment::Experiments) (a grasp hold and a sensor
//! readout on real devices), or a reproduction's own table through [`ExperimentTable`].
//!
//! ```
//! use handstack::scene::Scene;
//!
//! let scene = Scene::parse(
//!     "my-hand.toml",
//!     r#"
//!     title = "Bench hand"
//!     [sensors.fingertip]
//!     osr = 1024
//!     i2c_buses = ["/dev/i2c-1", "/dev/i2c-3", "/dev/i2c-4"]
//!     [controller]
//!     preset = "grasp"
//!     [hand]
//!     model = "mx28"
//!     serial_port = "/dev/ttyUSB0"
//!     [experiment.grasp]
//!     torque_band = [250, 320]
//!     hold_s = 30
//!     "#,
//! )?;
//! assert_eq!(scene.name, "my-hand");
//! // An OSR the MS5611 does not have names the key, the line and what is allowed.
//! let err = Scene::parse("bad.toml", "title = \"x\"\n[sensors.fingertip]\nosr = 300\n[experiment.readout]\nframes = 10\n")
//!     .unwrap_err();
//! assert!(err.to_string().starts_with("bad.toml:3:7: `sensors.fingertip.osr`"), "{err}");
//! # Ok::<(), handstack::scene::SceneError>(())
//! ```

mod error;
pub mod experiment;
pub mod force;
pub mod parts;
mod validate;

pub use error::{Location, SceneError};
pub use validate::Checker;

use serde::Deserialize;
use serde::de::DeserializeOwned;
use std::path::Path;
use tactile_nets::contact_cnn::ContactCnn;
use tactile_nets::contact_mlp::ContactMlp;
use tactile_nets::softness::SoftnessNet;
use toml::Spanned;

/// What a scene's `[experiment]` table holds: the experiments one program can run.
pub trait ExperimentTable: DeserializeOwned + Clone + Default + core::fmt::Debug {
    /// What may appear under `[experiment]`, for the error of a scene that names none
    /// (`"[experiment.grasp], [experiment.readout]"`).
    const ALLOWED: &'static str;
    /// Whether a scene must name an experiment (a node's scene need not: it runs its parts).
    const REQUIRED: bool = true;
    /// The names of the experiments present, in run order.
    fn names(&self) -> Vec<&'static str>;
    /// Checks the experiments against the parts they run on (the parts themselves are checked
    /// already); errors through [`Checker::err`] keep the offending key's span.
    fn check(scene: &SceneFile<Self>, cx: &Checker<'_>) -> Result<(), SceneError>;
}

/// A scene file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "X: DeserializeOwned + Default")]
pub struct SceneFile<X = experiment::Experiments> {
    /// One line saying what the scene reproduces.
    pub title: String,
    /// A simulated environment, as the program that simulates it reads it (the `handstack`
    /// binary opens real devices only and refuses it).
    #[serde(default)]
    pub sim: Option<Spanned<toml::Table>>,
    /// The sensors.
    #[serde(default)]
    pub sensors: parts::Sensors,
    /// The estimators.
    #[serde(default)]
    pub estimators: parts::Estimators,
    /// The grasp controller.
    pub controller: Option<Spanned<parts::Controller>>,
    /// The servo hand.
    pub hand: Option<Spanned<parts::Hand>>,
    /// The arm.
    pub arm: Option<Spanned<parts::Arm>>,
    /// What to run (absent: none, at the file's start).
    #[serde(default = "no_experiment")]
    pub experiment: Spanned<X>,
}

impl<X> SceneFile<X> {
    /// The scene's `[hand]` when it is the underactuated hand (`model = "underactuated4"`).
    pub fn underactuated_hand(&self) -> Option<&Spanned<parts::Hand>> {
        self.hand
            .as_ref()
            .filter(|h| h.get_ref().model.is_underactuated())
    }
}

/// An `[experiment]` table the file does not have.
fn no_experiment<X: Default>() -> Spanned<X> {
    Spanned::new(0..0, X::default())
}

/// A parsed and validated `handstack` scene.
pub type Scene = SceneOf<experiment::Experiments>;

/// A scene as `handstack node` reads it: its parts, and its experiments if any (a grasp gives
/// the hand node its band, goal and recovery).
pub type NodeScene = SceneOf<experiment::NodeExperiments>;

/// A parsed and validated scene whose `[experiment]` table is `X`.
#[derive(Debug, Clone)]
pub struct SceneOf<X> {
    /// The file stem (`weight-estimation`).
    pub name: String,
    /// The file's contents as written.
    pub file: SceneFile<X>,
    /// The force DNN `[estimators.force]` names, read (a weights file relative to the scene
    /// file's directory).
    pub force: Option<force::ForceNet>,
    /// The contact CNN `[estimators.contact] cnn_weights` names, read (relative to the scene
    /// file's directory); `None`: the built-in one ([`SceneOf::contact_cnn`]).
    pub cnn: Option<ContactCnn>,
    /// The contact MLP `[estimators.contact] mlp_weights` names, read (relative to the scene
    /// file's directory); `None`: the one the fingertip's firmware runs.
    pub mlp: Option<ContactMlp>,
    /// The softness net `[estimators.softness] weights` names, read (relative to the scene
    /// file's directory); `None`: the built-in one ([`SceneOf::softness_net`]).
    pub softness: Option<SoftnessNet>,
}

impl<X: ExperimentTable> SceneOf<X> {
    /// Reads and validates the scene file at `path`.
    pub fn load(path: &Path) -> Result<SceneOf<X>, SceneError> {
        let text = read(path)?;
        SceneOf::parse(&path.display().to_string(), &text)
    }

    /// Parses and validates scene text; `file` names it in errors (its stem names the scene).
    pub fn parse(file: &str, text: &str) -> Result<SceneOf<X>, SceneError> {
        let parsed: SceneFile<X> =
            toml::from_str(text).map_err(|e| SceneError::syntax(file, text, &e))?;
        let cx = Checker::new(file, text);
        validate::check_parts(&parsed, &cx)?;
        if X::REQUIRED && parsed.experiment.get_ref().names().is_empty() {
            return Err(cx.err(
                parsed.experiment.span(),
                "experiment",
                "names no experiment",
                format!("one or more of {}", X::ALLOWED),
            ));
        }
        X::check(&parsed, &cx)?;
        let force = force_net(file, &parsed, &cx)?;
        let cnn = cnn_file(file, &parsed, &cx)?;
        let mlp = mlp_file(file, &parsed, &cx)?;
        let softness = softness_file(file, &parsed, &cx)?;
        let name = Path::new(file)
            .file_stem()
            .map_or_else(|| file.to_owned(), |s| s.to_string_lossy().into_owned());
        Ok(SceneOf {
            name,
            file: parsed,
            force,
            cnn,
            mlp,
            softness,
        })
    }

    /// The contact locators `[estimators.contact]` names (none without that table).
    pub fn locators(&self) -> Vec<parts::Locator> {
        self.file
            .estimators
            .contact
            .as_ref()
            .map(|c| c.get_ref().locators.get_ref().clone())
            .unwrap_or_default()
    }

    /// The contact CNN the scene runs: its `cnn_weights` file, or the built-in paper variant
    /// (Al & Martinez-Hernandez, §IV-A).
    ///
    /// Errors: the built-in weights' (they are compiled in and tested: none in practice).
    pub fn contact_cnn(&self) -> Result<ContactCnn, tactile_nets::NetError> {
        match &self.cnn {
            Some(cnn) => Ok(cnn.clone()),
            None => {
                tactile_nets::pretrained::contact_cnn(tactile_nets::contact_cnn::Variant::Paper)
            }
        }
    }

    /// The softness net the scene runs: its `[estimators.softness] weights` file, or the
    /// built-in one (the underactuated-hand softness paper, §2.3).
    pub fn softness_net(&self) -> &SoftnessNet {
        self.softness
            .as_ref()
            .unwrap_or(&tactile_nets::pretrained::SOFTNESS)
    }

    /// The built-in force DNN `[estimators.force]` names (none without that table, or when it
    /// names a weights file).
    pub fn force_model(&self) -> Option<parts::ForceModel> {
        self.file
            .estimators
            .force
            .as_ref()
            .and_then(|f| f.get_ref().model)
    }
}

/// The force DNN of the scene `file`, its weights file read relative to the scene's directory.
fn force_net<X>(
    file: &str,
    scene: &SceneFile<X>,
    cx: &Checker<'_>,
) -> Result<Option<force::ForceNet>, SceneError> {
    let Some(f) = &scene.estimators.force else {
        return Ok(None);
    };
    let f = f.get_ref();
    if let Some(m) = f.model {
        return Ok(Some(force::ForceNet::BuiltIn(m)));
    }
    weights_file(
        file,
        f.weights.as_ref(),
        cx,
        "estimators.force.weights",
        "a force DNN weights file (`handstack train force` writes one)",
        force::ForceNet::load,
    )
}

/// The contact CNN weights file of the scene `file`, read relative to the scene's directory.
fn cnn_file<X>(
    file: &str,
    scene: &SceneFile<X>,
    cx: &Checker<'_>,
) -> Result<Option<ContactCnn>, SceneError> {
    let w = scene
        .estimators
        .contact
        .as_ref()
        .and_then(|c| c.get_ref().cnn_weights.as_ref());
    weights_file(
        file,
        w,
        cx,
        "estimators.contact.cnn_weights",
        "a contact CNN weights file (`handstack train contact-cnn` writes one)",
        ContactCnn::load,
    )
}

/// The contact MLP weights file of the scene `file`, read relative to the scene's directory.
fn mlp_file<X>(
    file: &str,
    scene: &SceneFile<X>,
    cx: &Checker<'_>,
) -> Result<Option<ContactMlp>, SceneError> {
    let w = scene
        .estimators
        .contact
        .as_ref()
        .and_then(|c| c.get_ref().mlp_weights.as_ref());
    weights_file(
        file,
        w,
        cx,
        "estimators.contact.mlp_weights",
        "a contact MLP weights file (`handstack train contact-mlp` writes one)",
        ContactMlp::load,
    )
}

/// The softness net weights file of the scene `file`, read relative to the scene's directory.
fn softness_file<X>(
    file: &str,
    scene: &SceneFile<X>,
    cx: &Checker<'_>,
) -> Result<Option<SoftnessNet>, SceneError> {
    let w = scene
        .estimators
        .softness
        .as_ref()
        .and_then(|c| c.get_ref().weights.as_ref());
    weights_file(
        file,
        w,
        cx,
        "estimators.softness.weights",
        "a softness net weights file (`handstack train softness` writes one)",
        SoftnessNet::load,
    )
}

/// The model in the weights file `w` names (if it names one), read with `load` relative to
/// the directory of the scene `file`; an error names `key` and says `what` the file must be.
fn weights_file<M>(
    file: &str,
    w: Option<&Spanned<std::path::PathBuf>>,
    cx: &Checker<'_>,
    key: &str,
    what: &str,
    load: impl FnOnce(&Path) -> Result<M, tactile_nets::NetError>,
) -> Result<Option<M>, SceneError> {
    let Some(w) = w else {
        return Ok(None);
    };
    let dir = Path::new(file).parent().unwrap_or(Path::new(""));
    load(&dir.join(w.get_ref())).map(Some).map_err(|e| {
        cx.err(
            w.span(),
            key,
            format!("cannot be used: {e}"),
            format!("{what}, relative to the scene file"),
        )
    })
}

/// The text of the scene file at `path`.
pub fn read(path: &Path) -> Result<String, SceneError> {
    std::fs::read_to_string(path).map_err(|source| SceneError::Read {
        path: path.to_owned(),
        source,
    })
}
