//! Nonlinear polish of a fundamental matrix on a few matches: the
//! reference code's PoseLib `refine_fundamental` call before IRLS (step 3 of
//! Algorithm 1; docs/method.md: "the reference first polishes F on the sample").
//!
//! It minimises the robust Sampson cost (square root of thesis Eq. 23 as the
//! residual `r_k = e_k / ‖∇e_k‖`, Cauchy loss)
//!
//! ```text
//! C(F) = Σ_k τ² log(1 + r_k² / τ²),   τ = 1 px,
//! ```
//!
//! over rank-2 matrices, as PoseLib 2.0.5 does when called without options:
//! * coordinates first normalised as its Python wrapper does: each image's
//!   centroid to the origin, then one shared scale `s` for both images (mean
//!   distance `√2` over all 2n points), so `r` and `τ` scale by `1/s` and the
//!   minimiser is the one in pixels;
//! * the factorisation of Bartoli and Sturm (PAMI 2004),
//!   `F = u₁ v₁ᵀ + σ u₂ v₂ᵀ` with rotations `U = [u₁ u₂ u₃]`,
//!   `V = [v₁ v₂ v₃]` (unit quaternions) and `σ = s₂ / s₁ ≥ 0`: 7 parameters,
//!   rank 2 by construction. A step `(δu, δv, δσ)` maps `U ← exp([δu]×) U`,
//!   `V ← exp([δv]×) V`, `σ ← σ + δσ`, so `∂F/∂δu_i = [e_i]× F`,
//!   `∂F/∂δv_i = −F [e_i]×`, `∂F/∂σ = u₂ v₂ᵀ`;
//! * Levenberg–Marquardt on the IRLS form of the Cauchy loss (normal
//!   equations `(Σ w_k J_kᵀ J_k + λ I) δ = −Σ w_k r_k J_kᵀ`,
//!   `w_k = 1 / (1 + r_k² / τ²)`), a step kept only when it lowers `C`,
//!   `λ` from `10⁻³` divided by 10 on success and multiplied by 10 on
//!   failure within `[10⁻¹⁰, 10¹⁰]`, stopping after 100 iterations, when
//!   `‖Σ w r J‖ < 10⁻¹⁰` or when `‖δ‖ < 10⁻⁸` (PoseLib's `BundleOptions`
//!   defaults, in the normalised frame).
//!
//! Differences from PoseLib are rounding only (nalgebra's quaternions and a
//! one-sided Jacobi SVD instead of Eigen's).

use crate::eight_point::{enforce_rank2, finish};
use crate::linalg::jacobi_svd;
use crate::{Correspondences, GeometryError};
use nalgebra::{Matrix3, Rotation3, SMatrix, SVector, UnitQuaternion, Vector3};
use std::cmp::Ordering;

/// Cauchy loss scale `τ`, in px (PoseLib's `loss_scale` default, 1.0).
pub const POLISH_LOSS_SCALE_PX: f64 = 1.0;
/// Maximum number of Levenberg–Marquardt iterations (PoseLib's default).
pub const POLISH_MAX_ITERS: usize = 100;
const GRADIENT_TOL: f64 = 1e-10;
const STEP_TOL: f64 = 1e-8;
const INITIAL_LAMBDA: f64 = 1e-3;
const MIN_LAMBDA: f64 = 1e-10;
const MAX_LAMBDA: f64 = 1e10;

type Vector7 = SVector<f64, 7>;
type Matrix7 = SMatrix<f64, 7, 7>;

/// The result of [`polish_fundamental`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polished {
    /// The polished matrix: rank 2, unit Frobenius norm, largest entry
    /// positive; the input's rank-2 projection when no step lowered the cost.
    pub f: Matrix3<f64>,
    /// Levenberg–Marquardt iterations run (`0 ..= POLISH_MAX_ITERS`).
    pub iterations: usize,
    /// Robust cost `C` of the input's rank-2 projection, in px² (NaN when
    /// the points coincide or the input has rank below 2).
    pub initial_cost: f64,
    /// Robust cost `C` of `f`, in px²; `≤ initial_cost`.
    pub cost: f64,
}

