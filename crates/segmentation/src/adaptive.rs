//! Adaptive M ([`crate::Params::adaptive_batch`]): hypotheses are drawn in
//! batches until a batch no longer finds a better model for the points.
//!
//! The *support* of a hypothesis is the number of matches within `thr_px`
//! of it (squared Sampson distance `≤ thr_px²`, the inlier test of Eq. 38's
//! preferences); the *best support* of a point is the largest support of a
//! hypothesis it is an inlier of. A point *gains* in a batch when the batch
//! holds a hypothesis that has it as an inlier and whose support exceeds the
//! point's best support so far by the factor [`SUPPORT_GAIN`] (any support
//! counts when it had none). A batch after which fewer than
//! `adaptive_tolerance · N` points gained ends the sampling: the structures
//! of the scene each have a well-supported hypothesis and new samples only
//! repeat them. The rule is checked from the second batch on.

use geometry::{sampson_distances_squared, Correspondences};
use nalgebra::Matrix3;

/// The factor by which a hypothesis's support must exceed a point's best
/// support for the point to gain (10 %): small changes of the support of
/// one structure's hypotheses are not new structure.
pub const SUPPORT_GAIN: f64 = 1.1;

/// The best support of every point over the hypotheses seen so far.
///
/// ```
/// use geometry::Correspondences;
/// use nalgebra::Matrix3;
/// use segmentation::SupportTracker;
/// // Pure horizontal translation: F = [t]x with t = (1, 0, 0) has every
/// // match with equal y as an inlier.
/// let p1 = [[0.0, 0.0], [5.0, 1.0], [9.0, 3.0], [2.0, 7.0]];
/// let p2 = [[3.0, 0.0], [8.0, 1.0], [1.0, 50.0], [4.0, 7.0]];
/// let points = Correspondences::new(&p1, &p2).unwrap();
/// let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
/// let mut tracker = SupportTracker::new(points.len(), 2.5);
/// assert_eq!(tracker.add_batch(&points, &[Some(f)]), 3); // three inliers gain
/// assert_eq!(tracker.add_batch(&points, &[Some(f), None]), 0); // nothing new
/// assert_eq!(tracker.best_support(), &[3, 3, 0, 3]);
/// ```
#[derive(Debug, Clone)]
pub struct SupportTracker {
    thr2: f64,
    best: Vec<u32>,
    batch_best: Vec<u32>,
    residuals: Vec<f64>,
}

impl SupportTracker {
    /// A tracker for `n` points and the inlier threshold `thr_px`.
    pub fn new(n: usize, thr_px: f64) -> Self {
        Self {
            thr2: thr_px * thr_px,
            best: vec![0; n],
            batch_best: vec![0; n],
            residuals: vec![0.0; n],
        }
    }

    /// The best support of each point so far.
    pub fn best_support(&self) -> &[u32] {
        &self.best
    }

    /// Adds one batch of models (None: a failed hypothesis, skipped) and
    /// returns the number of points that gained (see the module docs).
    pub fn add_batch(
        &mut self,
        points: &Correspondences,
        models: &[Option<Matrix3<f64>>],
    ) -> usize {
        self.batch_best.fill(0);
        for f in models.iter().flatten() {
            sampson_distances_squared(f, points, &mut self.residuals);
            let thr2 = self.thr2;
            let support = self.residuals.iter().filter(|&&r| r <= thr2).count() as u32;
            for (best, &r) in self.batch_best.iter_mut().zip(&self.residuals) {
                if r <= thr2 {
                    *best = (*best).max(support);
                }
            }
        }
        let mut gained = 0;
        for (best, &new) in self.best.iter_mut().zip(&self.batch_best) {
            if new > 0 && f64::from(new) > SUPPORT_GAIN * f64::from(*best) {
                gained += 1;
            }
            *best = (*best).max(new);
        }
        gained
    }
}

/// Whether the sampling stops after batch `batch` (0-based) in which
/// `gained` of `n` points gained: from the second batch on, when fewer
/// than `tolerance · n` did.
pub(crate) fn stop_after(batch: usize, gained: usize, n: usize, tolerance: f64) -> bool {
    batch >= 1 && (gained as f64) < tolerance * n as f64
}
