//! The resultant of two bivariate quartics with respect to t1, a
//! polynomial of degree <= 16 in t2 (the hidden-variable elimination of the
//! robust focal solver's step, docs/method.md step 4), interpolated at the 32nd
//! roots of unity from complex 4x4 Bezout determinants evaluated several
//! nodes at a time.

use nalgebra::Complex;

use crate::bivariate::Quartic2;
use crate::simd::{self, Simd};

type C64 = Complex<f64>;

/// Number of interpolation nodes on the circle (a power of two > 2 * 16).
const NODES: usize = 32;
/// Degree bound of the resultant of two bivariate quartics (Bezout: 4 * 4).
pub(crate) const RES_DEGREE: usize = 16;
/// Lanes of the inverse DFT in [`resultant_in_t2`]: the 17 coefficients
/// padded to a multiple of four (the padding lanes are ignored).
const LANES: usize = 20;

/// Nodes evaluated side by side in [`node_values`]: few enough that one
/// chunk's intermediate values stay in registers and the first-level cache.
const CHUNK: usize = 4;

/// One complex number per lane, in structure-of-arrays form.
#[derive(Clone, Copy)]
struct LaneComplex<const L: usize> {
    re: [f64; L],
    im: [f64; L],
}

impl<const L: usize> LaneComplex<L> {
    const ZERO: Self = Self {
        re: [0.0; L],
        im: [0.0; L],
    };

    /// `a * b - c * d` lane by lane, each product and the difference rounded
    /// as `Complex<f64>` arithmetic rounds them.
    #[inline(always)]
    fn mul_sub_mul(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        let mut out = Self::ZERO;
        for l in 0..L {
            let xr = a.re[l] * b.re[l] - a.im[l] * b.im[l];
            let xi = a.re[l] * b.im[l] + a.im[l] * b.re[l];
            let yr = c.re[l] * d.re[l] - c.im[l] * d.im[l];
            let yi = c.re[l] * d.im[l] + c.im[l] * d.re[l];
            out.re[l] = xr - yr;
            out.im[l] = xi - yi;
        }
        out
    }

    /// `a + b` lane by lane.
    #[inline(always)]
    fn add(a: &Self, b: &Self) -> Self {
        let mut out = *a;
        for l in 0..L {
            out.re[l] += b.re[l];
            out.im[l] += b.im[l];
        }
        out
    }
}

/// Coefficients (ascending powers of t2, length 17) of `det Bezout(P, Q)(t2)`,
/// the resultant of P and Q with respect to t1, obtained by evaluating it at
/// the 32nd roots of unity and applying the inverse DFT (exact for a
/// polynomial of degree <= 16; the real polynomial's values at conjugate
/// nodes are conjugate, so only 17 evaluations are needed).
///
/// At each node `z`, `P(., z)` and `Q(., z)` are univariate quartics in t1
/// with complex coefficients `a`, `b` (ascending powers); their 4x4 Bezout
/// matrix
/// `(P(x)Q(y) - P(y)Q(x)) / (x - y) = sum_{i,j} B_ij x^i y^j`,
/// `B_ij = sum_{q = max(0, i+j+1-4)}^{min(i,j)} (a_{i+j+1-q} b_q - a_q b_{i+j+1-q})`,
/// has their resultant as determinant (up to sign), computed by Laplace
/// expansion in 2x2 minors ([`det4_at_lanes`]: no pivoting and no division,
/// so [`CHUNK`] nodes are evaluated side by side, one per lane, with the
/// widest vector instructions present: [`Simd`]),
/// with the kernel compiled for `simd` ([`crate::simd`]), which the CPU
/// must support.
pub(crate) fn resultant_in_t2(simd: Simd, p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    simd::resultant_in_t2(simd, p, q)
}

