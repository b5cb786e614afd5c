//! Small polynomial toolkit for the robust focal solver: bivariate
//! polynomials of total degree at most 4, the univariate Aberth–Ehrlich root
//! finder, and the computation of all real solutions of two bivariate
//! quartics by hidden-variable elimination (Bezout resultant).
//!
//! Everything here works on fixed-size arrays: no allocation per call.

use nalgebra::Complex;

type C64 = Complex<f64>;

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
    fn coefs_in_t1(&self, t2: f64) -> [f64; 5] {
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

/// Number of interpolation nodes on the circle (a power of two > 2 * 16).
const NODES: usize = 32;
/// Degree bound of the resultant of two bivariate quartics (Bezout: 4 * 4).
const RES_DEGREE: usize = 16;
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
/// widest vector instructions present: [`Simd`]).
fn resultant_in_t2(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    resultant_in_t2_with(Simd::detect(), p, q)
}

/// [`resultant_in_t2`] with the kernel compiled for `simd`, which the CPU
/// must support (as [`Simd::detect`] and [`Simd::supported`] ensure).
fn resultant_in_t2_with(simd: Simd, p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    match simd {
        // SAFETY: `simd` is a level the CPU supports.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => unsafe { resultant_in_t2_avx512(p, q) },
        // SAFETY: as above.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => unsafe { resultant_in_t2_avx2(p, q) },
        _ => resultant_in_t2_lanes(p, q),
    }
}

/// [`resultant_in_t2_lanes`] compiled for AVX-512 (see [`Simd`]).
///
/// # Safety
/// The CPU must support [`Simd::Avx512`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
unsafe fn resultant_in_t2_avx512(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    resultant_in_t2_lanes(p, q)
}

/// [`resultant_in_t2_lanes`] compiled for AVX2 (see [`Simd`]).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn resultant_in_t2_avx2(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    resultant_in_t2_lanes(p, q)
}

