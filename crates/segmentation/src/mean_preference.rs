//! The preference extension of a clustered subset
//! (`subset_extension = "preference"` and the variants that start from
//! it): a left-out match joins the class, a cluster or the subset's
//! outliers, whose mean preference vector (Eq. 38) is nearest to its own
//! in Tanimoto distance (Eq. 39), as T-Linkage would join them.

use crate::ClusteredSubset;
use clustering::preference;
use geometry::{Correspondences, SampsonModels};
use nalgebra::Matrix3;
use rayon::prelude::*;

/// The preference vector (Eq. 38) of match `i` against `models`, into `out`.
fn preference_row(
    models: &SampsonModels,
    points: &Correspondences,
    i: usize,
    tau: f64,
    out: &mut [f64],
) {
    models.distances_squared(points.point1(i), points.point2(i), out);
    out.iter_mut().for_each(|v| *v = preference(*v, tau));
}

/// The mean preference vectors of the subset's classes (each cluster,
/// then the outliers), hypothesis-major: entry `j · classes + c` is class
/// `c`'s mean preference for hypothesis `j`.
struct MeanPreferences {
    classes: usize,
    means: Vec<f64>,
    /// `|μ_c|²` of each class.
    norms: Vec<f64>,
}

/// Matches of the subset summed per task: fixed chunks, added in order, so
/// the means do not depend on the thread count.
const SUM_CHUNK: usize = 64;

impl MeanPreferences {
    /// The means of the subset's clusters and of its outliers (zero when
    /// there are none).
    fn new(
        points: &Correspondences,
        subset: ClusteredSubset,
        models: &SampsonModels,
        tau: f64,
    ) -> Self {
        let (m, classes) = (models.len(), subset.clusters + 1);
        let class = |l: i32| {
            usize::try_from(l)
                .ok()
                .filter(|&c| c < subset.clusters)
                .unwrap_or(subset.clusters)
        };
        let partial_sums: Vec<Vec<f64>> = subset
            .indices
            .par_chunks(SUM_CHUNK)
            .zip(subset.labels.par_chunks(SUM_CHUNK))
            .map(|(indices, labels)| {
                let (mut sums, mut row) = (vec![0.0; m * classes], vec![0.0; m]);
                for (&i, &label) in indices.iter().zip(labels) {
                    preference_row(models, points, i, tau, &mut row);
                    let c = class(label);
                    for (j, &v) in row.iter().enumerate().filter(|(_, &v)| v > 0.0) {
                        sums[j * classes + c] += v;
                    }
                }
                sums
            })
            .collect();
        let mut means = vec![0.0; m * classes];
        for sums in &partial_sums {
            means.iter_mut().zip(sums).for_each(|(a, b)| *a += b);
        }
        let mut counts = vec![0usize; classes];
        subset.labels.iter().for_each(|&l| counts[class(l)] += 1);
        let mut norms = vec![0.0; classes];
        for (j, mean) in means.iter_mut().enumerate() {
            let c = j % classes;
            *mean /= counts[c].max(1) as f64;
            norms[c] += *mean * *mean;
        }
        Self {
            classes,
            means,
            norms,
        }
    }

    /// The class of largest Tanimoto similarity to the preference vector
    /// `row` (the first on ties), None when it is 0 for every class.
    fn nearest(&self, row: &[f64], dots: &mut [f64]) -> Option<usize> {
        dots.fill(0.0);
        let mut p2 = 0.0;
        for (j, &v) in row.iter().enumerate().filter(|(_, &v)| v > 0.0) {
            p2 += v * v;
            let means = &self.means[j * self.classes..(j + 1) * self.classes];
            dots.iter_mut().zip(means).for_each(|(d, mu)| *d += v * mu);
        }
        let mut best = None;
        let mut best_similarity = 0.0;
        for (c, (&dot, &m2)) in dots.iter().zip(&self.norms).enumerate() {
            let similarity = if dot > 0.0 {
                dot / (p2 + m2 - dot)
            } else {
                0.0
            };
            if similarity > best_similarity {
                (best, best_similarity) = (Some(c), similarity);
            }
        }
        best
    }
}

/// [`crate::SubsetExtension::Preference`]: the label of each match outside the
/// subset (−1 inside it), in parallel; independent of the thread count.
pub(crate) fn nearest_mean_preference(
    points: &Correspondences,
    subset: ClusteredSubset,
    models: &[Matrix3<f64>],
    tau: f64,
) -> Vec<i32> {
    let models = SampsonModels::new(models);
    let means = MeanPreferences::new(points, subset, &models, tau);
    let in_subset = subset.membership(points.len());
    (0..points.len())
        .into_par_iter()
        .map_init(
            || (vec![0.0; models.len()], vec![0.0; means.classes]),
            |(row, dots), i| {
                if in_subset[i] {
                    return -1;
                }
                preference_row(&models, points, i, tau, row);
                match means.nearest(row, dots) {
                    Some(c) if c < subset.clusters => c as i32,
                    _ => -1,
                }
            },
        )
        .collect()
}
