//! Pieces shared by the minimal solvers: the sample-size check, the
//! epipolar design row and the null space of a minimal epipolar system.

use crate::linalg::jacobi_svd;
use crate::{GeometryError, RANK_TOLERANCE};
use nalgebra::Matrix3;

/// [`GeometryError::SampleSize`] unless `got == needed`.
pub(crate) fn check_sample_size(got: usize, needed: usize) -> Result<(), GeometryError> {
    if got == needed {
        Ok(())
    } else {
        Err(GeometryError::SampleSize { got, needed })
    }
}

/// The design row `q2 ⊗ q1`, so that `row · vec_row(M) = q2ᵀ M q1`.
pub(crate) fn epipolar_row(q1: [f64; 3], q2: [f64; 3]) -> [f64; 9] {
    let mut row = [0.0; 9];
    for (i, a) in q2.iter().enumerate() {
        for (j, b) in q1.iter().enumerate() {
            row[3 * i + j] = a * b;
        }
    }
    row
}

/// The row-major vector `m` as a matrix.
pub(crate) fn matrix_from_row_major(m: &[f64; 9]) -> Matrix3<f64> {
    Matrix3::from_row_slice(m)
}

/// An orthonormal basis of the `K`-dimensional null space of the
/// `(9 − K) × 9` system `rows` (the right singular vectors of its `K`
/// smallest singular values, ascending, from a one-sided Jacobi SVD of the
/// system padded with zero rows). [`GeometryError::Degenerate`] when the
/// null space is larger than `K`: the smallest non-zero singular value is
/// below [`RANK_TOLERANCE`] times the largest (coincident or collinear
/// points, a rank-deficient sample). The rows should be well scaled
/// (normalised coordinates); [`GeometryError::Overflow`] if not finite.
pub(crate) fn null_basis<const K: usize>(
    rows: &[[f64; 9]],
) -> Result<[[f64; 9]; K], GeometryError> {
    if rows.len() + K != 9 {
        return Err(GeometryError::SampleSize {
            got: rows.len(),
            needed: 9 - K,
        });
    }
    if !rows.iter().flatten().all(|v| v.is_finite()) {
        return Err(GeometryError::Overflow("minimal design matrix"));
    }
    let mut columns = [[0.0; 9]; 9];
    for (i, row) in rows.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            columns[j][i] = v;
        }
    }
    let svd = jacobi_svd(columns).ok_or(GeometryError::Degenerate(
        "minimal system is zero or its SVD did not converge",
    ))?;
    let mut order: [usize; 9] = std::array::from_fn(|j| j);
    order.sort_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]));
    let largest = svd.singular_values[order[8]];
    if svd.singular_values[order[K]] <= RANK_TOLERANCE * largest {
        return Err(GeometryError::Degenerate(
            "rank-deficient minimal sample (coincident or collinear points)",
        ));
    }
    Ok(std::array::from_fn(|k| svd.v[order[k]]))
}

/// Two solutions closer than this (unit-norm matrices, up to sign) are one:
/// a near-double root can reach the root polish as two candidates.
const DUPLICATE_DISTANCE: f64 = 1e-10;

/// True when `m` equals one of `found` up to scale and sign, to
/// [`DUPLICATE_DISTANCE`] (all matrices of unit Frobenius norm).
pub(crate) fn is_duplicate<'a>(
    mut found: impl Iterator<Item = &'a Matrix3<f64>>,
    m: &Matrix3<f64>,
) -> bool {
    found.any(|f| (f - m).norm().min((f + m).norm()) < DUPLICATE_DISTANCE)
}