#[inline(always)]
fn resultant_in_t2_lanes(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
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

/// Maximum degree handled by [`aberth_roots`].
pub(crate) const MAX_DEGREE: usize = RES_DEGREE;

/// All complex roots of the real polynomial `sum_k coefs[k] z^k` by the
/// Aberth–Ehrlich simultaneous iteration. Leading coefficients that are
/// exactly zero are dropped; roots at zero are deflated exactly. Writes the
/// roots into `out` and returns their number (the degree).
///
/// The iteration starts from `warm` when it holds as many distinct finite
/// approximations as the degree (e.g. the roots of a nearby polynomial),
/// else from Bini's Newton-polygon approximations; a warm start that does
/// not converge is retried from the Newton polygon. Roots that miss the
/// backward-error test after the iteration budget are still returned (as
/// approximations); callers polish and verify them.
#[inline(always)]
pub(crate) fn aberth_roots(
    coefs: &[f64],
    out: &mut [C64; MAX_DEGREE],
    warm: Option<&[C64]>,
) -> usize {
    // Trim exact zero leading coefficients.
    let mut n = coefs.len();
    while n > 0 && coefs[n - 1] == 0.0 {
        n -= 1;
    }
    if n <= 1 {
        return 0;
    }
    let mut start = 0;
    let mut count = 0;
    // Exact roots at zero.
    while start < n - 1 && coefs[start] == 0.0 {
        out[count] = C64::new(0.0, 0.0);
        count += 1;
        start += 1;
    }
    let c = &coefs[start..n];
    let deg = c.len() - 1;
    if deg == 0 {
        return count;
    }
    debug_assert!(count + deg <= MAX_DEGREE);
    let roots = &mut out[count..count + deg];
    let usable_warm = warm.filter(|w| {
        w.len() == deg
            && w.iter().all(|z| z.re.is_finite() && z.im.is_finite())
            && (0..deg).all(|i| (i + 1..deg).all(|j| w[i] != w[j]))
    });
    if let Some(w) = usable_warm {
        roots.copy_from_slice(w);
        if aberth_iterate(c, roots, 30) {
            return count + deg;
        }
    }
    init_newton_polygon(c, roots);
    aberth_iterate(c, roots, 100);
    count + deg
}

/// Aberth–Ehrlich iterations on `roots` for the polynomial with ascending
/// coefficients `c` (nonzero ends): whole-set (Jacobi) sweeps, written so
/// that the compiler vectorises them across roots, while more than
/// [`JACOBI_MIN_MOVING`] roots are still moving, then one-root-at-a-time
/// (Gauss–Seidel) sweeps of [`aberth_gauss_seidel`] for the last few.
/// Returns true when every approximation met the backward-error test
/// `|p(z)| <= 4 eps sum |c_k| |z|^k`.
#[inline(always)]
fn aberth_iterate(c: &[f64], roots: &mut [C64], max_iter: usize) -> bool {
    let deg = c.len() - 1;
    if deg <= JACOBI_MIN_MOVING + 1 {
        return aberth_gauss_seidel(c, roots, max_iter);
    }
    let mut state = AberthState::new(c, roots);
    for _ in 0..max_iter {
        let moving = state.jacobi_sweep_dispatch();
        if moving == 0 {
            state.store(roots);
            return true;
        }
        if moving <= JACOBI_MIN_MOVING {
            break;
        }
    }
    state.store(roots);
    aberth_gauss_seidel(c, roots, max_iter)
}

/// Below this many unconverged roots, [`aberth_iterate`] switches from
/// whole-set sweeps to one-root updates.
const JACOBI_MIN_MOVING: usize = 3;

/// Coefficients and root approximations of [`aberth_iterate`] in
/// structure-of-arrays form, padded to [`MAX_DEGREE`] lanes.
struct AberthState {
    deg: usize,
    c: [f64; MAX_DEGREE + 1],
    abs_c: [f64; MAX_DEGREE + 1],
    re: [f64; MAX_DEGREE],
    im: [f64; MAX_DEGREE],
    converged: [bool; MAX_DEGREE],
    simd: Simd,
}

impl AberthState {
    fn new(c: &[f64], roots: &[C64]) -> Self {
        let deg = c.len() - 1;
        let mut state = Self {
            deg,
            c: [0.0; MAX_DEGREE + 1],
            abs_c: [0.0; MAX_DEGREE + 1],
            re: [0.0; MAX_DEGREE],
            im: [0.0; MAX_DEGREE],
            converged: [false; MAX_DEGREE],
            simd: Simd::detect(),
        };
        for (k, &v) in c.iter().enumerate() {
            state.c[k] = v;
            state.abs_c[k] = v.abs();
        }
        for (i, z) in roots.iter().enumerate().take(deg) {
            state.re[i] = z.re;
            state.im[i] = z.im;
        }
        state
    }

    fn store(&self, roots: &mut [C64]) {
        for (i, z) in roots.iter_mut().enumerate().take(self.deg) {
            *z = C64::new(self.re[i], self.im[i]);
        }
    }

    /// [`AberthState::jacobi_sweep`] compiled for `self.simd`.
    fn jacobi_sweep_dispatch(&mut self) -> usize {
        match self.simd {
            // SAFETY: `simd` is a level the CPU supports.
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512 => unsafe { self.jacobi_sweep_avx512() },
            // SAFETY: as above.
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2 => unsafe { self.jacobi_sweep_avx2() },
            _ => self.jacobi_sweep(),
        }
    }

    /// [`AberthState::jacobi_sweep`] compiled for AVX-512 (see [`Simd`]).
    ///
    /// # Safety
    /// The CPU must support [`Simd::Avx512`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512dq,avx512vl")]
    unsafe fn jacobi_sweep_avx512(&mut self) -> usize {
        self.jacobi_sweep()
    }

    /// [`AberthState::jacobi_sweep`] compiled for AVX2 (see [`Simd`]).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn jacobi_sweep_avx2(&mut self) -> usize {
        self.jacobi_sweep()
    }

    /// One Aberth step for every unconverged root from the same current
    /// approximations: `z_i <- z_i - w_i`, `w_i = r_i / (1 - r_i S_i)` with
    /// `r_i = p(z_i) / p'(z_i)` and `S_i = sum_{j != i} 1 / (z_i - z_j)`.
    /// Roots that pass the backward-error test are marked and stay fixed;
    /// returns how many did not.
    ///
    /// Only the unconverged roots are evaluated, packed into 4, 8 or 16
    /// lanes, so that the late sweeps, where a few roots are still moving,
    /// cost a fraction of the first ones.
    #[inline(always)]
    fn jacobi_sweep(&mut self) -> usize {
        let (active, n) = self.unconverged();
        match n {
            0 => 0,
            1..=4 => self.sweep_lanes::<4>(&active, n),
            5..=8 => self.sweep_lanes::<8>(&active, n),
            _ => self.sweep_lanes::<MAX_DEGREE>(&active, n),
        }
    }

    /// [`AberthState::jacobi_sweep`] with every unconverged root in 16
    /// lanes, however few they are (the reference for the packing).
    #[cfg(test)]
    fn jacobi_sweep_wide(&mut self) -> usize {
        let (active, n) = self.unconverged();
        if n == 0 {
            return 0;
        }
        self.sweep_lanes::<MAX_DEGREE>(&active, n)
    }

    /// The indices of the roots that have not converged, in increasing
    /// order (the first `n` entries), and `n`.
    #[inline(always)]
    fn unconverged(&self) -> ([usize; MAX_DEGREE], usize) {
        let mut active = [0usize; MAX_DEGREE];
        let mut n = 0;
        for i in 0..self.deg {
            if !self.converged[i] {
                active[n] = i;
                n += 1;
            }
        }
        (active, n)
    }

    /// [`AberthState::jacobi_sweep`] on the `n` roots `active[..n]`, held
    /// in `L >= n` lanes (the spare lanes repeat the last root and are
    /// ignored).
    #[inline(always)]
    fn sweep_lanes<const L: usize>(&mut self, active: &[usize; MAX_DEGREE], n: usize) -> usize {
        let deg = self.deg;
        let tol = 4.0 * f64::EPSILON;
        let (re, im) = (self.re, self.im);
        let mut zr = [0.0; L];
        let mut zi = [0.0; L];
        for a in 0..L {
            let i = active[a.min(n - 1)];
            zr[a] = re[i];
            zi[a] = im[i];
        }
        // Horner for p, p' and the bound sum |c_k| |z|^k at every lane.
        let mut pr = [self.c[deg]; L];
        let mut pi = [0.0; L];
        let mut dr = [0.0; L];
        let mut di = [0.0; L];
        let mut bound = [self.abs_c[deg]; L];
        let mut az = [0.0; L];
        for a in 0..L {
            az[a] = (zr[a] * zr[a] + zi[a] * zi[a]).sqrt();
        }
        for k in (0..deg).rev() {
            let (ck, ak) = (self.c[k], self.abs_c[k]);
            for a in 0..L {
                let ndr = dr[a] * zr[a] - di[a] * zi[a] + pr[a];
                let ndi = dr[a] * zi[a] + di[a] * zr[a] + pi[a];
                let npr = pr[a] * zr[a] - pi[a] * zi[a] + ck;
                let npi = pr[a] * zi[a] + pi[a] * zr[a];
                dr[a] = ndr;
                di[a] = ndi;
                pr[a] = npr;
                pi[a] = npi;
                bound[a] = bound[a] * az[a] + ak;
            }
        }
        // S_i over the other approximations (z_i itself adds nothing).
        let mut sr = [0.0; L];
        let mut si = [0.0; L];
        for j in 0..deg {
            let (rj, ij) = (re[j], im[j]);
            for a in 0..L {
                let ar = zr[a] - rj;
                let ai = zi[a] - ij;
                let d2 = ar * ar + ai * ai;
                let inv = if d2 > 0.0 { 1.0 / d2 } else { 0.0 };
                sr[a] += ar * inv;
                si[a] -= ai * inv;
            }
        }
        // The Aberth correction at every lane (lanes whose root passes the
        // test compute one too; it is not used).
        let mut passed = [false; L];
        let mut next_re = [0.0; L];
        let mut next_im = [0.0; L];
        for a in 0..L {
            let pv2 = pr[a] * pr[a] + pi[a] * pi[a];
            let lim = tol * bound[a];
            passed[a] = pv2 <= lim * lim;
            let dp2 = dr[a] * dr[a] + di[a] * di[a];
            // ratio = p / p'; at a stationary point of p, a nudge.
            let nudge = 1e-8 * (1.0 + az[a]);
            let regular = dp2 > 0.0;
            let rr_q = (pr[a] * dr[a] + pi[a] * di[a]) / dp2;
            let ri_q = (pi[a] * dr[a] - pr[a] * di[a]) / dp2;
            let rr = if regular { rr_q } else { nudge };
            let ri = if regular { ri_q } else { nudge };
            // w = ratio / (1 - ratio * sum)
            let (er, ei) = (1.0 - (rr * sr[a] - ri * si[a]), -(rr * si[a] + ri * sr[a]));
            let e2 = er * er + ei * ei;
            let wr_q = (rr * er + ri * ei) / e2;
            let wi_q = (ri * er - rr * ei) / e2;
            let (wr, wi) = if e2 > 0.0 { (wr_q, wi_q) } else { (rr, ri) };
            next_re[a] = zr[a] - wr;
            next_im[a] = zi[a] - wi;
        }
        let mut moving = 0;
        for a in 0..n {
            let i = active[a];
            if passed[a] {
                self.converged[i] = true;
                continue;
            }
            moving += 1;
            let (nr, ni) = (next_re[a], next_im[a]);
            if nr.is_finite() && ni.is_finite() {
                self.re[i] = nr;
                self.im[i] = ni;
            } else {
                self.converged[i] = true;
            }
        }
        moving
    }
}