/// [`resultant_in_t2`] in the build of the caller: the kernel that
/// [`crate::simd`] compiles once per instruction set.
#[inline(always)]
pub(crate) fn resultant_in_t2_lanes(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    let mut values = [C64::new(0.0, 0.0); NODES];
    for first in (0..=NODES / 2).step_by(CHUNK) {
        let det = node_values::<CHUNK>(p, q, first);
        for (l, k) in (first..=NODES / 2).take(CHUNK).enumerate() {
            let v = C64::new(det.re[l], det.im[l]);
            values[k] = v;
            if k != 0 && k != NODES / 2 {
                values[NODES - k] = v.conj();
            }
        }
    }
    let mut acc = [0.0; LANES];
    for (k, v) in values.iter().enumerate() {
        // Real part of (1/N) sum_k values[k] omega^{-jk}, all j at once.
        let (w_re, w_im) = (&IDFT_COS[k], &IDFT_SIN[k]);
        for j in 0..LANES {
            acc[j] += v.re * w_re[j] + v.im * w_im[j];
        }
    }
    let mut coefs = [0.0; RES_DEGREE + 1];
    for (c, a) in coefs.iter_mut().zip(acc) {
        *c = a / NODES as f64;
    }
    coefs
}

/// The Bezout determinant of P and Q at the nodes `omega^first …
/// omega^(first + L - 1)` (lanes past node 16 hold node 0 and are ignored).
#[inline(always)]
fn node_values<const L: usize>(p: &Quartic2, q: &Quartic2, first: usize) -> LaneComplex<L> {
    let mut z = LaneComplex::<L>::ZERO;
    for l in 0..L {
        let k = if first + l <= NODES / 2 { first + l } else { 0 };
        z.re[l] = IDFT_COS[1][k];
        z.im[l] = IDFT_SIN[1][k];
    }
    let a = coefs_in_t1_at_lanes(p, &z);
    let b = coefs_in_t1_at_lanes(q, &z);
    // m_pq = a_p b_q - a_q b_p for p > q.
    let m = |pp: usize, qq: usize| LaneComplex::mul_sub_mul(&a[pp], &b[qq], &a[qq], &b[pp]);
    let (m10, m20, m30, m40) = (m(1, 0), m(2, 0), m(3, 0), m(4, 0));
    let (m21, m31, m41, m32, m42, m43) = (m(2, 1), m(3, 1), m(4, 1), m(3, 2), m(4, 2), m(4, 3));
    // B_ij = sum_q m_{i+j+1-q, q}, q from max(0, i+j+1-4) to i, summed from
    // zero in increasing q; the matrix is symmetric.
    let sum = |terms: &[&LaneComplex<L>]| {
        terms
            .iter()
            .fold(LaneComplex::ZERO, |s, t| LaneComplex::add(&s, t))
    };
    let b00 = sum(&[&m10]);
    let b01 = sum(&[&m20]);
    let b02 = sum(&[&m30]);
    let b03 = sum(&[&m40]);
    let b11 = sum(&[&m30, &m21]);
    let b12 = sum(&[&m40, &m31]);
    let b13 = sum(&[&m41]);
    let b22 = sum(&[&m41, &m32]);
    let b23 = sum(&[&m42]);
    let b33 = sum(&[&m43]);
    let bezout = [
        [b00, b01, b02, b03],
        [b01, b11, b12, b13],
        [b02, b12, b22, b23],
        [b03, b13, b23, b33],
    ];
    det4_at_lanes(&bezout)
}

/// The coefficients (ascending powers of t1) of `P(., z)` at every lane's
/// `z`, by Horner in t2 over the coefficients of each power of t1.
#[inline(always)]
fn coefs_in_t1_at_lanes<const L: usize>(p: &Quartic2, z: &LaneComplex<L>) -> [LaneComplex<L>; 5] {
    let mut out = [LaneComplex::ZERO; 5];
    for (i, o) in out.iter_mut().enumerate() {
        for j in (0..5 - i).rev() {
            let c = p.0[i][j];
            for l in 0..L {
                let (ar, ai) = (o.re[l], o.im[l]);
                o.re[l] = (ar * z.re[l] - ai * z.im[l]) + c;
                o.im[l] = ar * z.im[l] + ai * z.re[l];
            }
        }
    }
    out
}

