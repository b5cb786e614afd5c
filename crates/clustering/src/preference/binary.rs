//! The binary preferences of J-Linkage, `b_ij = [r_ij ≤ τ]`, one bit set
//! per point.

use super::{binary_preference, check_points, check_residual, check_rows, check_tau};
use crate::ClusteringError;

/// Binary preference matrix of J-Linkage: N points × M hypotheses,
/// `b_ij = [r_ij ≤ τ]`, one bit set of M bits per point.
///
/// ```
/// use clustering::BinaryPreferenceMatrix;
/// let residuals = [[0.0, 2.0], [1.0, 0.5]];
/// let b = BinaryPreferenceMatrix::from_residuals(2, 2, 1.0, |i, j| residuals[i][j]).unwrap();
/// assert_eq!(b.row(0), vec![true, false]);
/// assert_eq!(b.row(1), vec![true, true]); // r = τ is preferred
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BinaryPreferenceMatrix {
    n_points: usize,
    n_hypotheses: usize,
    words_per_row: usize,
    /// Bit `j % 64` of `bits[i * words_per_row + j / 64]` is `b_ij`.
    bits: Vec<u64>,
}

impl BinaryPreferenceMatrix {
    /// An all-false matrix.
    pub(super) fn empty(n_points: usize, n_hypotheses: usize) -> Self {
        let words_per_row = n_hypotheses.div_ceil(64);
        Self {
            n_points,
            n_hypotheses,
            words_per_row,
            bits: vec![0; n_points * words_per_row],
        }
    }

    /// Builds `b_ij = [residual(i, j) ≤ τ]`.
    ///
    /// Errors on an invalid τ or a NaN / negative residual.
    pub fn from_residuals(
        n_points: usize,
        n_hypotheses: usize,
        tau: f64,
        residual: impl Fn(usize, usize) -> f64,
    ) -> Result<Self, ClusteringError> {
        check_tau(tau)?;
        check_points(n_points)?;
        let mut matrix = Self::empty(n_points, n_hypotheses);
        for i in 0..n_points {
            for j in 0..n_hypotheses {
                let r = check_residual(i, j, residual(i, j))?;
                matrix.set(i, j, binary_preference(r, tau));
            }
        }
        Ok(matrix)
    }

    /// Builds the matrix from boolean rows (one per point, all of length M).
    pub fn from_rows(rows: &[Vec<bool>]) -> Result<Self, ClusteringError> {
        let n_hypotheses = check_rows(rows)?;
        let mut matrix = Self::empty(rows.len(), n_hypotheses);
        for (i, row) in rows.iter().enumerate() {
            for (j, &b) in row.iter().enumerate() {
                matrix.set(i, j, b);
            }
        }
        Ok(matrix)
    }

    /// Sets row i to the bit set `words` (`words_per_row` words).
    pub(super) fn set_row_bits(&mut self, i: usize, words: &[u64]) {
        self.bits[i * self.words_per_row..(i + 1) * self.words_per_row].copy_from_slice(words);
    }

    /// Sets `b_ij`.
    pub(super) fn set(&mut self, i: usize, j: usize, value: bool) {
        let word = &mut self.bits[i * self.words_per_row + j / 64];
        let mask = 1u64 << (j % 64);
        if value {
            *word |= mask;
        } else {
            *word &= !mask;
        }
    }

    /// `b_ij`. Panics if `i ≥ N` or `j ≥ M`.
    pub fn get(&self, i: usize, j: usize) -> bool {
        assert!(
            i < self.n_points && j < self.n_hypotheses,
            "index out of range"
        );
        self.bits[i * self.words_per_row + j / 64] >> (j % 64) & 1 == 1
    }

    /// The preference set of point i as booleans (row i). Panics if `i ≥ N`.
    pub fn row(&self, i: usize) -> Vec<bool> {
        (0..self.n_hypotheses).map(|j| self.get(i, j)).collect()
    }

    /// The bit set of point i: `words_per_row` words, bit `j % 64` of word
    /// `j / 64` is `b_ij`, bits at `j ≥ M` are 0. Panics if `i ≥ N`.
    pub fn row_bits(&self, i: usize) -> &[u64] {
        &self.bits[i * self.words_per_row..(i + 1) * self.words_per_row]
    }

    /// Number of points N (rows).
    pub fn n_points(&self) -> usize {
        self.n_points
    }

    /// Number of hypotheses M (columns).
    pub fn n_hypotheses(&self) -> usize {
        self.n_hypotheses
    }

    /// Number of 64-bit words per row, `⌈M / 64⌉`.
    pub fn words_per_row(&self) -> usize {
        self.words_per_row
    }

    /// Fraction of true entries (0 for an empty matrix).
    pub fn density(&self) -> f64 {
        let total = self.n_points * self.n_hypotheses;
        if total == 0 {
            return 0.0;
        }
        let ones: u64 = self.bits.iter().map(|w| u64::from(w.count_ones())).sum();
        ones as f64 / total as f64
    }
}