/// The instruction sets the lane-parallel kernels ([`resultant_in_t2`] and
/// the Aberth sweeps) are compiled for, widest first. Each build performs
/// the same IEEE operations in the same order (the compiler fuses no
/// multiply-add and reorders no sum), so every level gives the same bits;
/// the wider ones only hold more lanes per instruction and, with AVX-512,
/// keep the 16 lanes' sums in 32 registers instead of spilling them. With
/// AVX-512 the whole robust solve is compiled for it (`robust::solve_avx512`);
/// the step's functions here are `#[inline(always)]` so that they are
/// compiled into that build rather than called in their baseline one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Simd {
    /// AVX-512 F, DQ and VL.
    Avx512,
    /// AVX2.
    Avx2,
    /// Whatever the target's baseline is (SSE2 on x86-64).
    Portable,
}

impl Simd {
    /// The widest level this CPU supports.
    pub(crate) fn detect() -> Self {
        Self::supported()[0]
    }

    /// The levels this CPU supports, widest first (`Portable` always).
    fn supported() -> [Self; 3] {
        let mut levels = [Self::Portable; 3];
        let mut n = 0;
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                levels[n] = Self::Avx512;
                n += 1;
            }
            if has!("avx2") {
                levels[n] = Self::Avx2;
                n += 1;
            }
        }
        levels[n] = Self::Portable;
        levels
    }
}

/// Aberth–Ehrlich iterations (Gauss–Seidel updates) on `roots` for the
/// polynomial with ascending coefficients `c` (nonzero ends); returns true
/// when every approximation met the backward-error test
/// `|p(z)| <= 4 eps sum |c_k| |z|^k`.
#[inline(always)]
fn aberth_gauss_seidel(c: &[f64], roots: &mut [C64], max_iter: usize) -> bool {
    let deg = c.len() - 1;
    let mut abs_c = [0.0; MAX_DEGREE + 1];
    for (k, v) in c.iter().enumerate() {
        abs_c[k] = v.abs();
    }
    let mut converged = [false; MAX_DEGREE];
    let tol = 4.0 * f64::EPSILON;
    for _ in 0..max_iter {
        let mut all = true;
        for i in 0..deg {
            if converged[i] {
                continue;
            }
            let z = roots[i];
            // Horner for p, p' and the bound sum |c_k| |z|^k.
            let az = z.norm_sqr().sqrt();
            let (mut pr, mut pi) = (c[deg], 0.0);
            let (mut dr, mut di) = (0.0, 0.0);
            let mut bound = abs_c[deg];
            for k in (0..deg).rev() {
                let ndr = dr * z.re - di * z.im + pr;
                let ndi = dr * z.im + di * z.re + pi;
                dr = ndr;
                di = ndi;
                let npr = pr * z.re - pi * z.im + c[k];
                let npi = pr * z.im + pi * z.re;
                pr = npr;
                pi = npi;
                bound = bound * az + abs_c[k];
            }
            let pv2 = pr * pr + pi * pi;
            let lim = tol * bound;
            if pv2 <= lim * lim {
                converged[i] = true;
                continue;
            }
            all = false;
            // sum_{j != i} 1 / (z - z_j)
            let (mut sr, mut si) = (0.0, 0.0);
            for (j, zj) in roots.iter().enumerate() {
                if j != i {
                    let (ar, ai) = (z.re - zj.re, z.im - zj.im);
                    let d2 = ar * ar + ai * ai;
                    if d2 > 0.0 {
                        let inv = 1.0 / d2;
                        sr += ar * inv;
                        si -= ai * inv;
                    }
                }
            }
            let dp2 = dr * dr + di * di;
            // ratio = p / p'
            let (rr, ri) = if dp2 > 0.0 {
                ((pr * dr + pi * di) / dp2, (pi * dr - pr * di) / dp2)
            } else {
                // Stationary point of p: nudge the approximation.
                (1e-8 * (1.0 + az), 1e-8 * (1.0 + az))
            };
            // w = ratio / (1 - ratio * sum)
            let (er, ei) = (1.0 - (rr * sr - ri * si), -(rr * si + ri * sr));
            let e2 = er * er + ei * ei;
            let (wr, wi) = if e2 > 0.0 {
                ((rr * er + ri * ei) / e2, (ri * er - rr * ei) / e2)
            } else {
                (rr, ri)
            };
            let next = C64::new(z.re - wr, z.im - wi);
            if next.re.is_finite() && next.im.is_finite() {
                roots[i] = next;
            } else {
                converged[i] = true;
            }
        }
        if all {
            return true;
        }
    }
    false
}

