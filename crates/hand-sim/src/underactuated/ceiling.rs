//! The most any classifier can get right on household objects: the Bayes rule on each finger's
//! exact local modulus, under the generator's own law ([`dataset`](super::dataset)).
//!
//! A household object's hidden *overall* class ([`GraspSpec::overall`]) is not what the fingers
//! meet: they meet only their local moduli (log-normal around the overall one, or a feature of an adjacent class). The sensor
//! series depend on the label through those four moduli alone, so no classifier of the series
//! can expect to beat the rule that knows them exactly: its accuracy is a ceiling, and on a
//! finite test set its count says how many objects are *misleading* — of an overall class
//! against what their fingers meet. (The dataset's `label`, [`sensor_class`](super::dataset::sensor_class),
//! is a function of those moduli, so its Bayes rule is right on every object.)

use super::dataset::{
    FEATURE_PROBABILITY, GraspSpec, LOCAL_MODULUS_SD, Set, adjacent, check_moduli, household,
    household_band,
};
use crate::SimError;
use hand_traits::Softness;

/// Points of the midpoint rule over each class's band of overall moduli (in ln): the
/// log-normal's σ of 0.5 spans ≥ 40 points in every band.
const GRID: usize = 256;

/// Log density, in ln(modulus), of the uniform law on `band`; −∞ outside it.
fn ln_band_density(x: f64, band: (f64, f64)) -> f64 {
    let (lo, hi) = (band.0.ln(), band.1.ln());
    if (lo..=hi).contains(&x) {
        -(hi - lo).ln()
    } else {
        f64::NEG_INFINITY
    }
}

fn ln_add_exp(a: f64, b: f64) -> f64 {
    let m = a.max(b);
    if m == f64::NEG_INFINITY {
        m
    } else {
        m + ((a - m).exp() + (b - m).exp()).ln()
    }
}

/// ln p(local moduli | class), integrating the overall modulus over the class's band.
fn ln_evidence(ln_local: &[f64; 4], class: Softness) -> f64 {
    let (lo, hi) = household_band(class);
    let (lo, hi) = (lo.ln(), hi.ln());
    // A finger on a feature does not depend on the overall modulus: once per finger.
    let ln_feature = ln_local.map(|x| {
        let [a, b] = adjacent(class).map(|c| ln_band_density(x, household_band(c)));
        ln_add_exp(a, b) + (0.5 * FEATURE_PROBABILITY).ln()
    });
    let ln_spread = (1.0 - FEATURE_PROBABILITY).ln()
        - (LOCAL_MODULUS_SD * (2.0 * std::f64::consts::PI).sqrt()).ln();
    let mut acc = f64::NEG_INFINITY;
    for k in 0..GRID {
        let g = lo + (hi - lo) * (k as f64 + 0.5) / GRID as f64;
        let ln_lik: f64 = ln_local
            .iter()
            .zip(ln_feature)
            .map(|(&x, feature)| {
                let z = (x - g) / LOCAL_MODULUS_SD;
                ln_add_exp(feature, ln_spread - 0.5 * z * z)
            })
            .sum();
        acc = ln_add_exp(acc, ln_lik);
    }
    acc - (GRID as f64).ln()
}

/// The posterior of each class (in [`Softness::ALL`] order) given the four local moduli, Pa,
/// the classes equally likely beforehand (the dataset draws them in turn).
///
/// Errors on a modulus that is not finite and positive.
///
/// ```
/// use hand_sim::underactuated::ceiling::posterior;
/// // Three fingers on a sponge-like 20 kPa, one on a 200 kPa cap: still a soft object.
/// let p = posterior([20e3, 20e3, 20e3, 200e3]).unwrap();
/// assert!(p[0] > 0.9 && (p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
/// assert!(posterior([20e3, f64::NAN, 20e3, 20e3]).is_err());
/// ```
pub fn posterior(local_moduli_pa: [f64; 4]) -> Result<[f64; 3], SimError> {
    check_moduli(&local_moduli_pa)?;
    let ln_local = local_moduli_pa.map(f64::ln);
    let ln_ev = Softness::ALL.map(|c| ln_evidence(&ln_local, c));
    let total = ln_ev.iter().copied().fold(f64::NEG_INFINITY, ln_add_exp);
    Ok(ln_ev.map(|e| (e - total).exp()))
}

/// The class of largest [`posterior`].
pub fn bayes_class(local_moduli_pa: [f64; 4]) -> Result<Softness, SimError> {
    let p = posterior(local_moduli_pa)?;
    let best = (0..3).fold(0, |b, i| if p[i] > p[b] { i } else { b });
    Ok(Softness::ALL[best])
}

