//! A sanity check of a dataset's difficulty: a nearest-centroid classifier on standardised
//! features. Not the paper's network (`tactile-nets` has that); only a floor it should clear.

use hand_traits::Softness;

/// A labelled feature vector.
pub type Sample<const N: usize> = ([f64; N], Softness);

/// Class centroids of standardised features, fitted on a training set.
#[derive(Debug, Clone, PartialEq)]
pub struct NearestCentroid<const N: usize> {
    mean: [f64; N],
    scale: [f64; N],
    centroids: Vec<([f64; N], Softness)>,
}

impl<const N: usize> NearestCentroid<N> {
    /// Fits on `train`: z-scores with the training mean and spread, one centroid per class seen.
    ///
    /// ```
    /// use hand_sim::underactuated::separability::NearestCentroid;
    /// use hand_traits::Softness::{Hard, Soft};
    /// let nc = NearestCentroid::fit(&[([0.0], Soft), ([1.0], Soft), ([9.0], Hard), ([10.0], Hard)]);
    /// assert_eq!(nc.classify(&[2.0]), Some(Soft));
    /// assert_eq!(nc.accuracy(&[([8.0], Hard), ([3.0], Hard)]), 0.5);
    /// ```
    pub fn fit(train: &[Sample<N>]) -> Self {
        let n = train.len().max(1) as f64;
        let mean: [f64; N] = std::array::from_fn(|j| train.iter().map(|s| s.0[j]).sum::<f64>() / n);
        let scale = std::array::from_fn(|j| {
            let var = train
                .iter()
                .map(|s| (s.0[j] - mean[j]).powi(2))
                .sum::<f64>()
                / n;
            if var > 0.0 { var.sqrt() } else { 1.0 }
        });
        let mut nc = NearestCentroid {
            mean,
            scale,
            centroids: Vec::new(),
        };
        for class in Softness::ALL {
            let members: Vec<[f64; N]> = train
                .iter()
                .filter(|s| s.1 == class)
                .map(|s| nc.standardise(&s.0))
                .collect();
            if !members.is_empty() {
                let m = members.len() as f64;
                let c = std::array::from_fn(|j| members.iter().map(|x| x[j]).sum::<f64>() / m);
                nc.centroids.push((c, class));
            }
        }
        nc
    }

    fn standardise(&self, x: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|j| (x[j] - self.mean[j]) / self.scale[j])
    }

    /// The class of the nearest centroid; `None` if it was fitted on nothing.
    pub fn classify(&self, x: &[f64; N]) -> Option<Softness> {
        let z = self.standardise(x);
        let dist = |c: &[f64; N]| c.iter().zip(&z).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
        self.centroids
            .iter()
            .min_by(|a, b| dist(&a.0).total_cmp(&dist(&b.0)))
            .map(|c| c.1)
    }

    /// Fraction of `samples` classified correctly (0 for none).
    pub fn accuracy(&self, samples: &[Sample<N>]) -> f64 {
        let right = samples
            .iter()
            .filter(|s| self.classify(&s.0) == Some(s.1))
            .count();
        right as f64 / samples.len().max(1) as f64
    }
}