/// Polishes `f` on the matches at `indices` (the [module](self)'s
/// Levenberg–Marquardt on the Cauchy-robust Sampson cost, as PoseLib's
/// `refine_fundamental`). Matches whose points coincide, or an `f` of rank
/// below 2, leave `f` as it is (its rank-2 projection, 0 iterations, NaN
/// costs); so does a cost that no step lowers (with the iterations run).
///
/// Errors: an index out of range ([`GeometryError::IndexOutOfRange`]), a
/// non-finite ([`GeometryError::NonFiniteMatrix`]) or zero
/// ([`GeometryError::ZeroMatrix`]) `f`, no index
/// ([`GeometryError::TooFewPoints`]).
///
/// ```
/// use geometry::{polish_fundamental, Correspondences};
/// use nalgebra::Matrix3;
/// // Sideways translation (F ∝ [e_x]×) seen with 0.1 px of vertical noise.
/// let p1: Vec<[f64; 2]> = (0..12).map(|i| [(i * 37 % 11) as f64 * 20.0 - 100.0, (i * i % 7) as f64 * 15.0 - 50.0]).collect();
/// let p2: Vec<[f64; 2]> = p1.iter().enumerate().map(|(i, p)| [p[0] + 4000.0 / (4.0 + i as f64), p[1] + 0.1 * (i as f64 * 1.3).sin()]).collect();
/// let points = Correspondences::new(&p1, &p2).unwrap();
/// let start = Matrix3::new(0.0, 0.001, 0.01, -0.001, 0.0, -1.0, 0.0, 1.0, 0.0);
/// let all: Vec<usize> = (0..12).collect();
/// let polished = polish_fundamental(&points, &all, &start).unwrap();
/// assert!(polished.cost < polished.initial_cost);
/// assert!(polished.f.determinant().abs() < 1e-12);
/// ```
pub fn polish_fundamental(
    points: &Correspondences,
    indices: &[usize],
    f: &Matrix3<f64>,
) -> Result<Polished, GeometryError> {
    let len = points.len();
    if let Some(&index) = indices.iter().find(|&&i| i >= len) {
        return Err(GeometryError::IndexOutOfRange { index, len });
    }
    if indices.is_empty() {
        return Err(GeometryError::TooFewPoints { got: 0, needed: 1 });
    }
    for (k, v) in f.iter().enumerate() {
        if !v.is_finite() {
            return Err(GeometryError::NonFiniteMatrix {
                row: k % 3,
                col: k / 3,
            });
        }
    }
    if f.iter().all(|&v| v == 0.0) {
        return Err(GeometryError::ZeroMatrix);
    }
    polish_at(points, indices, f, &mut Vec::new())
}

/// [`polish_fundamental`] without the argument checks (indices in range, `f`
/// finite and non-zero), with a reusable buffer for the normalised matches.
pub(crate) fn polish_at(
    points: &Correspondences,
    indices: &[usize],
    f: &Matrix3<f64>,
    scratch: &mut Vec<[f64; 4]>,
) -> Result<Polished, GeometryError> {
    let unchanged = || -> Result<Polished, GeometryError> {
        Ok(Polished {
            f: finish(enforce_rank2(*f))?,
            iterations: 0,
            initial_cost: f64::NAN,
            cost: f64::NAN,
        })
    };
    let Some(frame) = Frame::normalize_into(points, indices, scratch) else {
        return unchanged();
    };
    // x̂ = T x, so F̂ = T2⁻ᵀ F T1⁻¹ in the normalised frame.
    let f_hat = frame.inverse(1).transpose() * f * frame.inverse(0);
    let Some(start) = Factorized::new(&f_hat) else {
        return unchanged();
    };
    let problem = SampsonCauchy {
        matches: scratch,
        tau2: (POLISH_LOSS_SCALE_PX / frame.scale).powi(2),
    };
    let (end, iterations, initial_cost, cost) = levenberg_marquardt(&problem, start);
    let to_px = frame.scale * frame.scale;
    Ok(Polished {
        f: finish(frame.transform(1).transpose() * end.matrix() * frame.transform(0))?,
        iterations,
        initial_cost: initial_cost * to_px,
        cost: cost * to_px,
    })
}

/// PoseLib's normalisation of a match set: per-image centroids `c`, one
/// shared scale `s`, `x̂ = (x − c) / s`.
struct Frame {
    /// Centroids of image 1 and image 2.
    centroids: [[f64; 2]; 2],
    /// Mean distance to the centroids over all 2n points, divided by `√2`.
    scale: f64,
}

