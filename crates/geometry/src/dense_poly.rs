//! Dense polynomials in three variables `(x, y, z)` with every exponent at
//! most 3, and 3 × 3 matrices of them: the naive expansion of the cubic
//! constraints of the five-point solver (`det E = 0` and the trace
//! constraint `2 E Eᵀ E − tr(E Eᵀ) E = 0`) into coefficient matrices, the
//! reference its fixed-size expansion (src/essential_system.rs) is tested
//! against.

use crate::poly::Equations;
use std::ops::{Add, Mul, Sub};

/// Largest exponent of any variable.
const MAX_EXP: usize = 3;
/// Number of stored coefficients, `(MAX_EXP + 1)³`.
const LEN: usize = (MAX_EXP + 1) * (MAX_EXP + 1) * (MAX_EXP + 1);

/// `Σ c[a, b, c] xᵃ yᵇ zᶜ` with `a, b, c <= 3`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Poly3([f64; LEN]);

/// Storage index of the monomial `xᵃ yᵇ zᶜ`.
#[inline(always)]
const fn index(a: usize, b: usize, c: usize) -> usize {
    (a * (MAX_EXP + 1) + b) * (MAX_EXP + 1) + c
}

impl Poly3 {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Self([0.0; LEN])
    }

    /// `cx·x + cy·y + cz·z + c0`.
    pub fn linear(cx: f64, cy: f64, cz: f64, c0: f64) -> Self {
        let mut p = Self::zero();
        p.0[index(1, 0, 0)] = cx;
        p.0[index(0, 1, 0)] = cy;
        p.0[index(0, 0, 1)] = cz;
        p.0[index(0, 0, 0)] = c0;
        p
    }

    /// The coefficient of `xᵃ yᵇ zᶜ` (0 for exponents above 3).
    pub fn coeff(&self, a: usize, b: usize, c: usize) -> f64 {
        if a > MAX_EXP || b > MAX_EXP || c > MAX_EXP {
            return 0.0;
        }
        self.0[index(a, b, c)]
    }

    /// `s · self`.
    pub fn scale(&self, s: f64) -> Self {
        Self(self.0.map(|v| v * s))
    }

    /// The product with `z`: every exponent of `z` raised by one (terms of
    /// `z`-degree 3 would leave the storage; callers never have them).
    pub fn times_z(&self) -> Self {
        let mut out = Self::zero();
        for a in 0..=MAX_EXP {
            for b in 0..=MAX_EXP {
                for c in 0..MAX_EXP {
                    out.0[index(a, b, c + 1)] = self.0[index(a, b, c)];
                }
            }
        }
        out
    }

    /// The value at `(x, y, z)`, its gradient, and `Σ |term|` (the scale
    /// against which the value's rounding error is judged).
    pub fn eval(&self, x: f64, y: f64, z: f64) -> (f64, [f64; 3], f64) {
        let powers = |t: f64| [1.0, t, t * t, t * t * t];
        let (px, py, pz) = (powers(x), powers(y), powers(z));
        let (mut value, mut grad, mut magnitude) = (0.0, [0.0; 3], 0.0);
        for (a, b, c, v) in self.terms() {
            let term = v * px[a] * py[b] * pz[c];
            value += term;
            magnitude += term.abs();
            if a > 0 {
                grad[0] += v * a as f64 * px[a - 1] * py[b] * pz[c];
            }
            if b > 0 {
                grad[1] += v * b as f64 * px[a] * py[b - 1] * pz[c];
            }
            if c > 0 {
                grad[2] += v * c as f64 * px[a] * py[b] * pz[c - 1];
            }
        }
        (value, grad, magnitude)
    }

    /// The non-zero terms as `(a, b, c, coefficient)`.
    fn terms(&self) -> impl Iterator<Item = (usize, usize, usize, f64)> + '_ {
        self.0
            .iter()
            .enumerate()
            .filter(|(_, v)| **v != 0.0)
            .map(|(i, &v)| {
                let side = MAX_EXP + 1;
                (i / (side * side), (i / side) % side, i % side, v)
            })
    }
}

impl Add for Poly3 {
    type Output = Poly3;
    fn add(mut self, other: Poly3) -> Poly3 {
        self.0.iter_mut().zip(other.0).for_each(|(a, b)| *a += b);
        self
    }
}