/// Bini's initial approximations: for each edge of the upper convex hull of
/// the points (k, log|c_k|), place as many points as the edge is long on the
/// circle of the radius the edge's slope gives, with rotated angles.
#[inline(always)]
fn init_newton_polygon(c: &[f64], roots: &mut [C64]) {
    let deg = c.len() - 1;
    let mut hull = [0usize; MAX_DEGREE + 1];
    let mut h = 0usize;
    let mut logs = [f64::NEG_INFINITY; MAX_DEGREE + 1];
    for (l, ck) in logs.iter_mut().zip(c) {
        if *ck != 0.0 {
            *l = ck.abs().ln();
        }
    }
    let logc = |k: usize| logs[k];
    for (k, &ck) in c.iter().enumerate() {
        if ck == 0.0 {
            continue;
        }
        while h >= 2 {
            let (i0, i1) = (hull[h - 2], hull[h - 1]);
            // Keep the hull concave (upper hull): drop i1 if it lies on or
            // below the segment i0 -> k.
            let lhs = (logc(i1) - logc(i0)) * (k - i0) as f64;
            let rhs = (logc(k) - logc(i0)) * (i1 - i0) as f64;
            if lhs <= rhs {
                h -= 1;
            } else {
                break;
            }
        }
        hull[h] = k;
        h += 1;
    }
    let sigma = 0.7;
    let mut idx = 0usize;
    for e in 0..h.saturating_sub(1) {
        let (k0, k1) = (hull[e], hull[e + 1]);
        let m = k1 - k0;
        let radius = ((logc(k0) - logc(k1)) / m as f64).exp();
        let radius = if radius.is_finite() && radius > 0.0 {
            radius
        } else {
            1.0
        };
        for j in 0..m {
            let ang =
                std::f64::consts::TAU * (j as f64 / m as f64 + k0 as f64 / deg as f64) + sigma;
            roots[idx] = C64::from_polar(radius, ang);
            idx += 1;
        }
    }
    // Hull always spans 0..=deg because c[0] != 0 and c[deg] != 0.
    debug_assert_eq!(idx, deg);
}

/// Resultant roots closer than this (relative to `1 + |t2|`) count as a
/// cluster, whose common roots t1 [`min_l1_real_solution`] finds from the
/// real roots of the first quartic rather than from a null vector.
const ISOLATION: f64 = 1e-1;

/// The smallest diagonal cofactor, relative to the cube of the largest
/// Bezout matrix entry, at which [`bezout_null_t1`] trusts the null vector.
const NULL_VECTOR_TOLERANCE: f64 = 1e-6;

/// The common root t1 of `P(., t2)` and `Q(., t2)` from the null vector
/// `(1, t1, t1^2, t1^3)` of their real 4x4 Bezout matrix at `t2` (a column
/// of its adjugate, the one of the largest diagonal cofactor). `None` when
/// that cofactor is below [`NULL_VECTOR_TOLERANCE`] (no simple common root:
/// two common roots, or a near-double root of the resultant) or the ratio is
/// not finite.
// The symmetric matrix is filled by index pairs (i, j), j >= i.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn bezout_null_t1(p: &Quartic2, q: &Quartic2, t2: f64) -> Option<f64> {
    let a = p.coefs_in_t1(t2);
    let b = q.coefs_in_t1(t2);
    let mut m = [[0.0; 4]; 4];
    for i in 0..4usize {
        for j in i..4usize {
            let lo = (i + j + 1).saturating_sub(4);
            let mut s = 0.0;
            for qq in lo..=i {
                let pp = i + j + 1 - qq;
                s += a[pp] * b[qq] - a[qq] * b[pp];
            }
            m[i][j] = s;
            m[j][i] = s;
        }
    }
    // Cofactor C_ik: signed determinant of m without row i and column k.
    let cofactor = |i: usize, k: usize| -> f64 {
        let mut r = [0usize; 3];
        let mut c = [0usize; 3];
        let (mut nr, mut nc) = (0, 0);
        for x in 0..4 {
            if x != i {
                r[nr] = x;
                nr += 1;
            }
            if x != k {
                c[nc] = x;
                nc += 1;
            }
        }
        let e = |u: usize, v: usize| m[r[u]][c[v]];
        let det = e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
            - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
            + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0));
        if (i + k) % 2 == 0 {
            det
        } else {
            -det
        }
    };
    let diagonal = [0, 1, 2, 3].map(|x| cofactor(x, x).abs());
    let k = (0..4)
        .max_by(|&x, &y| diagonal[x].total_cmp(&diagonal[y]))
        .unwrap_or(0);
    // A rank-deficient adjugate (two common roots, or a near-double root
    // of the resultant) does not determine t1.
    let size = m.iter().flatten().fold(0.0_f64, |acc, v| acc.max(v.abs()));
    if diagonal[k].is_nan() || diagonal[k] <= NULL_VECTOR_TOLERANCE * size * size * size {
        return None;
    }
    let v = [0, 1, 2, 3].map(|i| cofactor(i, k));
    let t1 = if v[0].abs() >= v[3].abs() {
        v[1] / v[0]
    } else {
        v[3] / v[2]
    };
    t1.is_finite().then_some(t1)
}