/// The determinant of a complex 4x4 matrix at every lane, by Laplace
/// expansion in complementary 2x2 minors of rows (0, 1) and rows (2, 3):
/// `det M = sum_{a < b} (-1)^(a + b + 1) M01[a, b] M23[complement of a, b]`.
// Lane loops are written by index so that every lane takes the same
// operations side by side.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn det4_at_lanes<const L: usize>(m: &[[LaneComplex<L>; 4]; 4]) -> LaneComplex<L> {
    // The six column pairs, their complements and signs.
    const PAIRS: [(usize, usize, usize, usize, f64); 6] = [
        (0, 1, 2, 3, 1.0),
        (0, 2, 1, 3, -1.0),
        (0, 3, 1, 2, 1.0),
        (1, 2, 0, 3, 1.0),
        (1, 3, 0, 2, -1.0),
        (2, 3, 0, 1, 1.0),
    ];
    let mut det = LaneComplex::ZERO;
    for (a, b, c, d, sign) in PAIRS {
        let top = LaneComplex::mul_sub_mul(&m[0][a], &m[1][b], &m[0][b], &m[1][a]);
        let bottom = LaneComplex::mul_sub_mul(&m[2][c], &m[3][d], &m[2][d], &m[3][c]);
        for l in 0..L {
            let re = top.re[l] * bottom.re[l] - top.im[l] * bottom.im[l];
            let im = top.re[l] * bottom.im[l] + top.im[l] * bottom.re[l];
            det.re[l] += sign * re;
            det.im[l] += sign * im;
        }
    }
    det
}

/// `cos(2 pi k / 32)` for k = 0..=8.
const COS_32: [f64; 9] = [
    1.0,
    0.9807852804032304,
    0.9238795325112867,
    0.8314696123025452,
    std::f64::consts::FRAC_1_SQRT_2,
    0.5555702330196023,
    0.38268343236508984,
    0.19509032201612833,
    0.0,
];

/// `cos(2 pi k / 32)` for k = 0..32, from [`COS_32`] by symmetry.
const UNIT_ROOTS_COS: [f64; NODES] = {
    let mut t = [0.0; NODES];
    let mut k = 0;
    while k < NODES {
        t[k] = match k {
            0..=8 => COS_32[k],
            9..=16 => -COS_32[16 - k],
            17..=24 => -COS_32[k - 16],
            _ => COS_32[32 - k],
        };
        k += 1;
    }
    t
};

/// `omega^{jk}` for the node `k` (row) and the coefficient `j` (lane), with
/// `omega = exp(2 pi i / 32)`: real parts here, imaginary parts in
/// [`IDFT_SIN`]; lanes past the 17 coefficients are zero. Row 1 holds the
/// nodes themselves.
const IDFT_COS: [[f64; LANES]; NODES] = idft_table(0);
/// Imaginary parts of the table of [`IDFT_COS`].
const IDFT_SIN: [[f64; LANES]; NODES] = idft_table(NODES - 8);

