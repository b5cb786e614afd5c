//! Clustering a subset of a large scene (`cluster_subset = n`): steps 1–9
//! run on `n` matches drawn at random, and every other match then joins
//! the cluster it is nearest to ([`crate::SubsetExtension`]). T-Linkage's
//! cost grows with the square of the number of points it clusters; a
//! match left out costs one preference vector (its Sampson distances to
//! the kept hypotheses) and a comparison with each cluster.
//!
//! The same idea (cluster a sample, then classify the rest) is how
//! agglomerative clustering is scaled in CURE (Guha, Rastogi & Shim,
//! SIGMOD 1998). The classifier is T-Linkage's own measure, the Tanimoto
//! distance between preference vectors (Eq. 39), optionally checked with
//! the geometric test of Progressive-X's final assignment (Barath & Matas,
//! ICCV 2019).

use crate::assignment::drop_small_and_renumber;
use crate::mean_preference::nearest_mean_preference;
use crate::merge::cluster_hypotheses;
use crate::{hypothesis_rng, InlierBits, SubsetExtension};
use geometry::{sampson_distances_squared, Correspondences};
use nalgebra::Matrix3;

/// The matches steps 1–9 run on when `cluster_subset = size`: all of
/// `0..n` when `size` is 0 or at least `n`, else `size` distinct indices
/// drawn uniformly, increasing ([`crate::Params::clustered_matches`] of
/// them). They come from stream 2⁶⁴ − 1 of
/// [`hypothesis_rng`] (no hypothesis draws from it), so they depend on the
/// seed and `n` only.
///
/// ```
/// let s = segmentation::subset_indices(12345, 5000, 1000);
/// assert_eq!(s.len(), 1000);
/// assert!(s.windows(2).all(|w| w[0] < w[1]) && s[999] < 5000);
/// assert_eq!(segmentation::subset_indices(12345, 800, 1000), (0..800).collect::<Vec<_>>());
/// ```
pub fn subset_indices(seed: u64, n: usize, size: usize) -> Vec<usize> {
    if size == 0 || size >= n {
        return (0..n).collect();
    }
    sorted_draw(seed, usize::MAX, n, size)
}

/// `size` distinct indices of `0..n` (`size ≤ n`) drawn uniformly from
/// stream `stream` of [`hypothesis_rng`], increasing.
fn sorted_draw(seed: u64, stream: usize, n: usize, size: usize) -> Vec<usize> {
    let mut rng = hypothesis_rng(seed, stream);
    let mut indices = rand::seq::index::sample(&mut rng, n, size).into_vec();
    indices.sort_unstable();
    indices
}

/// The clustered subset and its labels (clusters `0..clusters`, −1
/// outliers): `labels[k]` is the label of match `indices[k]`.
#[derive(Debug, Clone, Copy)]
pub struct ClusteredSubset<'a> {
    /// Indices of the clustered matches among all of them, increasing.
    pub indices: &'a [usize],
    /// Their labels after steps 8–9 and the final assignment.
    pub labels: &'a [i32],
    /// The number of clusters.
    pub clusters: usize,
}

impl ClusteredSubset<'_> {
    /// Whether each of `n` matches is in the subset (its indices `< n`).
    pub(crate) fn membership(&self, n: usize) -> Vec<bool> {
        let mut in_subset = vec![false; n];
        self.indices.iter().for_each(|&i| in_subset[i] = true);
        in_subset
    }
}

/// The labels of all `points` (principal-point centred) from those of the
/// clustered `subset`, given the `models` that entered the preferences,
/// their `inliers` among the subset's matches (`r ≤ tau`, in the order of
/// `models`, as step 7 computes them for the merge; `Preference` does not
/// read them) and `tau = thr_px²`. A match of the subset keeps its label;
/// any other match joins a cluster by `how`:
///
/// * [`SubsetExtension::Preference`]: its preference vector `p` (Eq. 38)
///   against the mean preference vector `μ` of each cluster's matches and
///   of the subset's outliers. It joins the class of largest Tanimoto
///   similarity `p·μ / (|p|² + |μ|² − p·μ)` (one minus Eq. 39's distance;
///   the lower label on ties, the outliers last), and is an outlier when
///   that class is the outliers' or it prefers no model;
/// * [`SubsetExtension::PreferenceExplained`]: as `Preference`, and the
///   match is an outlier unless the joined cluster's model, the hypothesis
///   with the most inliers among its matches (the model of
///   [`crate::merge_explained`]), explains it (squared Sampson distance,
///   Eq. 23, `≤ tau`).
///
/// Labels are then renumbered 0, 1, … by first appearance, as the
/// clustering numbers them.
pub fn extend_labels(
    points: &Correspondences,
    subset: ClusteredSubset,
    models: &[Matrix3<f64>],
    inliers: &InlierBits,
    tau: f64,
    how: SubsetExtension,
) -> Vec<i32> {
    let mut labels = nearest_mean_preference(points, subset, models, tau);
    if how == SubsetExtension::PreferenceExplained {
        let cluster_models = cluster_hypotheses(subset.labels, subset.clusters, inliers, models);
        labels = unexplained_to_outliers(points, labels, &cluster_models, tau);
    }
    for (&i, &label) in subset.indices.iter().zip(subset.labels) {
        labels[i] = label;
    }
    drop_small_and_renumber(&labels, subset.clusters, 0)
}