impl Frame {
    /// Writes the matches at `indices`, normalised, into `out` as
    /// `[x1, y1, x2, y2]`; `None` when all points coincide (their spread is
    /// below `10⁻¹²` of the largest centroid coordinate, or of 1 px).
    fn normalize_into(
        points: &Correspondences,
        indices: &[usize],
        out: &mut Vec<[f64; 4]>,
    ) -> Option<Self> {
        let n = indices.len() as f64;
        let mut c = [0.0; 4];
        for &i in indices {
            let (p, q) = (points.point1(i), points.point2(i));
            for (ck, v) in c.iter_mut().zip([p[0], p[1], q[0], q[1]]) {
                *ck += v;
            }
        }
        c.iter_mut().for_each(|v| *v /= n);
        out.clear();
        let mut spread = 0.0;
        for &i in indices {
            let (p, q) = (points.point1(i), points.point2(i));
            let m = [p[0] - c[0], p[1] - c[1], q[0] - c[2], q[1] - c[3]];
            spread += m[0].hypot(m[1]) + m[2].hypot(m[3]);
            out.push(m);
        }
        let scale = spread / (std::f64::consts::SQRT_2 * n);
        // Coincident to rounding: the centroid's own rounding error is
        // ~ε·|c|, so a spread of that order is no spread.
        let magnitude = c.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        if !(scale.is_finite() && scale > 1e-12 * magnitude) {
            return None;
        }
        out.iter_mut()
            .for_each(|m| m.iter_mut().for_each(|v| *v /= scale));
        Some(Self {
            centroids: [[c[0], c[1]], [c[2], c[3]]],
            scale,
        })
    }

    /// `T` of image `k` (0 or 1): `x̂ = T x`.
    fn transform(&self, k: usize) -> Matrix3<f64> {
        let ([cx, cy], s) = (self.centroids[k], self.scale);
        Matrix3::new(1.0 / s, 0.0, -cx / s, 0.0, 1.0 / s, -cy / s, 0.0, 0.0, 1.0)
    }

    /// `T⁻¹` of image `k`.
    fn inverse(&self, k: usize) -> Matrix3<f64> {
        let ([cx, cy], s) = (self.centroids[k], self.scale);
        Matrix3::new(s, 0.0, cx, 0.0, s, cy, 0.0, 0.0, 1.0)
    }
}

/// The Bartoli–Sturm factorisation `F = u₁ v₁ᵀ + σ u₂ v₂ᵀ`.
#[derive(Debug, Clone, Copy)]
struct Factorized {
    u: UnitQuaternion<f64>,
    v: UnitQuaternion<f64>,
    sigma: f64,
}

impl Factorized {
    /// From the SVD `F = Σ s_j u_j v_jᵀ` (`s₁ ≥ s₂ ≥ s₃`, `s₃` dropped), with
    /// `u₃ = u₁ × u₂` and `v₃ = v₁ × v₂` so that `U` and `V` are rotations.
    /// `None` when the SVD fails or `F` has rank below 2 (`s₂ ≤ 10⁻¹² s₁`).
    fn new(f: &Matrix3<f64>) -> Option<Self> {
        let svd = jacobi_svd([0, 1, 2].map(|c| [f[(0, c)], f[(1, c)], f[(2, c)]]))?;
        let s = svd.singular_values;
        let mut order = [0, 1, 2];
        order.sort_by(|&a, &b| s[b].total_cmp(&s[a]));
        let (first, second) = (order[0], order[1]);
        // Rank below 2 (to rounding): no second direction to factorise.
        if s[second].partial_cmp(&(1e-12 * s[first])) != Some(Ordering::Greater) {
            return None;
        }
        let u1 = Vector3::from(svd.av[first]) / s[first];
        let u2 = Vector3::from(svd.av[second]) / s[second];
        let v1 = Vector3::from(svd.v[first]);
        let v2 = Vector3::from(svd.v[second]);
        let rotation = |a: Vector3<f64>, b: Vector3<f64>| {
            let m = Matrix3::from_columns(&[a, b, a.cross(&b)]);
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
        };
        Some(Self {
            u: rotation(u1, u2),
            v: rotation(v1, v2),
            sigma: s[second] / s[first],
        })
    }

