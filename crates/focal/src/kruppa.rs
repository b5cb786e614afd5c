//! The two Kruppa constraints in the SVD form of F (docs/method.md step 4): their
//! values, gradients and expansion along a step's plane, and the public
//! residuals that measure an estimate's feasibility.

use nalgebra::{Matrix3, Vector3};

use crate::bivariate::{Lin2, Quad2, Quartic2};
use crate::params::FocalEstimate;

/// The parts of the SVD `F = U diag(s1, s2, 0) V^T` the Kruppa constraints
/// use: `u1, u2` (first two columns of U, image 2), `v1, v2` (first two
/// columns of V, image 1) and the two largest singular values, F being
/// scaled to unit Frobenius norm first.
#[derive(Clone, Copy, Debug)]
pub(crate) struct KruppaSvd {
    pub s1: f64,
    pub s2: f64,
    pub u1: Vector3<f64>,
    pub u2: Vector3<f64>,
    pub v1: Vector3<f64>,
    pub v2: Vector3<f64>,
}

/// SVD of a 3x3 matrix, `m = U diag(s) V^T` with `s` sorted in decreasing
/// order and U, V orthogonal, by one-sided (Hestenes) Jacobi rotations, which
/// keep the small singular vectors accurate (the epipoles are the third
/// columns). The third column of U is completed as `u1 x u2`. `None` when
/// `m` is not finite.
pub(crate) fn sorted_svd(m: &Matrix3<f64>) -> Option<(Matrix3<f64>, Vector3<f64>, Matrix3<f64>)> {
    if !m.iter().all(|v| v.is_finite()) {
        return None;
    }
    let mut w = *m;
    let mut v = Matrix3::<f64>::identity();
    for _sweep in 0..60 {
        let mut rotated = false;
        for (i, j) in [(0usize, 1usize), (0, 2), (1, 2)] {
            let alpha = w.column(i).norm_squared();
            let beta = w.column(j).norm_squared();
            let gamma = w.column(i).dot(&w.column(j));
            if gamma == 0.0 || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                continue;
            }
            rotated = true;
            let zeta = (beta - alpha) / (2.0 * gamma);
            let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
            let c = 1.0 / (1.0 + t * t).sqrt();
            let s = c * t;
            for r in 0..3 {
                let (wi, wj) = (w[(r, i)], w[(r, j)]);
                w[(r, i)] = c * wi - s * wj;
                w[(r, j)] = s * wi + c * wj;
                let (vi, vj) = (v[(r, i)], v[(r, j)]);
                v[(r, i)] = c * vi - s * vj;
                v[(r, j)] = s * vi + c * vj;
            }
        }
        if !rotated {
            break;
        }
    }
    let norms = Vector3::new(w.column(0).norm(), w.column(1).norm(), w.column(2).norm());
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| norms[b].total_cmp(&norms[a]));
    let mut u = Matrix3::zeros();
    let mut vs = Matrix3::zeros();
    let mut s = Vector3::zeros();
    for (k, &i) in order.iter().enumerate() {
        s[k] = norms[i];
        vs.set_column(k, &v.column(i));
    }
    // u1, u2 from the rotated columns (completed when a column vanished),
    // u3 = u1 x u2; the sign of v3 keeps m = U diag(s) V^T.
    let w_sorted = |k: usize| w.column(order[k]).into_owned();
    let u1 = if s[0] > 0.0 {
        w_sorted(0) / s[0]
    } else {
        Vector3::x()
    };
    let u2 = if s[1] > 0.0 {
        w_sorted(1) / s[1]
    } else {
        any_orthogonal(&u1)
    };
    let u3 = u1.cross(&u2);
    if s[2] > 0.0 && w_sorted(2).dot(&u3) < 0.0 {
        let col = -vs.column(2);
        vs.set_column(2, &col);
    }
    u.set_column(0, &u1);
    u.set_column(1, &u2);
    u.set_column(2, &u3);
    if u.iter()
        .chain(vs.iter())
        .chain(s.iter())
        .all(|x| x.is_finite())
    {
        Some((u, s, vs))
    } else {
        None
    }
}