/// A real solution (t1, t2) of `P = Q = 0`.
pub(crate) type Solution = [f64; 2];

/// Newton's method on the 2x2 system `P = Q = 0` from `t`. Returns the
/// polished point when it converged to a real solution: both residuals below
/// `1e-10` times their magnitude bound `sum |c_ij| |t1|^i |t2|^j`.
#[inline(always)]
pub(crate) fn polish(p: &Quartic2, q: &Quartic2, mut t: [f64; 2]) -> Option<Solution> {
    for _ in 0..12 {
        let (pv, p1, p2, pm) = p.eval_with_grad(t[0], t[1]);
        let (qv, q1, q2, qm) = q.eval_with_grad(t[0], t[1]);
        if pv.abs() <= 1e-15 * pm && qv.abs() <= 1e-15 * qm {
            break;
        }
        let det = p1 * q2 - p2 * q1;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let d1 = (pv * q2 - p2 * qv) / det;
        let d2 = (p1 * qv - pv * q1) / det;
        t[0] -= d1;
        t[1] -= d2;
        if !(t[0].is_finite() && t[1].is_finite()) {
            return None;
        }
        let size = 1.0 + t[0].abs() + t[1].abs();
        if d1.abs() + d2.abs() <= 1e-14 * size {
            break;
        }
    }
    let (pv, _, _, pm) = p.eval_with_grad(t[0], t[1]);
    let (qv, _, _, qm) = q.eval_with_grad(t[0], t[1]);
    if pv.abs() <= 1e-10 * pm && qv.abs() <= 1e-10 * qm {
        Some(t)
    } else {
        None
    }
}

/// Roots of the previous resultant, reused as the starting point of the
/// next root-finding (see [`min_l1_real_solution`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RootCache {
    roots: [C64; MAX_DEGREE],
    len: usize,
}

impl Default for RootCache {
    fn default() -> Self {
        Self {
            roots: [C64::new(0.0, 0.0); MAX_DEGREE],
            len: 0,
        }
    }
}