    /// `(U, V)` as rotation matrices.
    fn rotations(&self) -> (Matrix3<f64>, Matrix3<f64>) {
        (
            self.u.to_rotation_matrix().into_inner(),
            self.v.to_rotation_matrix().into_inner(),
        )
    }

    /// `F = u₁ v₁ᵀ + σ u₂ v₂ᵀ`.
    fn matrix(&self) -> Matrix3<f64> {
        let (u, v) = self.rotations();
        u.column(0) * v.column(0).transpose() + self.sigma * u.column(1) * v.column(1).transpose()
    }

    /// The parameters after the step `δ = (δu, δv, δσ)`.
    fn step(&self, delta: &Vector7) -> Self {
        let du = Vector3::new(delta[0], delta[1], delta[2]);
        let dv = Vector3::new(delta[3], delta[4], delta[5]);
        Self {
            u: UnitQuaternion::from_scaled_axis(du) * self.u,
            v: UnitQuaternion::from_scaled_axis(dv) * self.v,
            sigma: self.sigma + delta[6],
        }
    }

    /// `∂F/∂p` for the 7 step parameters (see the module documentation).
    fn tangents(&self) -> [Matrix3<f64>; 7] {
        let (u, v) = self.rotations();
        let f = self.matrix();
        let axis = |i: usize| Vector3::ith(i, 1.0).cross_matrix();
        [
            axis(0) * f,
            axis(1) * f,
            axis(2) * f,
            -f * axis(0),
            -f * axis(1),
            -f * axis(2),
            u.column(1) * v.column(1).transpose(),
        ]
    }
}

/// The robust Sampson cost on normalised matches `[x1, y1, x2, y2]`.
struct SampsonCauchy<'a> {
    matches: &'a [[f64; 4]],
    /// `τ²` in the normalised frame.
    tau2: f64,
}

/// Residual `r = e / ‖∇e‖` of one match and `∂r/∂F` (row-major entries).
fn residual_and_gradient(f: &Matrix3<f64>, m: &[f64; 4]) -> (f64, Matrix3<f64>) {
    let x1 = Vector3::new(m[0], m[1], 1.0);
    let x2 = Vector3::new(m[2], m[3], 1.0);
    let (fx1, ftx2) = (f * x1, f.transpose() * x2);
    let e = x2.dot(&fx1);
    let g2 = fx1[0] * fx1[0] + fx1[1] * fx1[1] + ftx2[0] * ftx2[0] + ftx2[1] * ftx2[1];
    let norm = g2.sqrt();
    let r = e / norm;
    // ∂e/∂F_ij = x2_i x1_j; ∂(g²)/∂F_ij = 2 (Fᵀx2)_j x2_i [j < 2] + 2 (F x1)_i x1_j [i < 2].
    let s = e / g2;
    let d = Matrix3::from_fn(|i, j| {
        let mut dg = 0.0;
        if j < 2 {
            dg += ftx2[j] * x2[i];
        }
        if i < 2 {
            dg += fx1[i] * x1[j];
        }
        (x2[i] * x1[j] - s * dg) / norm
    });
    (r, d)
}

impl SampsonCauchy<'_> {
    /// `C(F) = Σ τ² log(1 + r² / τ²)`.
    fn cost(&self, f: &Matrix3<f64>) -> f64 {
        self.matches
            .iter()
            .map(|m| {
                let (r, _) = residual_and_gradient(f, m);
                self.tau2 * (r * r / self.tau2).ln_1p()
            })
            .sum()
    }

    /// `(Σ w JᵀJ, Σ w r Jᵀ)` at `p`, `w = 1 / (1 + r² / τ²)`.
    fn normal_equations(&self, p: &Factorized) -> (Matrix7, Vector7) {
        let f = p.matrix();
        let tangents = p.tangents();
        let (mut jtj, mut jtr) = (Matrix7::zeros(), Vector7::zeros());
        for m in self.matches {
            let (r, d) = residual_and_gradient(&f, m);
            let w = (1.0 / (1.0 + r * r / self.tau2)).max(f64::MIN_POSITIVE);
            let j = Vector7::from_fn(|k, _| d.dot(&tangents[k]));
            jtj += w * j * j.transpose();
            jtr += w * r * j;
        }
        (jtj, jtr)
    }
}

