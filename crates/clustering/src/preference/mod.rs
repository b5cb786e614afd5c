//! Preference matrices: N points × M hypotheses.
//!
//! * [`PreferenceMatrix`]: the continuous preferences of T-Linkage (Eq. 38),
//!   `φ_ij = exp(−r_ij / τ)` when `r_ij ≤ 5τ`, else 0.
//! * [`BinaryPreferenceMatrix`]: the binary preferences of J-Linkage,
//!   `b_ij = [r_ij ≤ τ]`.
//!
//! `r_ij` is the residual of point i to hypothesis j (in the pipeline the
//! squared Sampson distance, Eq. 23, in px²) and `τ = thr_px²`.
//!
//! Both can be built from a closure `residual(i, j)`, one hypothesis at a
//! time ([`PreferenceBuilder`]) or one point at a time, in parallel
//! (`from_residual_rows`, whose rows are stored at exactly their size), so
//! that no N × M residual matrix is ever stored.
//!
//! # Storage
//! [`PreferenceMatrix`] stores each point's preference vector as sparse
//! sorted lists (the hypotheses with `φ > 0` and their f64 values): with
//! Eq. 38 most preferences are exactly 0 (about two thirds in realistic
//! scenes), the T-Linkage merge (Eq. 40) is an intersection of two such
//! lists, and the inner products of Eq. 39 are sums over common hypotheses,
//! in hypothesis order. A column-at-a-time build appends to every point's
//! lists, and never writes (or later re-reads) the mostly-zero dense N × M
//! array.
//! [`BinaryPreferenceMatrix`] stores one bit set per point (64 hypotheses
//! per word), so the Jaccard counts are popcounts.
//!
//! Files: the continuous matrix and the input checks here, the binary
//! matrix in `binary.rs`, the one-hypothesis-at-a-time builder in
//! `builder.rs`, the one-point-at-a-time construction in `rows.rs`.

mod binary;
mod builder;
mod rows;

pub use binary::BinaryPreferenceMatrix;
pub use builder::{PreferenceBuilder, Preferences};

use builder::ContinuousBuilder;

use crate::ClusteringError;
use serde::{Deserialize, Serialize};

/// Cut-off of Eq. 38 in units of τ: residuals above `5 τ` get preference 0.
pub const PREFERENCE_CUTOFF: f64 = 5.0;

/// Continuous preference of one point for one hypothesis (Eq. 38):
/// `exp(−r / τ)` if `r ≤ 5 τ`, else 0. In `[exp(−5), 1] ∪ {0}` for `r ≥ 0`.
///
/// ```
/// use clustering::preference;
/// assert_eq!(preference(0.0, 4.0), 1.0);
/// assert!((preference(4.0, 4.0) - (-1.0f64).exp()).abs() < 1e-15);
/// assert_eq!(preference(20.0, 4.0), (-5.0f64).exp()); // r = 5τ is kept
/// assert_eq!(preference(20.000001, 4.0), 0.0);
/// assert_eq!(preference(f64::INFINITY, 4.0), 0.0);
/// ```
#[inline]
pub fn preference(residual: f64, tau: f64) -> f64 {
    if residual <= PREFERENCE_CUTOFF * tau {
        (-residual / tau).exp()
    } else {
        0.0
    }
}

/// Binary preference of J-Linkage: the hypothesis is preferred when `r ≤ τ`.
#[inline]
pub fn binary_preference(residual: f64, tau: f64) -> bool {
    residual <= tau
}

/// The two agglomerative linkages the crate implements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Linkage {
    /// Continuous preferences (Eq. 38), Tanimoto distance (Eq. 39),
    /// element-wise minimum merge (Eq. 40). Serialised as `"t-linkage"`.
    #[default]
    TLinkage,
    /// Binary preferences `r ≤ τ`, Jaccard distance, intersection merge.
    /// Serialised as `"j-linkage"`.
    JLinkage,
}