/// The real solution `t` of `P(t1, t2) = Q(t1, t2) = 0` minimising
/// `|(M t)_1| + |(M t)_2|` for the 2x2 matrix `m` (row-major), or `None`
/// when no real solution is found.
///
/// Method: hidden-variable elimination of t1 (the Bezout resultant, a
/// polynomial of degree <= 16 in t2), all its complex roots by
/// Aberth–Ehrlich (started from `cache`, the roots of the previous call,
/// when it has the right degree; the new roots are stored back), and for
/// every root close to the real axis the common root t1 of `P(., t2)` and
/// `Q(., t2)` from the null vector of their Bezout matrix
/// ([`bezout_null_t1`]), or when that does not polish to a solution, the
/// real roots t1 of `P(., t2)` at which `Q` nearly vanishes; each pair is
/// polished by Newton's method on the 2x2 system and kept only when it
/// solves both equations. Candidates are
/// visited in increasing `|t2|`; since `|Mt|_1 >= sigma_min(M) |t|_2 >=
/// sigma_min(M) |t2|`, the search stops once no remaining candidate can
/// improve on the best.
#[inline(always)]
pub(crate) fn min_l1_real_solution(
    p: &Quartic2,
    q: &Quartic2,
    m: [[f64; 2]; 2],
    cache: &mut RootCache,
) -> Option<Solution> {
    let res = resultant_in_t2(p, q);
    let scale = res.iter().fold(0.0_f64, |acc, c| acc.max(c.abs()));
    if !(scale.is_finite() && scale > 1e-300) {
        return None;
    }
    // Drop leading coefficients that are negligible: they only create roots
    // near infinity.
    let mut n = res.len();
    while n > 1 && res[n - 1].abs() <= 1e-14 * scale {
        n -= 1;
    }
    let mut roots = [C64::new(0.0, 0.0); MAX_DEGREE];
    let warm = (cache.len > 0).then(|| &cache.roots[..cache.len]);
    let nr = aberth_roots(&res[..n], &mut roots, warm);
    cache.roots = roots;
    cache.len = nr;

    // Candidate t2 values: roots near the real axis, by increasing |t2|.
    // Each with whether it is an isolated root: no other root within
    // ISOLATION of it, so that one common root t1 belongs to it.
    let mut cand = [(0.0f64, false); MAX_DEGREE];
    let mut nc = 0;
    for (i, z) in roots.iter().enumerate().take(nr) {
        if z.im.abs() <= 1e-2 * (1.0 + z.re.abs()) {
            let reach = ISOLATION * (1.0 + z.norm_sqr().sqrt());
            let isolated = roots[..nr]
                .iter()
                .enumerate()
                .all(|(j, w)| j == i || (z - w).norm_sqr() > reach * reach);
            cand[nc] = (z.re, isolated);
            nc += 1;
        }
    }
    let cand = &mut cand[..nc];
    cand.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));

    let sigma_min = smallest_singular_value(m);
    let objective = |s: &Solution| {
        (m[0][0] * s[0] + m[0][1] * s[1]).abs() + (m[1][0] * s[0] + m[1][1] * s[1]).abs()
    };
    let mut best: Option<(f64, Solution)> = None;
    let mut t1_roots = [C64::new(0.0, 0.0); MAX_DEGREE];
    for &(t2, isolated) in cand.iter() {
        if let Some((b, _)) = best {
            if sigma_min * t2.abs() > 1.01 * b {
                break;
            }
        }
        // At an isolated root, the common root from the Bezout matrix's null
        // vector, when it polishes to a solution; else every real root of
        // P(., t2).
        if let Some(s) = isolated
            .then(|| bezout_null_t1(p, q, t2))
            .flatten()
            .and_then(|t1| polish(p, q, [t1, t2]))
        {
            keep_better(&mut best, objective(&s), s);
            continue;
        }
        // The t1 candidates: real roots of P(., t2), or of Q(., t2) when P
        // vanishes identically there.
        let (first, other) = if p.coefs_in_t1(t2).iter().any(|&c| c != 0.0) {
            (p, q)
        } else {
            (q, p)
        };
        let k = aberth_roots(&first.coefs_in_t1(t2), &mut t1_roots, None);
        // Relative size of the other polynomial at each real candidate: at a
        // common root it is at the level of the error of t2.
        let mut picked = [(0.0f64, f64::INFINITY); 4];
        let mut np = 0;
        for z in t1_roots.iter().take(k) {
            if z.im.abs() > 1e-2 * (1.0 + z.re.abs()) || np == picked.len() {
                continue;
            }
            let (v, _, _, mag) = other.eval_with_grad(z.re, t2);
            picked[np] = (z.re, if mag > 0.0 { v.abs() / mag } else { 0.0 });
            np += 1;
        }
        let min_rel = picked[..np]
            .iter()
            .fold(f64::INFINITY, |a, &(_, r)| a.min(r));
        for &(t1, rel) in &picked[..np] {
            if rel > 1e-3 && rel > min_rel {
                continue;
            }
            if let Some(s) = polish(p, q, [t1, t2]) {
                keep_better(&mut best, objective(&s), s);
            }
        }
    }
    best.map(|(_, s)| s)
}

/// Replaces `best` by `(norm, s)` when there is none yet or `norm` is
/// strictly smaller (so the first of equal candidates stays).
fn keep_better(best: &mut Option<(f64, Solution)>, norm: f64, s: Solution) {
    if best.map_or(true, |(b, _)| norm < b) {
        *best = Some((norm, s));
    }
}