/// A unit vector orthogonal to the unit vector `a`.
fn any_orthogonal(a: &Vector3<f64>) -> Vector3<f64> {
    let axis = if a.x.abs() <= a.y.abs() && a.x.abs() <= a.z.abs() {
        Vector3::x()
    } else if a.y.abs() <= a.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    a.cross(&axis).normalize()
}

impl KruppaSvd {
    /// The SVD form of `f / |f|_F`; `None` when F is not finite or zero.
    pub(crate) fn new(f: &Matrix3<f64>) -> Option<Self> {
        if !f.iter().all(|v| v.is_finite()) {
            return None;
        }
        let norm = f.norm();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        let (u, s, v) = sorted_svd(&(f / norm))?;
        Some(Self {
            s1: s[0],
            s2: s[1],
            u1: u.column(0).into_owned(),
            u2: u.column(1).into_owned(),
            v1: v.column(0).into_owned(),
            v2: v.column(1).into_owned(),
        })
    }

    /// `(g1, g2)` and their gradients with respect to
    /// `x = (f1, u1, v1, f2, u2, v2)` (see [`crate::kruppa_residuals`]).
    pub(crate) fn eval_with_grad(&self, x: &[f64; 6]) -> ([f64; 2], [[f64; 6]; 2]) {
        let (f1, m1) = (x[0], Vector3::new(x[1], x[2], 1.0));
        let (f2, m2) = (x[3], Vector3::new(x[4], x[5], 1.0));
        let (a, da) = form_with_grad(&self.v1, &self.v1, f1, &m1);
        let (c, dc) = form_with_grad(&self.v1, &self.v2, f1, &m1);
        let (e, de) = form_with_grad(&self.v2, &self.v2, f1, &m1);
        let (b, db) = form_with_grad(&self.u1, &self.u2, f2, &m2);
        let (d, dd) = form_with_grad(&self.u2, &self.u2, f2, &m2);
        let (g, dg) = form_with_grad(&self.u1, &self.u1, f2, &m2);
        let (s1, s2) = (self.s1, self.s2);
        let g1 = s1 * a * b + s2 * c * d;
        let g2 = s1 * c * g + s2 * e * b;
        let mut j = [[0.0; 6]; 2];
        for k in 0..3 {
            j[0][k] = s1 * da[k] * b + s2 * dc[k] * d;
            j[0][3 + k] = s1 * a * db[k] + s2 * c * dd[k];
            j[1][k] = s1 * dc[k] * g + s2 * de[k] * b;
            j[1][3 + k] = s1 * c * dg[k] + s2 * e * db[k];
        }
        ([g1, g2], j)
    }

