//! Real eigenpairs of small non-symmetric matrices (the 20 × 20 companion
//! linearisation of the 6-point resultant): eigenvalues from nalgebra's
//! real Schur decomposition, one eigenvector per real eigenvalue by inverse
//! iteration, and the real roots of a univariate polynomial through its
//! companion matrix, polished by Newton steps.

use nalgebra::{DMatrix, DVector};

/// An eigenvalue counts as real when its imaginary part is below this
/// fraction of `1 + |real part|`, both of the matrix scaled to a largest
/// entry in `[1, 2)` (Schur splits a real pair into 1 × 1 blocks
/// with a zero imaginary part; a near-double real root can come out as a
/// conjugate pair with a rounding-level imaginary part, kept once).
pub(crate) const REAL_TOLERANCE: f64 = 1e-9;

/// Iteration cap of the Schur decomposition.
const SCHUR_MAX_ITERS: usize = 2000;

/// The real eigenvalues of `m` (each conjugate pair judged real counted
/// once), or `None` when `m` is not finite or the Schur iteration fails.
pub(crate) fn real_eigenvalues(m: &DMatrix<f64>) -> Option<Vec<f64>> {
    if !m.iter().all(|v| v.is_finite()) {
        return None;
    }
    // Exact power-of-two scaling to a largest entry in [1, 2), so that the
    // iteration cannot overflow; the eigenvalues scale back exactly.
    let largest = m.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    if largest == 0.0 {
        return Some(vec![0.0; m.nrows()]);
    }
    let exponent = (largest.log2().floor() as i32).clamp(-1000, 1000);
    let (down, up) = (2f64.powi(-exponent), 2f64.powi(exponent));
    let schur = nalgebra::Schur::try_new(m * down, f64::EPSILON, SCHUR_MAX_ITERS)?;
    let values = schur.complex_eigenvalues();
    Some(
        values
            .iter()
            .filter(|z| z.im >= 0.0 && z.im <= REAL_TOLERANCE * (1.0 + z.re.abs()))
            .map(|z| z.re * up)
            .filter(|v| v.is_finite())
            .collect(),
    )
}

/// A unit vector `v` with `a v ≈ 0` for a (nearly) singular square `a`: the
/// eigenvector of its eigenvalue closest to zero, by three steps of inverse
/// iteration with an LU factor. When the factor is exactly singular the
/// matrix is shifted by `δ = ε‖a‖`, widened ×16 until it factors. `None`
/// when `a` is not finite or zero.
pub(crate) fn null_vector(a: &DMatrix<f64>) -> Option<DVector<f64>> {
    let n = a.nrows();
    let norm = a.norm();
    if !norm.is_finite() || norm == 0.0 || n == 0 {
        return None;
    }
    let mut delta = 0.0;
    for _ in 0..12 {
        let shifted = a + DMatrix::identity(n, n) * delta;
        let lu = shifted.lu();
        // An irregular start: no structured null vector is orthogonal to it.
        let mut x = DVector::from_fn(n, |i, _| 1.0 + ((i * 7 + 3) as f64).sin() * 0.5);
        let mut ok = true;
        for _ in 0..3 {
            match lu.solve(&x) {
                Some(y) if y.iter().all(|v| v.is_finite()) && y.norm() > 0.0 => {
                    x = &y / y.norm();
                }
                _ => {
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            return Some(x);
        }
        delta = if delta == 0.0 {
            f64::EPSILON * norm
        } else {
            delta * 16.0
        };
    }
    None
}

/// The real roots of `Σ c_k tᵏ` (`coeffs[k] = c_k`, highest degree last,
/// a non-zero leading coefficient), from the eigenvalues of the companion
/// matrix, each polished by two Newton steps when they reduce `|p(t)|`.
/// `None` when a coefficient is not finite or the leading one is zero.
pub(crate) fn real_roots(coeffs: &[f64]) -> Option<Vec<f64>> {
    let degree = coeffs.len().checked_sub(1)?;
    let lead = coeffs[degree];
    if degree == 0 || lead == 0.0 || !coeffs.iter().all(|c| c.is_finite()) {
        return None;
    }
    // Companion matrix: last row −c_k / c_n, ones on the superdiagonal.
    let companion = DMatrix::from_fn(degree, degree, |r, c| {
        if r + 1 == degree {
            -coeffs[c] / lead
        } else if c == r + 1 {
            1.0
        } else {
            0.0
        }
    });
    let roots = real_eigenvalues(&companion)?;
    Some(
        roots
            .into_iter()
            .map(|t| newton_polish(coeffs, t))
            .collect(),
    )
}

/// Two Newton steps on `p(t) = Σ c_k tᵏ`, each kept only if `|p|` drops.
fn newton_polish(coeffs: &[f64], mut t: f64) -> f64 {
    let eval = |t: f64| {
        coeffs
            .iter()
            .rev()
            .fold((0.0, 0.0), |(p, dp), &c| (p * t + c, dp * t + p))
    };
    for _ in 0..2 {
        let (p, dp) = eval(t);
        if dp == 0.0 {
            break;
        }
        let next = t - p / dp;
        if next.is_finite() && eval(next).0.abs() < p.abs() {
            t = next;
        } else {
            break;
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_a_cubic_with_three_real_roots() {
        // (t − 1)(t + 2)(t − 0.5) = t³ + 0.5t² − 2.5t + 1
        let mut r = real_roots(&[1.0, -2.5, 0.5, 1.0]).unwrap();
        r.sort_by(f64::total_cmp);
        for (got, want) in r.iter().zip([-2.0, 0.5, 1.0]) {
            assert!((got - want).abs() < 1e-14, "{r:?}");
        }
        // t³ + t: one real root.
        assert_eq!(real_roots(&[0.0, 1.0, 0.0, 1.0]).unwrap().len(), 1);
        assert!(real_roots(&[1.0, f64::NAN]).is_none());
        assert!(real_roots(&[1.0, 0.0]).is_none());
    }

    #[test]
    fn eigenvector_of_a_non_symmetric_matrix() {
        let m = DMatrix::from_row_slice(3, 3, &[2.0, 1.0, 0.5, 0.0, -1.0, 3.0, 0.0, 0.0, 4.0]);
        let values = real_eigenvalues(&m).unwrap();
        assert_eq!(values.len(), 3);
        for &l in &values {
            let v = null_vector(&(&m - DMatrix::identity(3, 3) * l)).unwrap();
            assert!((&m * &v - &v * l).norm() < 1e-13);
        }
        assert!(null_vector(&DMatrix::zeros(3, 3)).is_none());
    }
}