/// How many objects the Bayes rule gets right.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Ceiling {
    /// Household objects counted.
    pub objects: usize,
    /// Of which the Bayes rule classifies correctly.
    pub correct: usize,
}

impl Ceiling {
    /// `correct / objects` (0 for none).
    pub fn accuracy(&self) -> f64 {
        self.correct as f64 / self.objects.max(1) as f64
    }
}

/// The ceiling of the hidden overall class on the household objects of `set` in `specs`
/// (other kinds are skipped: model and regular objects meet one modulus on every finger).
pub fn of_set(specs: &[GraspSpec], set: Set) -> Result<Ceiling, SimError> {
    let mut c = Ceiling::default();
    for s in specs
        .iter()
        .filter(|s| s.set == set && s.kind == "household")
    {
        c.objects += 1;
        if Some(bayes_class(s.object.local_moduli())?) == s.overall {
            c.correct += 1;
        }
    }
    Ok(c)
}

/// The expected ceiling: the Bayes rule on `per_class` fresh household objects of each class,
/// drawn with `seed` by the dataset's own generator.
pub fn expected(seed: u64, per_class: usize) -> Result<Ceiling, SimError> {
    let mut rng = crate::seed::stream(seed, "underactuated/ceiling");
    let mut c = Ceiling::default();
    for i in 0..3 * per_class {
        let class = Softness::ALL[i % 3];
        c.objects += 1;
        if bayes_class(household(&mut rng, class).local_moduli())? == class {
            c.correct += 1;
        }
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::underactuated::dataset::specs;

    #[test]
    fn an_object_whose_fingers_all_meet_its_band_is_its_class() {
        for class in Softness::ALL {
            let (lo, hi) = household_band(class);
            let mid = (lo * hi).sqrt();
            assert_eq!(bayes_class([mid; 4]).unwrap(), class);
            let p = posterior([mid; 4]).unwrap();
            assert!(p[class.index()] > 0.9, "{class:?}: {p:?}");
        }
    }

    #[test]
    fn posterior_is_a_distribution_even_far_outside_every_band() {
        for m in [1e-300, 1e-3, 50e3, 5e6, 1e300] {
            let p = posterior([m, 2.0 * m, m, m]).unwrap();
            assert!(p.iter().all(|x| x.is_finite() && *x >= 0.0), "{m}: {p:?}");
            assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{m}: {p:?}");
        }
        // Below every band the softest class wins, above every band the hardest.
        assert_eq!(bayes_class([1e-3; 4]).unwrap(), Softness::Soft);
        assert_eq!(bayes_class([1e300; 4]).unwrap(), Softness::Hard);
        for bad in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            assert!(posterior([bad, 1e5, 1e5, 1e5]).is_err());
        }
    }

    /// The Bayes rule is the best rule in expectation, so on the same fresh objects it must
    /// do at least as well as a plausible rival: the class of the four moduli's geometric
    /// mean (nearest band in ln).
    #[test]
    fn the_bayes_rule_beats_the_geometric_mean_rule() {
        let mut rng = crate::seed::stream(7, "ceiling-test");
        let (mut bayes, mut mean) = (0, 0);
        let n = 600;
        for i in 0..n {
            let class = Softness::ALL[i % 3];
            let local = household(&mut rng, class).local_moduli();
            bayes += usize::from(bayes_class(local).unwrap() == class);
            let g = local.iter().map(|m| m.ln()).sum::<f64>() / 4.0;
            let dist = |c: Softness| {
                let (lo, hi) = household_band(c);
                (lo.ln() - g).max(g - hi.ln()).max(0.0)
            };
            let nearest = Softness::ALL
                .into_iter()
                .min_by(|a, b| dist(*a).total_cmp(&dist(*b)))
                .unwrap();
            mean += usize::from(nearest == class);
        }
        assert!(
            bayes > mean,
            "Bayes {bayes} vs geometric mean {mean} of {n}"
        );
    }

    #[test]
    fn the_ceiling_counts_only_household_objects() {
        let s = specs(1).unwrap();
        assert_eq!(of_set(&s, Set::TestIrregular).unwrap().objects, 30);
        assert_eq!(of_set(&s, Set::TestIrregular1000).unwrap().objects, 1000);
        assert_eq!(of_set(&s, Set::Train).unwrap().objects, 18);
        assert_eq!(of_set(&s, Set::TestRegular).unwrap().objects, 0);
    }
}
