//! Preferences built one point (row) at a time: each row's residuals to
//! all M hypotheses are computed together, so a row is stored at exactly its
//! size. The column-at-a-time [`super::PreferenceBuilder`] appends to every
//! row once per hypothesis, and its rows grow by doubling (about 40 % of
//! spare capacity on average, the largest part of the memory of a large
//! scene).

use rayon::prelude::*;

use super::{
    binary_preference, check_hypotheses, check_points, check_residual, check_tau, preference,
    BinaryPreferenceMatrix, Linkage, PreferenceMatrix, Preferences,
};
use crate::ClusteringError;

/// Points per parallel task.
const ROWS_PER_TASK: usize = 64;

impl Preferences {
    /// The preferences of `linkage` built one point at a time: Eq. 38 for
    /// T-Linkage, `r ≤ τ` for J-Linkage. `fill_row(i, out)` writes the
    /// residuals `r_i0 … r_i(M−1)` of point i into `out` (length M). Rows
    /// are computed in parallel and a continuous row is stored at exactly
    /// its number of non-zero preferences; the preferences are those
    /// [`Preferences::from_residuals`] builds from the same residuals,
    /// whatever the number of threads.
    ///
    /// Errors on an invalid τ or a NaN / negative residual (the first point,
    /// then the first hypothesis, that has one).
    ///
    /// ```
    /// use clustering::{Linkage, Preferences};
    /// let residuals = [[0.0, 0.5, 9.0], [0.2, 7.0, 1.0]];
    /// let by_rows = Preferences::from_residual_rows(Linkage::TLinkage, 2, 3, 1.0, |i, out| {
    ///     out.copy_from_slice(&residuals[i])
    /// })
    /// .unwrap();
    /// let by_entries =
    ///     Preferences::from_residuals(Linkage::TLinkage, 2, 3, 1.0, |i, j| residuals[i][j]);
    /// assert_eq!(by_rows, by_entries.unwrap());
    /// ```
    pub fn from_residual_rows(
        linkage: Linkage,
        n_points: usize,
        n_hypotheses: usize,
        tau: f64,
        fill_row: impl Fn(usize, &mut [f64]) + Sync,
    ) -> Result<Self, ClusteringError> {
        check_tau(tau)?;
        check_points(n_points)?;
        check_hypotheses(n_hypotheses)?;
        Ok(match linkage {
            Linkage::TLinkage => {
                let rows = map_rows(n_points, n_hypotheses, &fill_row, |r| sparse_row(r, tau))?;
                let (index, value) = rows.into_iter().unzip();
                Self::Continuous(PreferenceMatrix {
                    n_points,
                    n_hypotheses,
                    index,
                    value,
                })
            }
            Linkage::JLinkage => {
                let rows = map_rows(n_points, n_hypotheses, &fill_row, |r| bit_row(r, tau))?;
                let mut matrix = BinaryPreferenceMatrix::empty(n_points, n_hypotheses);
                for (i, words) in rows.iter().enumerate() {
                    matrix.set_row_bits(i, words);
                }
                Self::Binary(matrix)
            }
        })
    }
}

/// Runs `row(residuals)` for every point i, `residuals` holding point i's
/// residuals to the M hypotheses as written by `fill_row(i, residuals)`
/// (`row` may overwrite them); in parallel, with the results in point
/// order. On invalid residuals, the error of the first point (and, within
/// it, the first hypothesis) that has one.
fn map_rows<T: Send>(
    n_points: usize,
    n_hypotheses: usize,
    fill_row: &(impl Fn(usize, &mut [f64]) + Sync),
    row: impl Fn(&mut [f64]) -> T + Sync,
) -> Result<Vec<T>, ClusteringError> {
    let rows: Vec<Result<T, ClusteringError>> = (0..n_points)
        .into_par_iter()
        .with_min_len(ROWS_PER_TASK)
        .map_init(
            || vec![0.0; n_hypotheses],
            |residuals, i| {
                fill_row(i, residuals);
                for (j, &r) in residuals.iter().enumerate() {
                    check_residual(i, j, r)?;
                }
                Ok(row(residuals))
            },
        )
        .collect();
    rows.into_iter().collect()
}

/// One row of Eq. 38 as sparse lists (the hypotheses with `φ > 0`,
/// ascending, and their values), each allocated at exactly its length;
/// `residuals` is overwritten with the preferences.
fn sparse_row(residuals: &mut [f64], tau: f64) -> (Vec<u32>, Vec<f64>) {
    for r in residuals.iter_mut() {
        *r = preference(*r, tau);
    }
    let count = residuals.iter().filter(|&&v| v > 0.0).count();
    let (mut index, mut value) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for (j, &v) in residuals.iter().enumerate() {
        if v > 0.0 {
            index.push(j as u32);
            value.push(v);
        }
    }
    (index, value)
}

/// One row of J-Linkage's preferences as a bit set: bit `j % 64` of word
/// `j / 64` is `r_j ≤ τ`.
fn bit_row(residuals: &mut [f64], tau: f64) -> Vec<u64> {
    let mut words = vec![0u64; residuals.len().div_ceil(64)];
    for (j, &r) in residuals.iter().enumerate() {
        if binary_preference(r, tau) {
            words[j / 64] |= 1 << (j % 64);
        }
    }
    words
}