/// The smallest singular value of a 2x2 matrix.
fn smallest_singular_value(m: [[f64; 2]; 2]) -> f64 {
    let (a, b, c, d) = (m[0][0], m[0][1], m[1][0], m[1][1]);
    let s1 = (a + d).hypot(c - b);
    let s2 = (a - d).hypot(c + b);
    0.5 * (s1 - s2).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lin(c0: f64, c1: f64, c2: f64) -> Lin2 {
        Lin2([c0, c1, c2])
    }

    /// Product of four lines a_k + b_k t1 + c_k t2.
    fn product_of_lines(lines: &[[f64; 3]; 4]) -> Quartic2 {
        let q1 = lin(lines[0][0], lines[0][1], lines[0][2]).mul(&lin(
            lines[1][0],
            lines[1][1],
            lines[1][2],
        ));
        let q2 = lin(lines[2][0], lines[2][1], lines[2][2]).mul(&lin(
            lines[3][0],
            lines[3][1],
            lines[3][2],
        ));
        q1.mul(&q2)
    }

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
            let fast = resultant_in_t2(p, q);
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
    /// Newton-polygon start until every root has converged.
    #[test]
    fn packed_sweeps_equal_wide_sweeps_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut packed_sweeps = 0;
        for _ in 0..300 {
            let deg = rng.gen_range(5..=MAX_DEGREE);
            let c: Vec<f64> = (0..=deg)
                .map(|_| rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-3..3)))
                .collect();
            let mut start = [C64::new(0.0, 0.0); MAX_DEGREE];
            init_newton_polygon(&c, &mut start[..deg]);
            let mut packed = AberthState::new(&c, &start[..deg]);
            let mut wide = AberthState::new(&c, &start[..deg]);
            for _ in 0..100 {
                packed_sweeps += usize::from(packed.converged.iter().filter(|&&v| !v).count() <= 8);
                let moving = packed.jacobi_sweep();
                assert_eq!(moving, wide.jacobi_sweep_wide());
                assert_eq!(packed.converged, wide.converged);
                for i in 0..deg {
                    assert_eq!(packed.re[i].to_bits(), wide.re[i].to_bits());
                    assert_eq!(packed.im[i].to_bits(), wide.im[i].to_bits());
                }
                if moving == 0 {
                    break;
                }
            }
        }
        assert!(packed_sweeps > 100, "only {packed_sweeps} packed sweeps");
    }

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
    fn aberth_finds_known_roots() {
        // (z - 1)(z + 2)(z - 0.5)(z^2 + 1)(z - 30) expanded.
        let roots_true = [1.0, -2.0, 0.5, 30.0];
        let mut poly = vec![1.0];
        let mul = |p: &Vec<f64>, r: &[f64]| -> Vec<f64> {
            // multiply p by polynomial r (ascending)
            let mut out = vec![0.0; p.len() + r.len() - 1];
            for (i, a) in p.iter().enumerate() {
                for (j, b) in r.iter().enumerate() {
                    out[i + j] += a * b;
                }
            }
            out
        };
        for r in roots_true {
            poly = mul(&poly, &[-r, 1.0]);
        }
        poly = mul(&poly, &[1.0, 0.0, 1.0]);
        let mut out = [C64::new(0.0, 0.0); MAX_DEGREE];
        let n = aberth_roots(&poly, &mut out, None);
        assert_eq!(n, 6);
        for r in roots_true {
            assert!(
                out[..n]
                    .iter()
                    .any(|z| (z - C64::new(r, 0.0)).norm() < 1e-9),
                "missing root {r}: {:?}",
                &out[..n]
            );
        }
        for im in [1.0, -1.0] {
            assert!(out[..n]
                .iter()
                .any(|z| (z - C64::new(0.0, im)).norm() < 1e-9));
        }
    }

    /// Ascending coefficients of `prod (z - r)` over real roots and
    /// conjugate pairs `a ± bi`.
    fn poly_from_roots(real: &[f64], pairs: &[(f64, f64)]) -> Vec<f64> {
        let mut poly = vec![1.0];
        let mut mul = |r: &[f64]| {
            let mut out = vec![0.0; poly.len() + r.len() - 1];
            for (i, a) in poly.iter().enumerate() {
                for (j, b) in r.iter().enumerate() {
                    out[i + j] += a * b;
                }
            }
            poly = out;
        };
        for &r in real {
            mul(&[-r, 1.0]);
        }
        for &(a, b) in pairs {
            mul(&[a * a + b * b, -2.0 * a, 1.0]);
        }
        poly
    }

    #[test]
    fn aberth_finds_all_sixteen_roots_cold_and_warm() {
        let real = [-3.0, -1.5, -0.7, -0.2, 0.3, 0.9, 1.6, 2.5];
        let pairs = [(0.5, 1.0), (-1.0, 0.4), (2.0, 0.8), (-0.3, 2.2)];
        let poly = poly_from_roots(&real, &pairs);
        let mut want: Vec<C64> = real.iter().map(|&r| C64::new(r, 0.0)).collect();
        for &(a, b) in &pairs {
            want.push(C64::new(a, b));
            want.push(C64::new(a, -b));
        }
        let check = |out: &[C64]| {
            for w in &want {
                assert!(
                    out.iter().any(|z| (z - w).norm() < 1e-8),
                    "missing root {w}: {out:?}"
                );
            }
        };
        let mut cold = [C64::new(0.0, 0.0); MAX_DEGREE];
        assert_eq!(aberth_roots(&poly, &mut cold, None), 16);
        check(&cold);
        // Warm start from the roots of a nearby polynomial.
        let nearby: Vec<f64> = poly
            .iter()
            .enumerate()
            .map(|(k, c)| c * (1.0 + 1e-3 * ((k as f64) * 0.9).sin()))
            .collect();
        let mut warm_start = [C64::new(0.0, 0.0); MAX_DEGREE];
        aberth_roots(&nearby, &mut warm_start, None);
        let mut warm = [C64::new(0.0, 0.0); MAX_DEGREE];
        assert_eq!(aberth_roots(&poly, &mut warm, Some(&warm_start[..16])), 16);
        check(&warm);
    }

    /// Every build of the sweeps and of the resultant that this CPU can run
    /// computes exactly what the portable one does.
    #[test]
    fn simd_builds_compute_the_same_bits() {
        let poly = poly_from_roots(
            &[-2.0, -0.5, 0.1, 0.8, 1.7, 3.0],
            &[(0.4, 0.9), (-1.2, 0.3)],
        );
        let mut start = [C64::new(0.0, 0.0); MAX_DEGREE];
        init_newton_polygon(&poly, &mut start[..10]);
        let p = product_of_lines(&LINES_P);
        let q = product_of_lines(&LINES_Q);
        let res_portable = resultant_in_t2_with(Simd::Portable, &p, &q);
        for simd in Simd::supported() {
            let res = resultant_in_t2_with(simd, &p, &q);
            assert_eq!(
                res.map(f64::to_bits),
                res_portable.map(f64::to_bits),
                "{simd:?}"
            );
            let mut portable = AberthState::new(&poly, &start[..10]);
            portable.simd = Simd::Portable;
            let mut vector = AberthState::new(&poly, &start[..10]);
            vector.simd = simd;
            for _ in 0..6 {
                let a = portable.jacobi_sweep_dispatch();
                let b = vector.jacobi_sweep_dispatch();
                assert_eq!(a, b);
                for i in 0..10 {
                    assert_eq!(portable.re[i].to_bits(), vector.re[i].to_bits(), "{simd:?}");
                    assert_eq!(portable.im[i].to_bits(), vector.im[i].to_bits(), "{simd:?}");
                }
            }
        }
    }

    #[test]
    fn aberth_deflates_zero_roots_and_trims_leading_zeros() {
        // z^2 (z - 3), written with two trailing zero coefficients.
        let poly = [0.0, 0.0, -3.0, 1.0, 0.0, 0.0];
        let mut out = [C64::new(0.0, 0.0); MAX_DEGREE];
        let n = aberth_roots(&poly, &mut out, None);
        assert_eq!(n, 3);
        assert_eq!(out[0], C64::new(0.0, 0.0));
        assert_eq!(out[1], C64::new(0.0, 0.0));
        assert!((out[2] - C64::new(3.0, 0.0)).norm() < 1e-12);
    }

    /// Two sets of four lines `a0 + a1 t1 + a2 t2 = 0` whose products are
    /// P and Q: their 16 intersections are the real solutions.
    const LINES_P: [[f64; 3]; 4] = [
        [0.3, 1.0, 0.2],
        [-0.5, 1.0, -0.4],
        [0.1, 0.8, 1.0],
        [-0.9, -0.3, 1.0],
    ];
    const LINES_Q: [[f64; 3]; 4] = [
        [0.2, 1.0, 0.9],
        [0.7, -1.0, 0.35],
        [-0.4, 0.15, 1.0],
        [0.6, 0.5, -1.0],
    ];

    #[test]
    fn resultant_vanishes_exactly_at_common_roots() {
        // P = product of 4 lines, Q = product of 4 other lines: the 16
        // intersection points are the solutions; the resultant in t2 must
        // vanish at each intersection's t2.
        let (lp, lq) = (LINES_P, LINES_Q);
        let p = product_of_lines(&lp);
        let q = product_of_lines(&lq);
        let res = resultant_in_t2(&p, &q);
        let scale = res.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        for a in &lp {
            for b in &lq {
                // Intersection of a0 + a1 t1 + a2 t2 = 0 and b0 + b1 t1 + b2 t2 = 0.
                let det = a[1] * b[2] - a[2] * b[1];
                let t2 = (a[1] * (-b[0]) - (-a[0]) * b[1]) / det;
                let v: f64 = res.iter().rev().fold(0.0, |acc, c| acc * t2 + c);
                let mag: f64 = res
                    .iter()
                    .rev()
                    .fold(0.0, |acc, c| acc * t2.abs() + c.abs());
                assert!(v.abs() <= 1e-10 * mag.max(scale), "t2 = {t2}: {v} vs {mag}");
            }
        }
    }

    #[test]
    fn finds_the_smallest_of_sixteen_real_solutions() {
        let (lp, lq) = (LINES_P, LINES_Q);
        let p = product_of_lines(&lp);
        let q = product_of_lines(&lq);
        let mut cache = RootCache::default();
        for m in [
            [[1.0, 0.0], [0.0, 1.0]],
            [[1.0, 0.0], [0.0, 10.0]],
            [[7.0, 0.0], [0.0, 0.5]],
            [[1.0, 0.7], [-0.2, 1.5]],
            [[0.3, -2.0], [1.0, 1.0]],
        ] {
            // Naive reference: all 16 intersections, minimum |M t|_1.
            let norm = |t: [f64; 2]| {
                (m[0][0] * t[0] + m[0][1] * t[1]).abs() + (m[1][0] * t[0] + m[1][1] * t[1]).abs()
            };
            let mut best = (f64::INFINITY, [0.0; 2]);
            for a in &lp {
                for b in &lq {
                    let det = a[1] * b[2] - a[2] * b[1];
                    let t1 = (-a[0] * b[2] + a[2] * b[0]) / det;
                    let t2 = (a[1] * (-b[0]) + a[0] * b[1]) / det;
                    if norm([t1, t2]) < best.0 {
                        best = (norm([t1, t2]), [t1, t2]);
                    }
                }
            }
            // Cold start, and warm start from the previous call's roots.
            for cache in [&mut RootCache::default(), &mut cache] {
                let s = min_l1_real_solution(&p, &q, m, cache).expect("a solution");
                assert!(
                    (s[0] - best.1[0]).abs() < 1e-9 && (s[1] - best.1[1]).abs() < 1e-9,
                    "M = {m:?}: got {s:?}, want {:?}",
                    best.1
                );
            }
        }
    }

    /// At the t2 of each of the 16 intersections of two sets of four lines,
    /// the Bezout null vector gives the intersection's t1.
    #[test]
    fn bezout_null_vector_recovers_the_common_root() {
        let p = product_of_lines(&LINES_P);
        let q = product_of_lines(&LINES_Q);
        let mut recovered = 0;
        for a in &LINES_P {
            for b in &LINES_Q {
                let det = a[1] * b[2] - a[2] * b[1];
                let t1 = (-a[0] * b[2] + a[2] * b[0]) / det;
                let t2 = (a[1] * (-b[0]) + a[0] * b[1]) / det;
                if let Some(got) = bezout_null_t1(&p, &q, t2) {
                    assert!((got - t1).abs() <= 1e-9 * (1.0 + t1.abs()), "{got} vs {t1}");
                    recovered += 1;
                }
            }
        }
        // All 16 have distinct t2, so each is a simple common root.
        assert_eq!(recovered, 16);
        // P = Q: every root is common, the adjugate vanishes.
        assert_eq!(bezout_null_t1(&p, &p, 0.3), None);
    }

    #[test]
    fn no_real_solution_is_reported_as_none() {
        // P = (t1^2 + t2^2 + 1)(t1^2 + 2 t2^2 + 0.5) > 0 everywhere.
        let c1 = Quad2([[1.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        let c2 = Quad2([[0.5, 0.0, 2.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        let p = c1.mul(&c2);
        let q = lin(0.2, 1.0, -1.0)
            .mul(&lin(1.0, 0.3, 0.1))
            .mul(&lin(-0.4, 0.2, 1.0).mul(&lin(0.3, -1.0, 0.5)));
        // The resultant is not identically zero: the system is generic.
        let res = resultant_in_t2(&p, &q);
        assert!(res.iter().any(|c| c.abs() > 1e-6));
        assert!(
            min_l1_real_solution(&p, &q, [[1.0, 0.0], [0.0, 1.0]], &mut RootCache::default())
                .is_none()
        );
    }
}
