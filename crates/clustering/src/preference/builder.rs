//! Preferences of either linkage ([`Preferences`]) and their construction
//! one hypothesis at a time ([`PreferenceBuilder`]), so that no N × M
//! residual matrix is stored.

use super::{
    binary_preference, check_hypotheses, check_points, check_residual, check_tau, preference,
    BinaryPreferenceMatrix, Linkage, PreferenceMatrix,
};
use crate::ClusteringError;

/// Preferences of either linkage, ready to cluster.
#[derive(Debug, Clone, PartialEq)]
pub enum Preferences {
    /// Continuous preferences for T-Linkage (Eq. 38).
    Continuous(PreferenceMatrix),
    /// Binary preferences for J-Linkage.
    Binary(BinaryPreferenceMatrix),
}

impl Preferences {
    /// Builds the preferences of `linkage` from `residual(i, j)`: Eq. 38 for
    /// T-Linkage, `r ≤ τ` for J-Linkage.
    pub fn from_residuals(
        linkage: Linkage,
        n_points: usize,
        n_hypotheses: usize,
        tau: f64,
        residual: impl Fn(usize, usize) -> f64,
    ) -> Result<Self, ClusteringError> {
        Ok(match linkage {
            Linkage::TLinkage => Self::Continuous(PreferenceMatrix::from_residuals(
                n_points,
                n_hypotheses,
                tau,
                residual,
            )?),
            Linkage::JLinkage => Self::Binary(BinaryPreferenceMatrix::from_residuals(
                n_points,
                n_hypotheses,
                tau,
                residual,
            )?),
        })
    }

    /// The linkage these preferences are for.
    pub fn linkage(&self) -> Linkage {
        match self {
            Self::Continuous(_) => Linkage::TLinkage,
            Self::Binary(_) => Linkage::JLinkage,
        }
    }

    /// Number of points N.
    pub fn n_points(&self) -> usize {
        match self {
            Self::Continuous(p) => p.n_points(),
            Self::Binary(b) => b.n_points(),
        }
    }

    /// Number of hypotheses M.
    pub fn n_hypotheses(&self) -> usize {
        match self {
            Self::Continuous(p) => p.n_hypotheses(),
            Self::Binary(b) => b.n_hypotheses(),
        }
    }

    /// Fraction of non-zero preferences.
    pub fn density(&self) -> f64 {
        match self {
            Self::Continuous(p) => p.density(),
            Self::Binary(b) => b.density(),
        }
    }
}

/// A continuous preference matrix built one hypothesis at a time.
pub(super) struct ContinuousBuilder {
    tau: f64,
    pub(super) matrix: PreferenceMatrix,
}

impl ContinuousBuilder {
    /// An empty matrix of `n_points` points.
    pub(super) fn new(n_points: usize, tau: f64) -> Result<Self, ClusteringError> {
        check_tau(tau)?;
        check_points(n_points)?;
        Ok(Self {
            tau,
            matrix: PreferenceMatrix::empty(n_points),
        })
    }

    /// Appends one hypothesis; on error the matrix is left unchanged.
    pub(super) fn push(&mut self, residuals: &[f64]) -> Result<(), ClusteringError> {
        let j = self.matrix.n_hypotheses;
        check_hypotheses(j + 1)?;
        for (i, &r) in residuals.iter().enumerate() {
            check_residual(i, j, r)?;
        }
        let tau = self.tau;
        self.matrix
            .push_column(residuals.iter().map(|&r| preference(r, tau)));
        Ok(())
    }
}

enum BuilderState {
    Continuous(ContinuousBuilder),
    Binary {
        tau: f64,
        /// One bit set per hypothesis while building (point-major at finish).
        columns: Vec<u64>,
        n_points: usize,
        n_hypotheses: usize,
    },
}

