//! Bivariate polynomials in `(t1, t2)` of total degree at most 4, the
//! form the two Kruppa constraints take on a step's plane of the robust
//! focal solver (docs/method.md step 4): products of linear and quadratic forms,
//! linear combinations, evaluation with the gradient and a magnitude bound.
//!
//! Everything here works on fixed-size arrays: no allocation per call.

/// A bivariate polynomial in (t1, t2) of total degree at most 1:
/// `c[0] + c[1] t1 + c[2] t2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lin2(pub [f64; 3]);

/// A bivariate polynomial of total degree at most 2; `c[i][j]` multiplies
/// `t1^i t2^j` (entries with `i + j > 2` stay zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Quad2(pub [[f64; 3]; 3]);

/// A bivariate polynomial of total degree at most 4; `c[i][j]` multiplies
/// `t1^i t2^j` (entries with `i + j > 4` stay zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Quartic2(pub [[f64; 5]; 5]);

impl Lin2 {
    /// The product of two linear polynomials.
    pub(crate) fn mul(&self, other: &Lin2) -> Quad2 {
        let a = &self.0;
        let b = &other.0;
        let mut q = [[0.0; 3]; 3];
        q[0][0] = a[0] * b[0];
        q[1][0] = a[1] * b[0] + a[0] * b[1];
        q[0][1] = a[2] * b[0] + a[0] * b[2];
        q[2][0] = a[1] * b[1];
        q[1][1] = a[1] * b[2] + a[2] * b[1];
        q[0][2] = a[2] * b[2];
        Quad2(q)
    }
}

impl Quad2 {
    /// `alpha * self + beta * other`.
    pub(crate) fn combine(&self, alpha: f64, other: &Quad2, beta: f64) -> Quad2 {
        let mut q = [[0.0; 3]; 3];
        for (i, row) in q.iter_mut().enumerate() {
            for (j, c) in row.iter_mut().enumerate() {
                *c = alpha * self.0[i][j] + beta * other.0[i][j];
            }
        }
        Quad2(q)
    }

    /// The product of two quadratics.
    pub(crate) fn mul(&self, other: &Quad2) -> Quartic2 {
        let mut r = [[0.0; 5]; 5];
        for i in 0..3 {
            for j in 0..3 - i {
                let a = self.0[i][j];
                if a == 0.0 {
                    continue;
                }
                for k in 0..3 {
                    for l in 0..3 - k {
                        r[i + k][j + l] += a * other.0[k][l];
                    }
                }
            }
        }
        Quartic2(r)
    }
}

impl Quartic2 {
    /// `alpha * self + beta * other`.
    pub(crate) fn combine(&self, alpha: f64, other: &Quartic2, beta: f64) -> Quartic2 {
        let mut q = [[0.0; 5]; 5];
        for (i, row) in q.iter_mut().enumerate() {
            for (j, c) in row.iter_mut().enumerate() {
                *c = alpha * self.0[i][j] + beta * other.0[i][j];
            }
        }
        Quartic2(q)
    }

    /// The largest absolute coefficient.
    pub(crate) fn max_abs_coef(&self) -> f64 {
        self.0
            .iter()
            .flat_map(|row| row.iter())
            .fold(0.0_f64, |m, c| m.max(c.abs()))
    }

    /// The polynomial divided by `s`.
    pub(crate) fn scaled(&self, s: f64) -> Quartic2 {
        self.combine(1.0 / s, self, 0.0)
    }

    /// Value, partial derivatives (d/dt1, d/dt2) and the magnitude bound
    /// `sum |c_ij| |t1|^i |t2|^j` at (t1, t2).
    pub(crate) fn eval_with_grad(&self, t1: f64, t2: f64) -> (f64, f64, f64, f64) {
        let mut p1 = [1.0; 5];
        let mut p2 = [1.0; 5];
        for k in 1..5 {
            p1[k] = p1[k - 1] * t1;
            p2[k] = p2[k - 1] * t2;
        }
        // Straight-line sums (fully unrolled): a zero coefficient adds an
        // exact zero, so skipping none of them changes no sum.
        let (mut v, mut d1, mut d2, mut mag) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..5 {
            for j in 0..5 - i {
                let c = self.0[i][j];
                let term = c * p1[i] * p2[j];
                v += term;
                mag += term.abs();
                if i > 0 {
                    d1 += c * (i as f64) * p1[i - 1] * p2[j];
                }
                if j > 0 {
                    d2 += c * (j as f64) * p1[i] * p2[j - 1];
                }
            }
        }
        (v, d1, d2, mag)
    }

    /// Value at (t1, t2).
    #[cfg(test)]
    pub(crate) fn eval(&self, t1: f64, t2: f64) -> f64 {
        self.eval_with_grad(t1, t2).0
    }

    /// Coefficients (ascending powers of t1) with t2 fixed to a real value.
    pub(crate) fn coefs_in_t1(&self, t2: f64) -> [f64; 5] {
        let mut out = [0.0; 5];
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = 0.0;
            for j in (0..5 - i).rev() {
                acc = acc * t2 + self.0[i][j];
            }
            *o = acc;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::lin;

    #[test]
    fn polynomial_products_match_pointwise_products() {
        let a = lin(0.3, -1.2, 0.7);
        let b = lin(-2.0, 0.5, 1.5);
        let c = lin(1.1, 0.2, -0.9);
        let d = lin(0.4, -0.6, 0.25);
        let q = a.mul(&b).mul(&c.mul(&d));
        let ev = |l: &Lin2, x: f64, y: f64| l.0[0] + l.0[1] * x + l.0[2] * y;
        for &(x, y) in &[(0.0, 0.0), (1.5, -0.3), (-2.2, 3.1), (0.7, 0.9)] {
            let want = ev(&a, x, y) * ev(&b, x, y) * ev(&c, x, y) * ev(&d, x, y);
            assert!((q.eval(x, y) - want).abs() <= 1e-12 * (1.0 + want.abs()));
            // Gradient against central differences.
            let (_, g1, g2, _) = q.eval_with_grad(x, y);
            let h = 1e-6;
            let n1 = (q.eval(x + h, y) - q.eval(x - h, y)) / (2.0 * h);
            let n2 = (q.eval(x, y + h) - q.eval(x, y - h)) / (2.0 * h);
            assert!((g1 - n1).abs() <= 1e-6 * (1.0 + n1.abs()));
            assert!((g2 - n2).abs() <= 1e-6 * (1.0 + n2.abs()));
        }
    }
}