fn check_tau(tau: f64) -> Result<(), ClusteringError> {
    if tau.is_finite() && tau > 0.0 {
        Ok(())
    } else {
        Err(ClusteringError::InvalidTau(tau))
    }
}

fn check_residual(point: usize, hypothesis: usize, value: f64) -> Result<f64, ClusteringError> {
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(ClusteringError::InvalidResidual {
            point,
            hypothesis,
            value,
        })
    }
}

fn check_points(n_points: usize) -> Result<(), ClusteringError> {
    if n_points > i32::MAX as usize {
        Err(ClusteringError::TooManyPoints(n_points))
    } else {
        Ok(())
    }
}

fn check_hypotheses(n_hypotheses: usize) -> Result<(), ClusteringError> {
    if n_hypotheses > u32::MAX as usize {
        Err(ClusteringError::TooManyHypotheses(n_hypotheses))
    } else {
        Ok(())
    }
}

fn check_rows<T>(rows: &[Vec<T>]) -> Result<usize, ClusteringError> {
    check_points(rows.len())?;
    let expected = rows.first().map_or(0, Vec::len);
    match rows.iter().position(|row| row.len() != expected) {
        Some(point) => Err(ClusteringError::RaggedRow {
            point,
            expected,
            got: rows[point].len(),
        }),
        None => Ok(expected),
    }
}

/// Continuous preference matrix of T-Linkage: N points × M hypotheses,
/// values `φ_ij ∈ [0, 1]` (Eq. 38), stored as f64 in sparse rows.
///
/// ```
/// use clustering::PreferenceMatrix;
/// // Two points, three hypotheses; τ = 1.
/// let residuals = [[0.0, 0.5, 9.0], [0.2, 7.0, 1.0]];
/// let p = PreferenceMatrix::from_residuals(2, 3, 1.0, |i, j| residuals[i][j]).unwrap();
/// assert_eq!(p.get(0, 0), 1.0);
/// assert_eq!(p.get(0, 2), 0.0); // 9 > 5τ
/// assert_eq!(p.get(1, 2), (-1.0f64).exp());
/// assert_eq!(p.row_support(1), (&[0u32, 2][..], &[(-0.2f64).exp(), (-1.0f64).exp()][..]));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PreferenceMatrix {
    n_points: usize,
    n_hypotheses: usize,
    /// `index[i]`: the hypotheses with `φ_ij > 0`, ascending.
    index: Vec<Vec<u32>>,
    /// `value[i][t] = φ_i,index[i][t]`.
    value: Vec<Vec<f64>>,
}

impl PreferenceMatrix {
    fn empty(n_points: usize) -> Self {
        Self {
            n_points,
            n_hypotheses: 0,
            index: vec![Vec::new(); n_points],
            value: vec![Vec::new(); n_points],
        }
    }

    /// Appends hypothesis `n_hypotheses` with the preferences `column`.
    fn push_column(&mut self, column: impl Iterator<Item = f64>) {
        let j = self.n_hypotheses as u32;
        for ((index, value), v) in self.index.iter_mut().zip(&mut self.value).zip(column) {
            if v > 0.0 {
                index.push(j);
                value.push(v);
            }
        }
        self.n_hypotheses += 1;
    }

    /// Builds the matrix of Eq. 38 from `residual(i, j)` (point i, hypothesis
    /// j), evaluated once per entry, hypothesis by hypothesis.
    ///
    /// Errors on an invalid τ or a NaN / negative residual.
    pub fn from_residuals(
        n_points: usize,
        n_hypotheses: usize,
        tau: f64,
        residual: impl Fn(usize, usize) -> f64,
    ) -> Result<Self, ClusteringError> {
        let mut builder = ContinuousBuilder::new(n_points, tau)?;
        let mut column = vec![0.0; n_points];
        for j in 0..n_hypotheses {
            for (i, r) in column.iter_mut().enumerate() {
                *r = residual(i, j);
            }
            builder.push(&column)?;
        }
        Ok(builder.matrix)
    }