    /// The largest magnitude of the products `s1 (v1'w1v1)(u1'w2u2)`,
    /// `s2 (v1'w1v2)(u2'w2u2)`, `s1 (v1'w1v2)(u1'w2u1)`, `s2 (v2'w1v2)(u1'w2u2)`
    /// that make up g1 and g2 at `x`: the scale of their rounding error.
    pub(crate) fn term_magnitude(&self, x: &[f64; 6]) -> f64 {
        let (f1, m1) = (x[0], Vector3::new(x[1], x[2], 1.0));
        let (f2, m2) = (x[3], Vector3::new(x[4], x[5], 1.0));
        let a = form_with_grad(&self.v1, &self.v1, f1, &m1).0;
        let c = form_with_grad(&self.v1, &self.v2, f1, &m1).0;
        let e = form_with_grad(&self.v2, &self.v2, f1, &m1).0;
        let b = form_with_grad(&self.u1, &self.u2, f2, &m2).0;
        let d = form_with_grad(&self.u2, &self.u2, f2, &m2).0;
        let g = form_with_grad(&self.u1, &self.u1, f2, &m2).0;
        [
            self.s1 * a * b,
            self.s2 * c * d,
            self.s1 * c * g,
            self.s2 * e * b,
        ]
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    /// `(g1, g2)` at `x = (f1, u1, v1, f2, u2, v2)`.
    pub(crate) fn eval(&self, x: &[f64; 6]) -> [f64; 2] {
        self.eval_with_grad(x).0
    }

    /// `g1(p + C t)` and `g2(p + C t)` as bivariate quartics in
    /// `t = (t1, t2)`, where `C = [c1 c2]` (6x2).
    pub(crate) fn along_plane(
        &self,
        p: &[f64; 6],
        c1: &[f64; 6],
        c2: &[f64; 6],
    ) -> (Quartic2, Quartic2) {
        let lin = |k: usize| Lin2([p[k], c1[k], c2[k]]);
        let one = Lin2([1.0, 0.0, 0.0]);
        let (f1, u1, v1) = (lin(0), lin(1), lin(2));
        let (f2, u2, v2) = (lin(3), lin(4), lin(5));
        let f1sq = f1.mul(&f1);
        let f2sq = f2.mul(&f2);
        // a . m as a linear polynomial, m = (u, v, 1).
        let dot_m = |a: &Vector3<f64>, u: &Lin2, v: &Lin2| -> Lin2 {
            Lin2([
                a[0] * u.0[0] + a[1] * v.0[0] + a[2] * one.0[0],
                a[0] * u.0[1] + a[1] * v.0[1],
                a[0] * u.0[2] + a[1] * v.0[2],
            ])
        };
        // a' w b = f^2 (a0 b0 + a1 b1) + (a . m)(b . m).
        let form = |a: &Vector3<f64>, b: &Vector3<f64>, fsq: &Quad2, u: &Lin2, v: &Lin2| -> Quad2 {
            let am = dot_m(a, u, v);
            let bm = dot_m(b, u, v);
            fsq.combine(a[0] * b[0] + a[1] * b[1], &am.mul(&bm), 1.0)
        };
        let a = form(&self.v1, &self.v1, &f1sq, &u1, &v1);
        let c = form(&self.v1, &self.v2, &f1sq, &u1, &v1);
        let e = form(&self.v2, &self.v2, &f1sq, &u1, &v1);
        let b = form(&self.u1, &self.u2, &f2sq, &u2, &v2);
        let d = form(&self.u2, &self.u2, &f2sq, &u2, &v2);
        let g = form(&self.u1, &self.u1, &f2sq, &u2, &v2);
        let g1 = a.mul(&b).combine(self.s1, &c.mul(&d), self.s2);
        let g2 = c.mul(&g).combine(self.s1, &e.mul(&b), self.s2);
        (g1, g2)
    }
}

/// The bilinear form `a^T w b` of the dual image of the absolute conic
/// `w = K K^T = f^2 diag(1, 1, 0) + m m^T` (m = (u, v, 1)) and its gradient
/// with respect to (f, u, v).
fn form_with_grad(a: &Vector3<f64>, b: &Vector3<f64>, f: f64, m: &Vector3<f64>) -> (f64, [f64; 3]) {
    let ab = a[0] * b[0] + a[1] * b[1];
    let am = a.dot(m);
    let bm = b.dot(m);
    (
        f * f * ab + am * bm,
        [2.0 * f * ab, a[0] * bm + b[0] * am, a[1] * bm + b[1] * am],
    )
}

/// The two Kruppa constraints `(g1, g2)` of docs/method.md step 4 (Hartley &
/// Zisserman's ratio form in the SVD of F) at the cameras
/// `(f1, pp1)`, `(f2, pp2)`:
///
/// ```text
/// F / |F| = U diag(s1, s2, 0) V^T,  w = K K^T = [[f^2+u^2, uv, u], [uv, f^2+v^2, v], [u, v, 1]]
/// g1 = s1 (v1'w1v1)(u1'w2u2) + s2 (v1'w1v2)(u2'w2u2)
/// g2 = s1 (v1'w1v2)(u1'w2u1) + s2 (v2'w1v2)(u1'w2u2)
/// ```
///
/// (u_i columns of U: image 2; v_i columns of V: image 1). F is scaled to
/// unit Frobenius norm. `None` when F is not finite or zero.
pub fn kruppa_residuals(
    f: &Matrix3<f64>,
    f1: f64,
    pp1: [f64; 2],
    f2: f64,
    pp2: [f64; 2],
) -> Option<[f64; 2]> {
    let k = KruppaSvd::new(f)?;
    Some(k.eval(&[f1, pp1[0], pp1[1], f2, pp2[0], pp2[1]]))
}

/// The Kruppa residual of an estimate relative to the residual at the prior
/// `p = (f_prior, 0, 0, f_prior, 0, 0)`: `max_i |g_i(x)| / max(max_i
/// |g_i(p)|, 1e-8 T(p))` (the fixture's feasibility measure; a solver
/// success has it <= [`KRUPPA_TOLERANCE`]). `T(p)` is the largest magnitude
/// of the two products in each `g_i` at the prior, so the floor only matters
/// when the prior itself satisfies the constraints to rounding level.
/// `None` when F is not finite or zero.
pub fn relative_kruppa_residual(
    f: &Matrix3<f64>,
    estimate: &FocalEstimate,
    f_prior: f64,
) -> Option<f64> {
    let k = KruppaSvd::new(f)?;
    Some(relative_residual(&k, &estimate.unknowns(), f_prior))
}

/// [`relative_kruppa_residual`] with the SVD of F at hand.
pub(crate) fn relative_residual(k: &KruppaSvd, x: &[f64; 6], f_prior: f64) -> f64 {
    let g = k.eval(x);
    let p = [f_prior, 0.0, 0.0, f_prior, 0.0, 0.0];
    let g0 = k.eval(&p);
    let num = g[0].abs().max(g[1].abs());
    let den = g0[0]
        .abs()
        .max(g0[1].abs())
        .max(1e-8 * k.term_magnitude(&p));
    if num == 0.0 {
        0.0
    } else {
        num / den
    }
}

/// Tolerance of the final Kruppa check, relative to the prior's residual.
pub const KRUPPA_TOLERANCE: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_f() -> Matrix3<f64> {
        Matrix3::new(
            1.529013496527722e-06,
            -9.026893034015955e-06,
            -0.0009366451596395651,
            1.0831256830304013e-05,
            1.2161384819538267e-06,
            0.003930970879780438,
            0.0007421425474902622,
            -0.007744546089766246,
            -0.9999615698572981,
        )
    }