/// `labels` with every match whose cluster's model does not explain it
/// (squared Sampson distance, Eq. 23, `> tau`, or no model) made an
/// outlier.
fn unexplained_to_outliers(
    points: &Correspondences,
    mut labels: Vec<i32>,
    cluster_models: &[Option<Matrix3<f64>>],
    tau: f64,
) -> Vec<i32> {
    let mut residuals = vec![0.0; points.len()];
    for (c, model) in cluster_models.iter().enumerate() {
        match model {
            Some(f) => sampson_distances_squared(f, points, &mut residuals),
            None => residuals.fill(f64::INFINITY),
        }
        for (label, &r) in labels.iter_mut().zip(&residuals) {
            if *label == c as i32 && r > tau {
                *label = -1;
            }
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;
    use clustering::preference;

    #[test]
    fn subsets_are_distinct_sorted_and_seeded() {
        let a = subset_indices(7, 3000, 500);
        assert_eq!(a, subset_indices(7, 3000, 500));
        assert_ne!(a, subset_indices(8, 3000, 500));
        assert!(a.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(subset_indices(7, 300, 0), (0..300).collect::<Vec<_>>());
    }

    /// `[d]×`: the F of the pure image translation `x2 = x1 + d`.
    fn translation(d: [f64; 2]) -> Matrix3<f64> {
        Matrix3::new(0.0, 0.0, d[1], 0.0, 0.0, -d[0], -d[1], d[0], 0.0)
    }

    /// The inlier sets (`r ≤ tau`) of `models` among the subset's matches,
    /// as step 7 gives them to [`extend_labels`].
    fn inliers(
        points: &Correspondences,
        indices: &[usize],
        models: &[Matrix3<f64>],
        tau: f64,
    ) -> InlierBits {
        let sub = points.subset(indices).unwrap();
        let mut bits = InlierBits::new(sub.len());
        let mut residuals = vec![0.0; sub.len()];
        for f in models {
            sampson_distances_squared(f, &sub, &mut residuals);
            bits.push(&residuals, tau);
        }
        bits
    }

    /// `n` matches spread over a 100 × 100 square, match `i` moved by
    /// `shift(i)`.
    fn shifted_matches(n: usize, shift: impl Fn(usize) -> [f64; 2]) -> Correspondences {
        let p1: Vec<[f64; 2]> = (0..n)
            .map(|i| [(i * 37 % 101) as f64 - 50.0, (i * 53 % 97) as f64 - 48.0])
            .collect();
        let p2: Vec<[f64; 2]> = (0..n)
            .map(|i| [p1[i][0] + shift(i)[0], p1[i][1] + shift(i)[1]])
            .collect();
        Correspondences::new(&p1, &p2).unwrap()
    }

    /// Two motions, `x2 = x1 + (1, 0)` on matches 0..20 and `x2 = x1 +
    /// (0, 1)` on 20..40, and two gross outliers 40, 41 that move by
    /// (3, 5).
    fn two_translations() -> Correspondences {
        shifted_matches(42, |i| match i {
            0..20 => [1.0, 0.0],
            20..40 => [0.0, 1.0],
            _ => [3.0, 5.0],
        })
    }

    #[test]
    fn the_left_out_matches_join_the_cluster_that_explains_them() {
        let points = two_translations();
        // The subset: every fourth match and outlier 40, labelled by
        // motion; match 0 an outlier of the clustering.
        let indices: Vec<usize> = (0..40).step_by(4).chain([40]).collect();
        let labels: Vec<i32> = indices
            .iter()
            .map(|&i| match i {
                1..20 => 0,
                20..40 => 1,
                _ => -1,
            })
            .collect();
        let subset = ClusteredSubset {
            indices: &indices,
            labels: &labels,
            clusters: 2,
        };
        let expected: Vec<i32> = (0..42)
            .map(|i| match i {
                1..20 => 0,
                20..40 => 1,
                _ => -1,
            })
            .collect();
        // A model that explains nothing, the two motions' models and the
        // outliers' own: outlier 41 prefers what the subset's outliers
        // prefer.
        let noise = Matrix3::new(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, -1.0, -1.0, 0.0);
        let models = [
            noise,
            translation([0.0, 1.0]),
            translation([1.0, 0.0]),
            translation([3.0, 5.0]),
        ];
        for how in BOTH {
            let bits = inliers(&points, &indices, &models, 1e-9);
            let out = extend_labels(&points, subset, &models, &bits, 1e-9, how);
            assert_eq!(out, expected, "{how:?}");
        }
        // Without the second motion's model its left-out matches prefer
        // nothing: outliers.
        for how in BOTH {
            let bits = inliers(&points, &indices, &models[2..], 1e-9);
            let out = extend_labels(&points, subset, &models[2..], &bits, 1e-9, how);
            for (i, &l) in out.iter().enumerate() {
                let left_out_of_b = (20..40).contains(&i) && !indices.contains(&i);
                let want = if left_out_of_b { -1 } else { expected[i] };
                assert_eq!(l, want, "{how:?}, match {i}");
            }
        }
    }

    #[test]
    fn a_match_its_cluster_prefers_but_does_not_explain_is_vetoed() {
        // Motions x2 = x1 + (10, 0) (matches 0..20) and x2 = x1 + (0, 10)
        // (20..40); match 40 moves by (10, 2): 2 px² (squared Sampson) off
        // the first motion's model, within its preference cutoff 5 tau but
        // above tau = 1, and 50 px² off the second's.
        let points = shifted_matches(41, |i| match i {
            0..20 => [10.0, 0.0],
            20..40 => [0.0, 10.0],
            _ => [10.0, 2.0],
        });
        let indices: Vec<usize> = (0..40).step_by(4).collect();
        let labels: Vec<i32> = indices.iter().map(|&i| i32::from(i >= 20)).collect();
        let subset = ClusteredSubset {
            indices: &indices,
            labels: &labels,
            clusters: 2,
        };
        let models = [translation([10.0, 0.0]), translation([0.0, 10.0])];
        let bits = inliers(&points, &indices, &models, 1.0);
        let label_of_40 = |how| extend_labels(&points, subset, &models, &bits, 1.0, how)[40];
        assert_eq!(label_of_40(SubsetExtension::Preference), 0);
        assert_eq!(label_of_40(SubsetExtension::PreferenceExplained), -1);
    }

    /// The homography of [`one_motion`].
    fn motion_homography() -> Matrix3<f64> {
        Matrix3::new(1.02, 0.01, 3.0, -0.015, 0.99, -2.0, 1e-4, -5e-5, 1.0)
    }

    /// `n` noise-free matches of one rigid motion, `F = [e]× H` with
    /// epipole `e = (400, 150)` and `H` [`motion_homography`]: match `i`
    /// has parallax `λᵢ` along its epipolar line, `x2 = Hx1 + λᵢ (Hx1 −
    /// e)`, `|λᵢ| ≤ 0.1`.
    fn one_motion(n: usize) -> Correspondences {
        let (h, e) = (
            motion_homography(),
            nalgebra::Vector3::new(400.0, 150.0, 1.0),
        );
        let (mut p1, mut p2) = (Vec::new(), Vec::new());
        for i in 0..n {
            let x1 = [(i * 37 % 101) as f64 - 50.0, (i * 53 % 97) as f64 - 48.0];
            let hx = h * nalgebra::Vector3::new(x1[0], x1[1], 1.0);
            let hx = [hx.x / hx.z, hx.y / hx.z];
            let lambda = ((i * 29 % 23) as f64 / 22.0 - 0.5) * 0.2;
            p1.push(x1);
            p2.push([
                hx[0] + lambda * (hx[0] - e.x),
                hx[1] + lambda * (hx[1] - e.y),
            ]);
        }
        Correspondences::new(&p1, &p2).unwrap()
    }

    #[test]
    fn preference_joins_what_the_model_does_not_explain() {
        // The sampled hypothesis has its epipole 20 px off: it explains
        // the matches of small parallax only, and the others still prefer
        // it.
        let points = one_motion(90);
        let sampled =
            nalgebra::Vector3::new(400.0, 170.0, 1.0).cross_matrix() * motion_homography();
        let indices: Vec<usize> = (0..90).step_by(3).collect();
        let labels = vec![0; indices.len()];
        let subset = ClusteredSubset {
            indices: &indices,
            labels: &labels,
            clusters: 1,
        };
        let (models, tau) = ([sampled], 0.01);
        let mut r = vec![0.0; 90];
        sampson_distances_squared(&sampled, &points, &mut r);
        let missed = |i: usize| i % 3 != 0 && r[i] > tau;
        assert!((0..90).filter(|&i| missed(i)).count() >= 20);
        let bits = inliers(&points, &indices, &models, tau);
        let extend = |how| extend_labels(&points, subset, &models, &bits, tau, how);
        let explained = extend(SubsetExtension::PreferenceExplained);
        assert!((0..90).all(|i| (explained[i] == -1) == missed(i)));
        // Without the check a match joins when it prefers the sampled
        // model at all (within 5 tau), explained or not.
        let out = extend(SubsetExtension::Preference);
        let preferring = |i: usize| i % 3 == 0 || preference(r[i], tau) > 0.0;
        assert!((0..90).all(|i| (out[i] == 0) == preferring(i)), "{out:?}");
        assert!((0..90).filter(|&i| missed(i) && out[i] == 0).count() > 0);
    }

    const BOTH: [SubsetExtension; 2] = [
        SubsetExtension::Preference,
        SubsetExtension::PreferenceExplained,
    ];
}
