//! Pieces shared by the minimal solvers: the sample-size check, the
//! epipolar design row, the null space of a minimal epipolar system and the
//! duplicate test.

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
/// `(9 − K) × 9` system `rows`: the last `K` columns of `Q` in a Householder
/// QR with column pivoting of its transpose, `Aᵀ P = Q R` (the first
/// `9 − K` columns of `Q` span the row space). [`GeometryError::Degenerate`]
/// when the null space is larger than `K`: the last pivot `|R_kk|` is below
/// [`RANK_TOLERANCE`] times the first (coincident or collinear points, a
/// repeated match). The rows should be well scaled (normalised
/// coordinates); [`GeometryError::Overflow`] if not finite.
pub(crate) fn null_basis<const K: usize>(
    rows: &[[f64; 9]],
) -> Result<[[f64; 9]; K], GeometryError> {
    let k = rows.len();
    if k + K != 9 {
        return Err(GeometryError::SampleSize {
            got: k,
            needed: 9 - K,
        });
    }
    if !rows.iter().flatten().all(|v| v.is_finite()) {
        return Err(GeometryError::Overflow("minimal design matrix"));
    }
    // Columns of Aᵀ (the rows of A), reduced in place; q holds Q row-wise.
    let mut columns = [[0.0; 9]; 9];
    columns[..k].copy_from_slice(rows);
    let mut q = [[0.0; 9]; 9];
    for (i, row) in q.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let mut first_pivot = 0.0;
    for j in 0..k {
        let tail_norm2 = |c: &[f64; 9]| c[j..].iter().map(|v| v * v).sum::<f64>();
        let pivot = (j..k)
            .max_by(|&a, &b| tail_norm2(&columns[a]).total_cmp(&tail_norm2(&columns[b])))
            .unwrap_or(j);
        columns.swap(j, pivot);
        let alpha = tail_norm2(&columns[j]).sqrt();
        if j == 0 {
            first_pivot = alpha;
        }
        if !(alpha > RANK_TOLERANCE * first_pivot && alpha.is_finite()) {
            return Err(GeometryError::Degenerate(
                "rank-deficient minimal sample (coincident or collinear points)",
            ));
        }
        // Householder vector v with (I − 2vvᵀ/vᵀv) x = ∓α e_j.
        let mut v = [0.0; 9];
        v[j..].copy_from_slice(&columns[j][j..]);
        v[j] += alpha.copysign(v[j]);
        let vtv: f64 = v.iter().map(|x| x * x).sum();
        for column in columns[j + 1..k].iter_mut() {
            let d = 2.0 * dot(&v, column) / vtv;
            column.iter_mut().zip(&v).for_each(|(c, vi)| *c -= d * vi);
        }
        // Q ← Q H_j.
        for row in q.iter_mut() {
            let d = 2.0 * dot(&v, row) / vtv;
            row.iter_mut().zip(&v).for_each(|(c, vi)| *c -= d * vi);
        }
    }
    Ok(std::array::from_fn(|c| {
        std::array::from_fn(|r| q[r][k + c])
    }))
}

fn dot(a: &[f64; 9], b: &[f64; 9]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
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
