//! Seed 002: the ICM-20789 tactile pad, its contact CNN and the UR3 tap-to-move experiment.

use crate::table::{constants_fixture, typed_fixture};

/// A row of Table I: CNN contact-region accuracy for one contact depth, or for all depths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CnnAccuracyRow {
    /// Contact depth in millimetres; `None` for the "All cases" row.
    pub depth_mm: Option<f64>,
    /// Mean accuracy over 10 random 80 / 20 splits, in percent.
    pub trial_mean_pct: f64,
    /// Its standard deviation, in percent.
    pub trial_std_pct: f64,
    /// Mean accuracy over 5-fold cross-validation, in percent.
    pub kfold_mean_pct: f64,
    /// Its standard deviation, in percent.
    pub kfold_std_pct: f64,
}

/// A measured (and FEA-predicted) force at one contact depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceDepthRow {
    /// Contact depth, in millimetres.
    pub depth_mm: f64,
    /// Force measured with the FT-300, in newton.
    pub measured_n: f64,
    /// Force the paper's FEA predicts, in newton.
    pub fea_n: f64,
}

/// One barometer measurement mode with its noise and current.
#[derive(Debug, Clone, PartialEq)]
pub struct PressureModeRow {
    /// `LP`, `N`, `LN` or `ULN`.
    pub mode: String,
    /// RMS pressure noise, in pascal.
    pub noise_pa: f64,
    /// Supply current, in microampere.
    pub current_ua: f64,
}

/// A Yeoh material constant of Ecoflex 00-30.
#[derive(Debug, Clone, PartialEq)]
pub struct YeohRow {
    /// `C1`…`C3`, `D1`…`D3`.
    pub name: String,
    /// The value.
    pub value: f64,
    /// `kPa` for the `C_i`; empty for the `D_i`, which the paper gives without a unit.
    pub unit: String,
}

typed_fixture!(
    /// Table I: CNN accuracy per contact depth 0.2…1.6 mm and for all depths (9 rows).
    table1_cnn_accuracy, table1_cnn_accuracy_in, "seed002_table1_cnn_accuracy", CnnAccuracyRow,
    |r| Ok(CnnAccuracyRow {
        depth_mm: r.opt_f64("depth_mm")?,
        trial_mean_pct: r.f64("trial_mean_pct")?,
        trial_std_pct: r.f64("trial_std_pct")?,
        kfold_mean_pct: r.f64("kfold_mean_pct")?,
        kfold_std_pct: r.f64("kfold_std_pct")?,
    })
);

typed_fixture!(
    /// Force against contact depth: 0.8 mm 3.5 N, 1.3 mm 8 N, 1.7 mm 13 N (and the FEA figures).
    force_depth, force_depth_in, "seed002_force_depth", ForceDepthRow,
    |r| Ok(ForceDepthRow {
        depth_mm: r.f64("depth_mm")?,
        measured_n: r.f64("measured_n")?,
        fea_n: r.f64("fea_n")?,
    })
);

typed_fixture!(
    /// The four barometer modes LP / N / LN / ULN with noise and current.
    pressure_modes, pressure_modes_in, "seed002_pressure_modes", PressureModeRow,
    |r| Ok(PressureModeRow {
        mode: r.str("mode")?.to_string(),
        noise_pa: r.f64("noise_pa")?,
        current_ua: r.f64("current_ua")?,
    })
);

typed_fixture!(
    /// The six Yeoh constants of eq. 2.
    yeoh, yeoh_in, "seed002_yeoh", YeohRow,
    |r| Ok(YeohRow { name: r.str("name")?.to_string(), value: r.f64("value")?, unit: r.str("unit")?.to_string() })
);

constants_fixture!("seed002_constants");

/// The force polynomial of eq. 1, `F(p) = a2·p² + a1·p + a0`, in newton for `p` in counts,
/// with its coefficients read from the constants fixture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForcePolynomial {
    /// Quadratic coefficient, N/count².
    pub a2: f64,
    /// Linear coefficient, N/count.
    pub a1: f64,
    /// Constant term, N.
    pub a0: f64,
}

impl ForcePolynomial {
    /// Eq. 1's coefficients from `constants`.
    pub fn from_constants(constants: &crate::Constants) -> Result<Self, crate::FixtureError> {
        Ok(Self {
            a2: constants.value("force_poly_a2", "N/count^2")?,
            a1: constants.value("force_poly_a1", "N/count")?,
            a0: constants.value("force_poly_a0", "N")?,
        })
    }

    /// `F(p)` in newton.
    ///
    /// ```
    /// use paper_fixtures::seed002::{constants, ForcePolynomial};
    /// let f = ForcePolynomial::from_constants(&constants()?)?;
    /// assert!((f.force_n(0.0) - 2.3304).abs() < 1e-12);
    /// # Ok::<(), paper_fixtures::FixtureError>(())
    /// ```
    pub fn force_n(&self, counts: f64) -> f64 {
        (self.a2 * counts + self.a1) * counts + self.a0
    }
}
