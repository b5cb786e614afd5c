//! The FROB score between predicted and ground-truth fundamental matrices.

use geometry::frob_distance;
use nalgebra::Matrix3;

use crate::labels::optimal_assignment;

/// FROB score (Eq. 45): the mean Frobenius distance between matched
/// fundamental matrices.
///
/// Each cost is `min(‖Fa/‖Fa‖ − Fb/‖Fb‖‖, ‖Fa/‖Fa‖ + Fb/‖Fb‖‖)`
/// ([`geometry::frob_distance`]); predicted and ground-truth matrices are
/// assigned one-to-one by the Hungarian algorithm minimising the total cost
/// (rectangular: `min(P, G)` pairs), and the score is the mean of the
/// assigned costs. The caller fits the matrices (8-point on each predicted
/// cluster and on each ground-truth motion with at least 8 points).
///
/// Returns `None` when FROB is undefined: either side empty, or a matrix
/// with zero norm or non-finite entries (its distance is not a number).
///
/// ```
/// use metrics::frob_score;
/// use nalgebra::Matrix3;
///
/// let a = Matrix3::new(0.0, -1.0, 0.5, 1.0, 0.0, -0.2, -0.5, 0.2, 0.0);
/// let b = Matrix3::new(0.3, 0.0, 1.0, 0.0, 0.0, 2.0, -1.0, -2.0, 0.0);
/// // Scale and sign are irrelevant, the order of the matrices too.
/// let score = frob_score(&[-2.0 * b, 5.0 * a], &[a, b]).unwrap();
/// assert!(score < 1e-12);
/// assert_eq!(frob_score(&[], &[a]), None);
/// ```
pub fn frob_score(predicted: &[Matrix3<f64>], ground_truth: &[Matrix3<f64>]) -> Option<f64> {
    if predicted.is_empty() || ground_truth.is_empty() {
        return None;
    }
    let costs: Vec<f64> = predicted
        .iter()
        .flat_map(|fa| ground_truth.iter().map(move |fb| frob_distance(fa, fb)))
        .collect();
    if costs.iter().any(|c| !c.is_finite()) {
        return None;
    }
    let pairs = optimal_assignment(predicted.len(), ground_truth.len(), &costs, false);
    let total: f64 = pairs
        .iter()
        .map(|&(r, c)| costs[r * ground_truth.len() + c])
        .sum();
    Some(total / pairs.len() as f64)
}
