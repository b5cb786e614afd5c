//! The semi-calibrated model of a group, the second model the NFA scores
//! besides the group's F: one camera with one focal length took both
//! images, so a rigid motion's F is `K⁻ᵀ E K⁻¹` (Hartley & Zisserman
//! Eq. 9.12) with E of 5 degrees of freedom once the focal is fixed at the
//! prior. A fit brings 5 matches onto their epipolar lines whatever they
//! are, not 7, so a small rigid motion needs fewer matches beyond the fit
//! to be significant.
//!
//! The model is the best of [`SEMICALIBRATED_SAMPLES`] five-point samples
//! of the group's matches (Nistér 2004, the solver of the hypotheses; RANSAC's
//! consensus, ties broken by MSAC's truncated cost, Torr & Zisserman 2000),
//! and the NFA counts every candidate tried as a test. The focal prior need
//! not be right: five-point hypotheses at 0.5–4× the true focal cost
//! little (docs/method.md, the paragraph on the focal prior after "The
//! default"), and this model at 0.5× or 2× max(W, H) moves no validation
//! family by 0.2 points (results/notes/selection.md).

use crate::minimal::candidates;
use crate::{hypothesis_rng, splitmix64};
use geometry::{sampson_distances_squared, Correspondences};
use nalgebra::Matrix3;
use rand::seq::index::sample;

/// Five-point samples drawn per group (validation, results/notes/selection.md).
pub const SEMICALIBRATED_SAMPLES: usize = 32;

/// The matches a five-point fit brings onto their epipolar lines whatever
/// they are: the NFA's binomial counts the other `k − 5` among `n − 5`.
pub const SEMICALIBRATED_FITTED: usize = 5;

/// The best five-point F of a group and how many candidates it was chosen
/// among.
#[derive(Debug, Clone, PartialEq)]
pub struct SemicalibratedFit {
    /// `K⁻ᵀ E K⁻¹` in the points' frame (principal-point-centred, px).
    pub f: Matrix3<f64>,
    /// The candidate Fs tried (up to 10 per sample).
    pub candidates: usize,
}

/// The F among the five-point candidates of [`SEMICALIBRATED_SAMPLES`]
/// samples of `own` (indices into `points`, at least 5) at `focal_px` that
/// puts the most of `own` within `thr_px` (Sampson distance), ties broken
/// by the smaller truncated cost `Σ min(d², thr_px²)` (the hypotheses'
/// choice among a sample's roots, `minimal.rs`, keeps the first on ties
/// instead; this choice was measured as it is). The samples are
/// drawn from a stream keyed by the group's indices, so the fit is a pure
/// function of its input. None when no sample gives a candidate.
pub fn semicalibrated_fit(
    points: &Correspondences,
    own: &[usize],
    focal_px: f64,
    thr_px: f64,
) -> Option<SemicalibratedFit> {
    if own.len() < 5 {
        return None;
    }
    let group = points.subset(own).ok()?;
    let mut rng = hypothesis_rng(group_key(own), 0);
    let thr2 = thr_px * thr_px;
    let mut d2 = vec![0.0; group.len()];
    let mut best: Option<(Score, Matrix3<f64>)> = None;
    let mut tried = 0;
    for _ in 0..SEMICALIBRATED_SAMPLES {
        let pick = sample(&mut rng, group.len(), 5).into_vec();
        let Ok(minimal) = group.subset(&pick) else {
            continue;
        };
        for f in candidates(&minimal, focal_px) {
            tried += 1;
            sampson_distances_squared(&f, &group, &mut d2);
            let score = Score::of(&d2, thr2);
            if best.as_ref().map_or(true, |(b, _)| score.beats(b)) {
                best = Some((score, f));
            }
        }
    }
    best.map(|(_, f)| SemicalibratedFit {
        f,
        candidates: tried,
    })
}

/// A candidate's consensus and truncated cost over the group.
struct Score {
    inliers: usize,
    cost: f64,
}

impl Score {
    fn of(d2: &[f64], thr2: f64) -> Self {
        Self {
            inliers: d2.iter().filter(|&&d| d <= thr2).count(),
            cost: d2.iter().map(|&d| d.min(thr2)).sum(),
        }
    }

    fn beats(&self, other: &Self) -> bool {
        (self.inliers, -self.cost) > (other.inliers, -other.cost)
    }
}

/// The sampling key of a group: SplitMix64 folded over its indices.
fn group_key(own: &[usize]) -> u64 {
    own.iter()
        .fold(own.len() as u64, |k, &m| splitmix64(k ^ m as u64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Vector3};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `n` points of a rigid scene seen by `K = diag(focal, focal, 1)`
    /// before and after a motion (R, t), centred pixel coordinates.
    fn rigid_scene(n: usize, focal: f64, seed: u64) -> Correspondences {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let r = Rotation3::from_euler_angles(0.05, -0.08, 0.03);
        let t = Vector3::new(0.4, -0.1, 0.05);
        let project = |p: Vector3<f64>| [focal * p.x / p.z, focal * p.y / p.z];
        let (p1, p2): (Vec<_>, Vec<_>) = (0..n)
            .map(|_| {
                let p = Vector3::new(
                    rng.gen_range(-2.0..2.0),
                    rng.gen_range(-1.5..1.5),
                    rng.gen_range(4.0..8.0),
                );
                (project(p), project(r * p + t))
            })
            .unzip();
        Correspondences::new(&p1, &p2).unwrap()
    }

    #[test]
    fn a_noiseless_rigid_group_is_fitted_exactly_at_the_true_focal() {
        let points = rigid_scene(30, 800.0, 1);
        let own: Vec<usize> = (0..30).collect();
        let fit = semicalibrated_fit(&points, &own, 800.0, 1.0).unwrap();
        let mut d2 = vec![0.0; 30];
        sampson_distances_squared(&fit.f, &points, &mut d2);
        assert!(d2.iter().all(|&d| d < 1e-12), "{d2:?}");
        assert!(fit.candidates >= SEMICALIBRATED_SAMPLES);
    }

    #[test]
    fn the_fit_is_a_function_of_its_input_and_too_few_matches_give_none() {
        let points = rigid_scene(30, 800.0, 2);
        let own: Vec<usize> = (3..25).collect();
        let a = semicalibrated_fit(&points, &own, 1000.0, 1.0);
        assert!(a.is_some());
        assert_eq!(a, semicalibrated_fit(&points, &own, 1000.0, 1.0));
        assert_eq!(semicalibrated_fit(&points, &own[..4], 1000.0, 1.0), None);
    }
}