impl Sub for Poly3 {
    type Output = Poly3;
    fn sub(mut self, other: Poly3) -> Poly3 {
        self.0.iter_mut().zip(other.0).for_each(|(a, b)| *a -= b);
        self
    }
}

impl Mul for Poly3 {
    type Output = Poly3;
    /// The product; callers only multiply polynomials whose product
    /// keeps every exponent at most 3 (a term beyond would be dropped).
    fn mul(self, other: Poly3) -> Poly3 {
        let mut out = Poly3::zero();
        let mut right = [(0, 0, 0, 0.0); LEN];
        let mut count = 0;
        for term in other.terms() {
            right[count] = term;
            count += 1;
        }
        for (a, b, c, u) in self.terms() {
            for &(d, e, f, v) in &right[..count] {
                let (i, j, k) = (a + d, b + e, c + f);
                if i <= MAX_EXP && j <= MAX_EXP && k <= MAX_EXP {
                    out.0[index(i, j, k)] += u * v;
                }
            }
        }
        out
    }
}

/// A 3 × 3 matrix of polynomials, `m[row][col]`.
pub(crate) type PolyMatrix = [[Poly3; 3]; 3];

/// `a · b`.
pub(crate) fn mat_mul(a: &PolyMatrix, b: &PolyMatrix) -> PolyMatrix {
    let mut out = [[Poly3::zero(); 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, entry) in row.iter_mut().enumerate() {
            *entry = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    out
}

/// `aᵀ`.
pub(crate) fn transpose(a: &PolyMatrix) -> PolyMatrix {
    let mut out = *a;
    for (r, row) in out.iter_mut().enumerate() {
        for (c, entry) in row.iter_mut().enumerate() {
            *entry = a[c][r];
        }
    }
    out
}

/// `det a`, by the cofactor expansion along the first row.
pub(crate) fn det(a: &PolyMatrix) -> Poly3 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// The nine entries (row-major) of `2 P A − tr(P) A`. With `P = E Eᵀ`,
/// `A = E` it is the essential-matrix trace constraint
/// `2 E Eᵀ E − tr(E Eᵀ) E = 0` (Nistér 2004, Eq. 5).
pub(crate) fn trace_constraint(p: &PolyMatrix, a: &PolyMatrix) -> [Poly3; 9] {
    let product = mat_mul(p, a);
    let trace = p[0][0] + p[1][1] + p[2][2];
    let mut out = [Poly3::zero(); 9];
    for r in 0..3 {
        for c in 0..3 {
            out[3 * r + c] = product[r][c].scale(2.0) - trace * a[r][c];
        }
    }
    out
}

impl Equations for [Poly3; 10] {
    fn evaluate(&self, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10] {
        self.map(|e| e.eval(p[0], p[1], p[2]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(p: &Poly3, x: f64, y: f64, z: f64) -> f64 {
        p.terms()
            .map(|(a, b, c, v)| v * x.powi(a as i32) * y.powi(b as i32) * z.powi(c as i32))
            .sum()
    }

    #[test]
    fn product_and_determinant_evaluate_like_numbers() {
        let p = Poly3::linear(1.5, -2.0, 0.5, 3.0);
        let q = Poly3::linear(-0.25, 1.0, 2.0, -1.0);
        let (x, y, z) = (0.3, -1.7, 2.2);
        let pq = p * q;
        assert!((eval(&pq, x, y, z) - eval(&p, x, y, z) * eval(&q, x, y, z)).abs() < 1e-12);
        let m: PolyMatrix = [0, 1, 2].map(|r| {
            [0, 1, 2].map(|c| {
                let k = (3 * r + c) as f64;
                Poly3::linear(k.sin(), k.cos(), (k * 0.7).sin(), k * 0.1 - 0.4)
            })
        });
        let numeric = nalgebra::Matrix3::from_fn(|r, c| eval(&m[r][c], x, y, z)).determinant();
        assert!((eval(&det(&m), x, y, z) - numeric).abs() < 1e-12);
        let t = transpose(&m);
        assert_eq!(t[0][2], m[2][0]);
        assert!((eval(&p.times_z(), x, y, z) - z * eval(&p, x, y, z)).abs() < 1e-12);
    }
}