/// `cos(2 pi (jk + shift) / 32)` for node `k` and lane `j <= 16`
/// (`sin(x) = cos(x - pi/2)`, a shift of 24 = -8 nodes).
const fn idft_table(shift: usize) -> [[f64; LANES]; NODES] {
    let mut t = [[0.0; LANES]; NODES];
    let mut k = 0;
    while k < NODES {
        let mut j = 0;
        while j <= RES_DEGREE {
            t[k][j] = UNIT_ROOTS_COS[(j * k + shift) % NODES];
            j += 1;
        }
        k += 1;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{intersection, product_of_lines, LINES_P, LINES_Q};

    /// The resultant's value at one node `z` computed independently of
    /// [`resultant_in_t2`]: the coefficients of `P(., z)` in t1 and the
    /// Bezout determinant by Gaussian elimination with partial pivoting,
    /// with `Complex<f64>` arithmetic.
    fn bezout_det_at(p: &Quartic2, q: &Quartic2, z: C64) -> C64 {
        bezout_det(&coefs_in_t1_complex(p, z), &coefs_in_t1_complex(q, z))
    }

    fn coefs_in_t1_complex(p: &Quartic2, z: C64) -> [C64; 5] {
        let mut out = [C64::new(0.0, 0.0); 5];
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = C64::new(0.0, 0.0);
            for j in (0..5 - i).rev() {
                acc = acc * z + p.0[i][j];
            }
            *o = acc;
        }
        out
    }

    /// Determinant of the 4x4 Bezout matrix of two univariate quartics (complex
    /// coefficients, ascending powers): it equals, up to sign, their resultant.
    ///
    /// `(P(x)Q(y) - P(y)Q(x)) / (x - y) = sum_{i,j} B_ij x^i y^j` with
    /// `B_ij = sum_{q = max(0, i+j+1-4)}^{min(i,j)} (a_{i+j+1-q} b_q - a_q b_{i+j+1-q})`.
    fn bezout_det(a: &[C64; 5], b: &[C64; 5]) -> C64 {
        let n: usize = 4;
        // m_pq = a_p b_q - a_q b_p for p > q.
        let mut mpq = [[C64::new(0.0, 0.0); 5]; 5];
        for p in 1..5 {
            for q in 0..p {
                mpq[p][q] = a[p] * b[q] - a[q] * b[p];
            }
        }
        let mut m = [[C64::new(0.0, 0.0); 4]; 4];
        for i in 0..4usize {
            for j in i..4usize {
                let lo = (i + j + 1).saturating_sub(n);
                let mut s = C64::new(0.0, 0.0);
                for q in lo..=i {
                    s += mpq[i + j + 1 - q][q];
                }
                // The Bezout matrix is symmetric.
                m[i][j] = s;
                m[j][i] = s;
            }
        }
        det4_complex(m)
    }

    /// Determinant of a complex 4x4 matrix by Gaussian elimination with partial
    /// pivoting.
    fn det4_complex(mut m: [[C64; 4]; 4]) -> C64 {
        let mut det = C64::new(1.0, 0.0);
        for col in 0..4 {
            let mut piv = col;
            let mut best = m[col][col].norm_sqr();
            for (r, row) in m.iter().enumerate().skip(col + 1) {
                let v = row[col].norm_sqr();
                if v > best {
                    best = v;
                    piv = r;
                }
            }
            if best == 0.0 {
                return C64::new(0.0, 0.0);
            }
            if piv != col {
                m.swap(piv, col);
                det = -det;
            }
            let d = m[col][col];
            det *= d;
            let inv = C64::new(1.0, 0.0) / d;
            for r in col + 1..4 {
                let factor = m[r][col] * inv;
                if factor.norm_sqr() == 0.0 {
                    continue;
                }
                let pivot_row = m[col];
                for (entry, v) in m[r].iter_mut().zip(pivot_row.iter()).skip(col) {
                    *entry -= factor * v;
                }
            }
        }
        det
    }

    /// `exp(2 pi i k / 32)` from [`UNIT_ROOTS_COS`] (`sin(x) = cos(x - pi/2)`).
    fn unit_root(k: usize) -> C64 {
        C64::new(
            UNIT_ROOTS_COS[k % NODES],
            UNIT_ROOTS_COS[(k + NODES - 8) % NODES],
        )
    }

    /// The resultant with one node evaluated at a time.
    fn resultant_in_t2_one_node_at_a_time(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
        let mut omega = [C64::new(0.0, 0.0); NODES];
        for (k, w) in omega.iter_mut().enumerate() {
            *w = unit_root(k);
        }
        let mut values = [C64::new(0.0, 0.0); NODES];
        for k in 0..=NODES / 2 {
            let z = omega[k];
            let v = bezout_det_at(p, q, z);
            values[k] = v;
            if k != 0 && k != NODES / 2 {
                values[NODES - k] = v.conj();
            }
        }
        let mut coefs = [0.0; RES_DEGREE + 1];
        for (j, c) in coefs.iter_mut().enumerate() {
            // Real part of (1/N) sum_k values[k] omega^{-jk}.
            let mut acc = 0.0;
            for (k, v) in values.iter().enumerate() {
                let w = omega[(j * k) % NODES];
                acc += v.re * w.re + v.im * w.im;
            }
            *c = acc / NODES as f64;
        }
        coefs
    }

    /// The node-parallel resultant (Laplace-expanded determinants) agrees
    /// with the one-node-at-a-time computation by Gaussian elimination with
    /// partial pivoting to rounding level, on random quartics, on ones with
    /// zero coefficients, and on a pair whose Bezout matrix is singular at
    /// every node (P = Q, resultant zero).
    #[test]
    fn resultant_agrees_with_pivoted_elimination_one_node_at_a_time() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut random_quartic = |zeros: f64| {
            let mut c = [[0.0; 5]; 5];
            for (i, row) in c.iter_mut().enumerate() {
                for v in row.iter_mut().take(5 - i) {
                    if !rng.gen_bool(zeros) {
                        *v = rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-6..6));
                    }
                }
            }
            Quartic2(c)
        };
        let mut pairs = Vec::new();
        for zeros in [0.0, 0.3, 0.7] {
            for _ in 0..200 {
                pairs.push((random_quartic(zeros), random_quartic(zeros)));
            }
        }
        let p = product_of_lines(&LINES_P);
        pairs.push((p, p));
        pairs.push((p, product_of_lines(&LINES_Q)));
        let largest = |c: &[f64]| c.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (p, q) in &pairs {
            let fast = resultant_in_t2(Simd::detect(), p, q);
            let reference = resultant_in_t2_one_node_at_a_time(p, q);
            // Rounding level: relative to the resultant, or for a resultant
            // that vanishes, to the size of the Bezout determinant's terms.
            let terms = (largest(p.0.as_flattened()) * largest(q.0.as_flattened())).powi(4);
            let scale = largest(&reference).max(1e-10 * terms);
            for (a, b) in fast.iter().zip(&reference) {
                assert!((a - b).abs() <= 1e-9 * scale, "{fast:?}\n{reference:?}");
            }
        }
    }

    /// Packing the unconverged roots into 4 or 8 lanes changes no bit of
    /// any sweep: random polynomials of degree 5 to 16, swept from the

    #[test]
    fn unit_roots_and_idft_tables_match_trigonometry() {
        for k in 0..NODES {
            let ang = std::f64::consts::TAU * k as f64 / NODES as f64;
            let z = unit_root(k);
            assert!(
                (z.re - ang.cos()).abs() < 1e-15 && (z.im - ang.sin()).abs() < 1e-15,
                "k = {k}"
            );
            for j in 0..LANES {
                let (c, s) = if j <= RES_DEGREE {
                    let ang = std::f64::consts::TAU * ((j * k) % NODES) as f64 / NODES as f64;
                    (ang.cos(), ang.sin())
                } else {
                    (0.0, 0.0)
                };
                assert!(
                    (IDFT_COS[k][j] - c).abs() < 1e-15 && (IDFT_SIN[k][j] - s).abs() < 1e-15,
                    "k = {k}, j = {j}"
                );
            }
        }
    }

    #[test]
    fn resultant_vanishes_exactly_at_common_roots() {
        // P = product of 4 lines, Q = product of 4 other lines: the 16
        // intersection points are the solutions; the resultant in t2 must
        // vanish at each intersection's t2.
        let (lp, lq) = (LINES_P, LINES_Q);
        let p = product_of_lines(&lp);
        let q = product_of_lines(&lq);
        let res = resultant_in_t2(Simd::detect(), &p, &q);
        let scale = res.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        for a in &lp {
            for b in &lq {
                // Intersection of a0 + a1 t1 + a2 t2 = 0 and b0 + b1 t1 + b2 t2 = 0.
                let [_, t2] = intersection(a, b);
                let v: f64 = res.iter().rev().fold(0.0, |acc, c| acc * t2 + c);
                let mag: f64 = res
                    .iter()
                    .rev()
                    .fold(0.0, |acc, c| acc * t2.abs() + c.abs());
                assert!(v.abs() <= 1e-10 * mag.max(scale), "t2 = {t2}: {v} vs {mag}");
            }
        }
    }
}