    /// Direct evaluation of the ratio-form constraints with explicit
    /// matrices w1, w2 (the naive reference).
    fn naive(f: &Matrix3<f64>, x: &[f64; 6]) -> [f64; 2] {
        let k = KruppaSvd::new(f).unwrap();
        let w = |f: f64, u: f64, v: f64| {
            Matrix3::new(f * f + u * u, u * v, u, u * v, f * f + v * v, v, u, v, 1.0)
        };
        let w1 = w(x[0], x[1], x[2]);
        let w2 = w(x[3], x[4], x[5]);
        let q = |a: &Vector3<f64>, m: &Matrix3<f64>, b: &Vector3<f64>| (a.transpose() * m * b)[0];
        [
            k.s1 * q(&k.v1, &w1, &k.v1) * q(&k.u1, &w2, &k.u2)
                + k.s2 * q(&k.v1, &w1, &k.v2) * q(&k.u2, &w2, &k.u2),
            k.s1 * q(&k.v1, &w1, &k.v2) * q(&k.u1, &w2, &k.u1)
                + k.s2 * q(&k.v2, &w1, &k.v2) * q(&k.u1, &w2, &k.u2),
        ]
    }

    #[test]
    fn sorted_svd_reconstructs_and_sorts() {
        let rank2 = {
            let a = Vector3::new(0.3, -1.0, 2.0);
            let b = Vector3::new(1e-3, 0.5, -0.25);
            a * Vector3::new(1.0, 0.2, -0.1).transpose()
                + b * Vector3::new(-0.3, 1.0, 0.7).transpose()
        };
        for m in [
            Matrix3::new(0.1, 2.0, -0.3, 0.5, 0.05, 1.2, -3.0, 0.2, 0.4),
            sample_f(),
            rank2,
            Matrix3::zeros(),
        ] {
            let (u, s, v) = sorted_svd(&m).unwrap();
            assert!(s[0] >= s[1] && s[1] >= s[2]);
            let back = u * Matrix3::from_diagonal(&s) * v.transpose();
            assert!(
                (back - m).norm() <= 1e-14 * m.norm().max(1e-300) + 1e-300,
                "{m}"
            );
            assert!((u.transpose() * u - Matrix3::identity()).norm() < 1e-14);
            assert!((v.transpose() * v - Matrix3::identity()).norm() < 1e-14);
        }
        // The null vector of a rank-2 matrix to working precision.
        let (_, _, v) = sorted_svd(&rank2).unwrap();
        assert!((rank2 * v.column(2)).norm() < 1e-15);
    }

