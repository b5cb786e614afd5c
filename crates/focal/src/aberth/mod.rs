//! All complex roots of a real univariate polynomial of degree <= 16 (the
//! resultant of a robust focal step, and the quartics of its fallback) by
//! the Aberth–Ehrlich simultaneous iteration from Bini's Newton-polygon
//! start or a warm start: whole-set (Jacobi) sweeps across lanes while many
//! roots move, one-root (Gauss–Seidel) updates for the last few.

use nalgebra::Complex;

use crate::resultant::RES_DEGREE;
use crate::simd::{self, Simd};

type C64 = Complex<f64>;

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
    simd: Simd,
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
        if aberth_iterate(c, roots, 30, simd) {
            return count + deg;
        }
    }
    init_newton_polygon(c, roots);
    aberth_iterate(c, roots, 100, simd);
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
fn aberth_iterate(c: &[f64], roots: &mut [C64], max_iter: usize, simd: Simd) -> bool {
    let deg = c.len() - 1;
    if deg <= JACOBI_MIN_MOVING + 1 {
        return aberth_gauss_seidel(c, roots, max_iter);
    }
    let mut state = AberthState::new(c, roots);
    for _ in 0..max_iter {
        let moving = simd::jacobi_sweep(simd, &mut state);
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
pub(crate) struct AberthState {
    deg: usize,
    c: [f64; MAX_DEGREE + 1],
    abs_c: [f64; MAX_DEGREE + 1],
    /// Real parts of the approximations.
    pub(crate) re: [f64; MAX_DEGREE],
    /// Imaginary parts of the approximations.
    pub(crate) im: [f64; MAX_DEGREE],
    converged: [bool; MAX_DEGREE],
}

impl AberthState {
    /// The state for the polynomial `c` from the approximations `roots`.
    pub(crate) fn new(c: &[f64], roots: &[C64]) -> Self {
        let deg = c.len() - 1;
        let mut state = Self {
            deg,
            c: [0.0; MAX_DEGREE + 1],
            abs_c: [0.0; MAX_DEGREE + 1],
            re: [0.0; MAX_DEGREE],
            im: [0.0; MAX_DEGREE],
            converged: [false; MAX_DEGREE],
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

    /// Writes the approximations back into `roots`.
    fn store(&self, roots: &mut [C64]) {
        for (i, z) in roots.iter_mut().enumerate().take(self.deg) {
            *z = C64::new(self.re[i], self.im[i]);
        }
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
    pub(crate) fn jacobi_sweep(&mut self) -> usize {
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
        let mut z = Lanes::<L>::default();
        for a in 0..L {
            let i = active[a.min(n - 1)];
            z.re[a] = self.re[i];
            z.im[a] = self.im[i];
        }
        let h = self.horner(&z);
        let sum = self.inverse_distance_sums(&z);
        let step = aberth_corrections(&z, &h, &sum);
        let mut moving = 0;
        for (a, &i) in active.iter().enumerate().take(n) {
            if step.passed[a] {
                self.converged[i] = true;
                continue;
            }
            moving += 1;
            let (nr, ni) = (step.next.re[a], step.next.im[a]);
            if nr.is_finite() && ni.is_finite() {
                self.re[i] = nr;
                self.im[i] = ni;
            } else {
                self.converged[i] = true;
            }
        }
        moving
    }

    /// Horner for p, p' and the bound `sum |c_k| |z|^k` at every lane.
    #[inline(always)]
    fn horner<const L: usize>(&self, z: &Lanes<L>) -> HornerLanes<L> {
        let deg = self.deg;
        let (zr, zi) = (&z.re, &z.im);
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
        HornerLanes {
            p: Lanes { re: pr, im: pi },
            dp: Lanes { re: dr, im: di },
            bound,
            abs_z: az,
        }
    }

    /// `S_i = sum_{j != i} 1 / (z_i - z_j)` over the other approximations
    /// at every lane (`z_i` itself adds nothing).
    #[inline(always)]
    fn inverse_distance_sums<const L: usize>(&self, z: &Lanes<L>) -> Lanes<L> {
        let mut sr = [0.0; L];
        let mut si = [0.0; L];
        for j in 0..self.deg {
            let (rj, ij) = (self.re[j], self.im[j]);
            for a in 0..L {
                let ar = z.re[a] - rj;
                let ai = z.im[a] - ij;
                let d2 = ar * ar + ai * ai;
                let inv = if d2 > 0.0 { 1.0 / d2 } else { 0.0 };
                sr[a] += ar * inv;
                si[a] -= ai * inv;
            }
        }
        Lanes { re: sr, im: si }
    }
}

/// One complex value per lane, in structure-of-arrays form.
#[derive(Clone, Copy)]
struct Lanes<const L: usize> {
    re: [f64; L],
    im: [f64; L],
}

impl<const L: usize> Default for Lanes<L> {
    fn default() -> Self {
        Self {
            re: [0.0; L],
            im: [0.0; L],
        }
    }
}

/// `p(z)`, `p'(z)`, the bound `sum |c_k| |z|^k` and `|z|` at every lane.
struct HornerLanes<const L: usize> {
    p: Lanes<L>,
    dp: Lanes<L>,
    bound: [f64; L],
    abs_z: [f64; L],
}

/// The outcome of an Aberth step at every lane.
struct StepLanes<const L: usize> {
    /// The lane's root passed the backward-error test.
    passed: [bool; L],
    /// `z - w`, the updated approximation.
    next: Lanes<L>,
}

/// The backward-error test and the Aberth correction at every lane (lanes
/// whose root passes the test compute one too; it is not used):
/// `w = r / (1 - r S)` with `r = p / p'` (at a stationary point of p, a
/// nudge).
#[inline(always)]
fn aberth_corrections<const L: usize>(
    z: &Lanes<L>,
    h: &HornerLanes<L>,
    sum: &Lanes<L>,
) -> StepLanes<L> {
    let tol = 4.0 * f64::EPSILON;
    let (pr, pi, dr, di) = (&h.p.re, &h.p.im, &h.dp.re, &h.dp.im);
    let (sr, si) = (&sum.re, &sum.im);
    let mut step = StepLanes {
        passed: [false; L],
        next: Lanes::default(),
    };
    for a in 0..L {
        let pv2 = pr[a] * pr[a] + pi[a] * pi[a];
        let lim = tol * h.bound[a];
        step.passed[a] = pv2 <= lim * lim;
        let dp2 = dr[a] * dr[a] + di[a] * di[a];
        // ratio = p / p'; at a stationary point of p, a nudge.
        let nudge = 1e-8 * (1.0 + h.abs_z[a]);
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
        step.next.re[a] = z.re[a] - wr;
        step.next.im[a] = z.im[a] - wi;
    }
    step
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
pub(crate) fn init_newton_polygon(c: &[f64], roots: &mut [C64]) {
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

#[cfg(test)]
mod tests;