/// PoseLib's Levenberg–Marquardt loop (see the module documentation):
/// returns the end point, the iteration count and the initial and final
/// costs (normalised frame).
fn levenberg_marquardt(
    problem: &SampsonCauchy,
    start: Factorized,
) -> (Factorized, usize, f64, f64) {
    let mut p = start;
    let initial_cost = problem.cost(&p.matrix());
    let mut cost = initial_cost;
    let mut lambda = INITIAL_LAMBDA;
    let (mut jtj, mut jtr) = (Matrix7::zeros(), Vector7::zeros());
    let mut recompute = true;
    let mut iterations = 0;
    while iterations < POLISH_MAX_ITERS {
        if recompute {
            (jtj, jtr) = problem.normal_equations(&p);
            if jtr.norm() < GRADIENT_TOL {
                break;
            }
        }
        let damped = jtj + Matrix7::identity() * lambda;
        // Only a non-finite system has no Cholesky factor (λ > 0); its steps
        // would all be rejected.
        let Some(cholesky) = damped.cholesky() else {
            break;
        };
        let delta = -cholesky.solve(&jtr);
        if delta.norm() < STEP_TOL {
            break;
        }
        let candidate = p.step(&delta);
        let candidate_cost = problem.cost(&candidate.matrix());
        if candidate_cost < cost {
            p = candidate;
            cost = candidate_cost;
            lambda = (lambda / 10.0).max(MIN_LAMBDA);
            recompute = true;
        } else {
            lambda = (lambda * 10.0).min(MAX_LAMBDA);
            recompute = false;
        }
        iterations += 1;
    }
    (p, iterations, initial_cost, cost)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_matches() -> Vec<[f64; 4]> {
        (0..9)
            .map(|i| {
                let t = i as f64;
                [
                    (t * 1.3).sin(),
                    (t * 0.7).cos(),
                    (t * 2.1).sin() * 0.9,
                    (t * 0.4).cos() - 0.2,
                ]
            })
            .collect()
    }

    fn start() -> Factorized {
        let f = Matrix3::new(0.3, -1.2, 0.4, 0.9, 0.2, -0.7, -0.5, 0.8, 0.1);
        let g = crate::enforce_rank2(f);
        Factorized::new(&g).unwrap()
    }

    #[test]
    fn factorisation_reproduces_a_rank_2_matrix() {
        let f = Matrix3::new(0.3, -1.2, 0.4, 0.9, 0.2, -0.7, -0.5, 0.8, 0.1);
        let g = crate::enforce_rank2(f);
        let p = Factorized::new(&g).unwrap();
        let h = p.matrix();
        // Same matrix up to the scale s₁ (and sign).
        let (a, b) = (g / g.norm(), h / h.norm());
        assert!((a - b).norm().min((a + b).norm()) < 1e-14);
        assert!(p.sigma > 0.0 && p.sigma <= 1.0);
        assert!(
            Factorized::new(&Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)).is_none()
        );
    }

    #[test]
    fn analytic_jacobian_matches_central_differences() {
        let matches = sample_matches();
        let p = start();
        let f = p.matrix();
        let tangents = p.tangents();
        let h = 1e-6;
        for m in &matches {
            let (_, d) = residual_and_gradient(&f, m);
            for k in 0..7 {
                let mut delta = Vector7::zeros();
                delta[k] = h;
                let (plus, _) = residual_and_gradient(&p.step(&delta).matrix(), m);
                let (minus, _) = residual_and_gradient(&p.step(&-delta).matrix(), m);
                let numeric = (plus - minus) / (2.0 * h);
                let analytic = d.dot(&tangents[k]);
                assert!(
                    (numeric - analytic).abs() < 1e-7 * (1.0 + analytic.abs()),
                    "parameter {k}: {numeric} vs {analytic}"
                );
            }
        }
    }

    #[test]
    fn levenberg_marquardt_never_increases_the_cost_and_reaches_a_stationary_point() {
        let matches = sample_matches();
        let problem = SampsonCauchy {
            matches: &matches,
            tau2: 0.25,
        };
        let (end, iterations, initial, cost) = levenberg_marquardt(&problem, start());
        assert!(cost <= initial && iterations > 0);
        let (_, jtr) = problem.normal_equations(&end);
        assert!(jtr.norm() < 1e-6, "gradient {:e}", jtr.norm());
    }
}