    /// Builds the matrix from preference values given directly, one row per
    /// point (all rows of equal length M). Every value must lie in `[0, 1]`.
    ///
    /// ```
    /// use clustering::PreferenceMatrix;
    /// let p = PreferenceMatrix::from_rows(&[vec![1.0, 0.0], vec![0.5, 0.25]]).unwrap();
    /// assert_eq!((p.n_points(), p.n_hypotheses()), (2, 2));
    /// assert_eq!(p.row(1), vec![0.5, 0.25]);
    /// assert!(PreferenceMatrix::from_rows(&[vec![1.0], vec![-0.1]]).is_err());
    /// ```
    pub fn from_rows(rows: &[Vec<f64>]) -> Result<Self, ClusteringError> {
        let n_hypotheses = check_rows(rows)?;
        check_hypotheses(n_hypotheses)?;
        let mut matrix = Self::empty(rows.len());
        matrix.n_hypotheses = n_hypotheses;
        for (i, row) in rows.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                if check_preference(i, j, v)? > 0.0 {
                    matrix.index[i].push(j as u32);
                    matrix.value[i].push(v);
                }
            }
        }
        Ok(matrix)
    }

    /// Number of points N (rows).
    pub fn n_points(&self) -> usize {
        self.n_points
    }

    /// Number of hypotheses M (columns).
    pub fn n_hypotheses(&self) -> usize {
        self.n_hypotheses
    }

    /// `φ_ij`. Panics if `i ≥ N` or `j ≥ M`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        assert!(
            i < self.n_points && j < self.n_hypotheses,
            "index out of range"
        );
        match self.index[i].binary_search(&(j as u32)) {
            Ok(t) => self.value[i][t],
            Err(_) => 0.0,
        }
    }

    /// The preference vector of point i, dense (row i). Panics if `i ≥ N`.
    pub fn row(&self, i: usize) -> Vec<f64> {
        let mut row = vec![0.0; self.n_hypotheses];
        for (&j, &v) in self.index[i].iter().zip(&self.value[i]) {
            row[j as usize] = v;
        }
        row
    }

    /// The non-zero preferences of point i: the hypotheses with `φ_ij > 0`
    /// in ascending order, and their values. Panics if `i ≥ N`.
    pub fn row_support(&self, i: usize) -> (&[u32], &[f64]) {
        (&self.index[i], &self.value[i])
    }

    /// The rows' lists, taken: `(index, value)` with `index[i]` the
    /// hypotheses of point i (ascending) and `value[i]` their preferences.
    pub(crate) fn into_rows(self) -> (Vec<Vec<u32>>, Vec<Vec<f64>>) {
        (self.index, self.value)
    }

    /// The N preferences of hypothesis j (column j). Panics if `j ≥ M`.
    pub fn column(&self, j: usize) -> Vec<f64> {
        (0..self.n_points).map(|i| self.get(i, j)).collect()
    }

    /// Number of non-zero preferences.
    pub fn nonzeros(&self) -> usize {
        self.index.iter().map(Vec::len).sum()
    }

    /// Entries allocated but not used by the rows (their spare capacity):
    /// 0 when built by [`Preferences::from_residual_rows`].
    pub fn spare_capacity(&self) -> usize {
        let index: usize = self.index.iter().map(|r| r.capacity() - r.len()).sum();
        let value: usize = self.value.iter().map(|r| r.capacity() - r.len()).sum();
        index + value
    }

    /// Fraction of non-zero entries (0 for an empty matrix).
    pub fn density(&self) -> f64 {
        let total = self.n_points * self.n_hypotheses;
        if total == 0 {
            0.0
        } else {
            self.nonzeros() as f64 / total as f64
        }
    }
}

/// Checks a directly given preference value, mapping `-0.0` to `+0.0`.
fn check_preference(point: usize, hypothesis: usize, value: f64) -> Result<f64, ClusteringError> {
    if (0.0..=1.0).contains(&value) {
        Ok(value + 0.0)
    } else {
        Err(ClusteringError::InvalidPreference {
            point,
            hypothesis,
            value,
        })
    }
}