/// Builds preferences one hypothesis at a time from its N residuals, as the
/// pipeline computes them (one `F` against all points), so the N × M
/// residual matrix is never stored.
///
/// ```
/// use clustering::{Linkage, PreferenceBuilder, Preferences};
/// let mut builder = PreferenceBuilder::new(Linkage::TLinkage, 3, 2.0).unwrap();
/// builder.push_residuals(&[0.0, 1.0, 100.0]).unwrap(); // hypothesis 0
/// builder.push_residuals(&[3.0, 0.0, 0.5]).unwrap(); // hypothesis 1
/// assert!(builder.push_residuals(&[0.0]).is_err()); // wrong length: rejected
/// let Preferences::Continuous(p) = builder.finish() else { unreachable!() };
/// assert_eq!(p.n_hypotheses(), 2);
/// assert_eq!(p.get(2, 0), 0.0);
/// assert_eq!(p.get(1, 0), (-0.5f64).exp());
/// ```
pub struct PreferenceBuilder {
    state: BuilderState,
}

impl PreferenceBuilder {
    /// A builder for N points with threshold τ (`thr_px²` in the pipeline).
    /// Errors on a non-finite or non-positive τ.
    pub fn new(linkage: Linkage, n_points: usize, tau: f64) -> Result<Self, ClusteringError> {
        let state = match linkage {
            Linkage::TLinkage => BuilderState::Continuous(ContinuousBuilder::new(n_points, tau)?),
            Linkage::JLinkage => {
                check_tau(tau)?;
                check_points(n_points)?;
                BuilderState::Binary {
                    tau,
                    columns: Vec::new(),
                    n_points,
                    n_hypotheses: 0,
                }
            }
        };
        Ok(Self { state })
    }

    /// Number of hypotheses pushed so far.
    pub fn n_hypotheses(&self) -> usize {
        match &self.state {
            BuilderState::Continuous(b) => b.matrix.n_hypotheses,
            BuilderState::Binary { n_hypotheses, .. } => *n_hypotheses,
        }
    }

    /// Appends one hypothesis given its residuals to all N points
    /// (`residuals[i] = r_ij`). Errors, leaving the builder unchanged, on a
    /// length other than N or a NaN / negative residual.
    pub fn push_residuals(&mut self, residuals: &[f64]) -> Result<(), ClusteringError> {
        let (n_points, hypothesis) = match &self.state {
            BuilderState::Continuous(b) => (b.matrix.n_points, b.matrix.n_hypotheses),
            BuilderState::Binary {
                n_points,
                n_hypotheses,
                ..
            } => (*n_points, *n_hypotheses),
        };
        if residuals.len() != n_points {
            return Err(ClusteringError::ColumnLength {
                hypothesis,
                expected: n_points,
                got: residuals.len(),
            });
        }
        match &mut self.state {
            BuilderState::Continuous(b) => b.push(residuals),
            BuilderState::Binary {
                tau,
                columns,
                n_hypotheses,
                ..
            } => {
                let mut column = vec![0u64; n_points.div_ceil(64)];
                for (i, &r) in residuals.iter().enumerate() {
                    let r = check_residual(i, hypothesis, r)?;
                    if binary_preference(r, *tau) {
                        column[i / 64] |= 1 << (i % 64);
                    }
                }
                columns.extend_from_slice(&column);
                *n_hypotheses += 1;
                Ok(())
            }
        }
    }

    /// The preferences of all hypotheses pushed so far.
    pub fn finish(self) -> Preferences {
        match self.state {
            BuilderState::Continuous(b) => Preferences::Continuous(b.matrix),
            BuilderState::Binary {
                columns,
                n_points,
                n_hypotheses,
                ..
            } => {
                let mut matrix = BinaryPreferenceMatrix::empty(n_points, n_hypotheses);
                let column_words = n_points.div_ceil(64);
                for j in 0..n_hypotheses {
                    let column = &columns[j * column_words..(j + 1) * column_words];
                    for i in 0..n_points {
                        if column[i / 64] >> (i % 64) & 1 == 1 {
                            matrix.set(i, j, true);
                        }
                    }
                }
                Preferences::Binary(matrix)
            }
        }
    }
}