    #[test]
    fn constraint_values_match_explicit_matrices() {
        let f = sample_f();
        let k = KruppaSvd::new(&f).unwrap();
        for x in [
            [1024.0, 0.0, 0.0, 1024.0, 0.0, 0.0],
            [800.0, 3.0, -2.0, 1300.0, -5.0, 7.5],
        ] {
            let got = k.eval(&x);
            let want = naive(&f, &x);
            for i in 0..2 {
                assert!((got[i] - want[i]).abs() <= 1e-12 * want[i].abs().max(1.0));
            }
        }
    }

    #[test]
    fn gradient_matches_central_differences() {
        let k = KruppaSvd::new(&sample_f()).unwrap();
        let x = [900.0, 2.0, -1.0, 1100.0, -3.0, 4.0];
        let (_, j) = k.eval_with_grad(&x);
        for c in 0..6 {
            let h = 1e-3;
            let mut xp = x;
            let mut xm = x;
            xp[c] += h;
            xm[c] -= h;
            let (gp, gm) = (k.eval(&xp), k.eval(&xm));
            for r in 0..2 {
                let num = (gp[r] - gm[r]) / (2.0 * h);
                assert!(
                    (num - j[r][c]).abs() <= 1e-6 * num.abs().max(1.0),
                    "d g{r} / d x{c}: {num} vs {}",
                    j[r][c]
                );
            }
        }
    }

    #[test]
    fn plane_expansion_matches_direct_evaluation() {
        let k = KruppaSvd::new(&sample_f()).unwrap();
        let p = [1024.0, 0.0, 0.0, 1024.0, 0.0, 0.0];
        let c1 = [300.0, 0.5, -0.2, 100.0, 0.1, 0.3];
        let c2 = [-50.0, 0.05, 0.4, 400.0, -0.6, 0.2];
        let (q1, q2) = k.along_plane(&p, &c1, &c2);
        for &(t1, t2) in &[(0.0, 0.0), (0.3, -0.7), (-1.2, 0.4), (2.0, 1.5)] {
            let mut x = [0.0; 6];
            for i in 0..6 {
                x[i] = p[i] + t1 * c1[i] + t2 * c2[i];
            }
            let g = k.eval(&x);
            assert!((q1.eval(t1, t2) - g[0]).abs() <= 1e-9 * g[0].abs().max(1.0));
            assert!((q2.eval(t1, t2) - g[1]).abs() <= 1e-9 * g[1].abs().max(1.0));
        }
    }
}
