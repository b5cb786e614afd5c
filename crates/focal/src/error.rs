//! The typed failures of the focal solvers.

/// Why a focal-length solver gave no answer.
///
/// Bougnoux's closed form fails with [`NoRealFocal`](Self::NoRealFocal) or
/// [`Singular`](Self::Singular); the robust iterative solver (docs/method.md
/// step 4) with [`NoRealSolution`](Self::NoRealSolution),
/// [`NonFinite`](Self::NonFinite) or [`NoConvergence`](Self::NoConvergence),
/// each carrying the iteration index at which it stopped (the count that
/// [`OnFailure::Prior`](crate::OnFailure::Prior) reports).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FocalFailure {
    /// The fundamental matrix has a NaN or infinite entry, or is zero.
    #[error("the fundamental matrix has a non-finite entry or is zero")]
    InvalidMatrix,
    /// A parameter is NaN, infinite, or out of its domain.
    #[error("invalid parameter `{name}` = {value}: {requirement}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        requirement: &'static str,
    },
    /// Bougnoux's formula gives `f^2 <= 0`: no real focal length.
    #[error("no real focal length (Bougnoux: f^2 <= 0)")]
    NoRealFocal,
    /// The denominator of Bougnoux's formula vanishes (e.g. parallel optical
    /// axes), or the result is not finite.
    #[error("Bougnoux's formula is singular (vanishing denominator)")]
    Singular,
    /// The robust solver's step has no real solution: the two Kruppa
    /// constraints cannot both be met on the plane `p + l1 c1 + l2 c2`
    /// (or the directions c1, c2 are degenerate).
    #[error("no real solution of the Kruppa constraints at iteration {iteration}")]
    NoRealSolution {
        /// The iteration index k at which no solution was found.
        iteration: usize,
    },
    /// A non-finite value appeared in the iteration.
    #[error("non-finite value in the robust focal iteration at iteration {iteration}")]
    NonFinite {
        /// The iteration index k at which it appeared.
        iteration: usize,
    },
    /// The final iterate does not satisfy the Kruppa constraints to `1e-6`
    /// of their value at the prior.
    #[error(
        "the Kruppa constraints are not satisfied after {iterations} iterations \
         (residual {residual:e} relative to the prior)"
    )]
    NoConvergence {
        /// The iteration count reached.
        iterations: usize,
        /// `max |g_i(x)| / max |g_i(p)|`.
        residual: f64,
    },
    /// The multi-start solver was given no weight sets.
    #[error("no weight sets given to the multi-start solver")]
    NoWeightSets,
}

impl FocalFailure {
    /// The iteration count the robust solver had used when it failed (0 for
    /// failures that happen before the first iteration).
    pub fn iterations(&self) -> usize {
        match *self {
            Self::NoRealSolution { iteration } | Self::NonFinite { iteration } => iteration,
            Self::NoConvergence { iterations, .. } => iterations,
            _ => 0,
        }
    }

    /// True for the failures of the robust iteration itself
    /// ([`NoRealSolution`](Self::NoRealSolution), [`NonFinite`](Self::NonFinite),
    /// [`NoConvergence`](Self::NoConvergence)), false for invalid input and
    /// Bougnoux's failures.
    pub fn is_solve_failure(&self) -> bool {
        matches!(
            self,
            Self::NoRealSolution { .. } | Self::NonFinite { .. } | Self::NoConvergence { .. }
        )
    }
}
