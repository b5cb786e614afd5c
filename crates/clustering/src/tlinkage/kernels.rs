//! The certified bound kernels of T-Linkage: the `u8` quantisation of the
//! preferences, the error margin that makes a bound sum an upper bound of
//! the exact inner product, and the sweeps (initial and after a merge),
//! compiled for AVX2 when the CPU has it (the only `unsafe` of the crate).

use std::ops::Range;

use super::ContinuousState;
use crate::linkage::Candidate;

/// One entry of the bound matrix: a preference φ stored as an integer
/// `q ≥ LEVELS · φ`.
pub(super) type Level = u8;
/// Quantisation levels of the bound matrix: a preference φ is stored as an
/// integer `q ≥ 255 φ` (`q = 0` iff `φ = 0`). One byte a bound: the sweeps
/// stream the matrix from memory once per merge, and a byte where two were
/// used made the linkage about a fifth faster, with the same merges.
pub(super) const LEVELS: f64 = Level::MAX as f64;
/// The slot count of the bound matrix is a multiple of this.
pub(super) const LANES: usize = 16;
/// Products summed in f32 before the partial sum is added to the f64 total.
pub(super) const CHUNK: usize = 64;
/// `q = ⌈255 φ⌉` computed so that `q ≥ 255 φ` holds exactly (the product
/// is inflated by 2⁻⁵⁰ before rounding up), capped at 255 (`φ ≤ 1`).
#[inline]
pub(super) fn quantise(v: f64) -> Level {
    if v > 0.0 {
        let scaled = (v * LEVELS * (1.0 + 4.0 * f64::EPSILON)).min(LEVELS);
        let q = scaled as Level; // truncation: ⌊scaled⌋
        if f64::from(q) < scaled {
            q + 1
        } else {
            q
        }
    } else {
        0
    }
}

/// `γ_n = n u / (1 − n u)`, the classic bound on the relative error of a sum
/// of n non-negative terms in a format of unit roundoff u.
fn gamma(n: f64, unit_roundoff: f64) -> f64 {
    n * unit_roundoff / (1.0 - n * unit_roundoff)
}

/// The factor that turns a computed bound sum into a certified upper bound
/// of the computed inner product, for M hypotheses (see
/// [`ContinuousState::dot_upper`]):
/// `(1 + γ⁶⁴_(M+1)) (1 + u₆₄)⁴ / ((1 − γ³²_(C+1)) (1 − γ⁶⁴_M))`, inflated by
/// `1 + 2⁻⁴⁸` for the rounding of this very evaluation.
pub(super) fn bound_margin(n_hypotheses: usize) -> f64 {
    let (u32_, u64_) = (f64::from(f32::EPSILON) / 2.0, f64::EPSILON / 2.0);
    let m = n_hypotheses as f64;
    let numerator = (1.0 + gamma(m + 1.0, u64_)) * (1.0 + u64_).powi(4);
    let denominator = (1.0 - gamma(CHUNK as f64 + 1.0, u32_)) * (1.0 - gamma(m, u64_));
    numerator / denominator * (1.0 + 2f64.powi(-48))
}

/// `partial[s] += q · row[s]` for every slot s, in f32.
#[inline(always)]
fn axpy_bounds(partial: &mut [f32], q: f32, row: &[Level]) {
    for (a, &r) in partial.iter_mut().zip(row) {
        *a += q * f32::from(r);
    }
}

/// `total[s] += partial[s]` in f64, then `partial[s] = 0`.
#[inline(always)]
fn flush(total: &mut [f64], partial: &mut [f32]) {
    for (t, p) in total.iter_mut().zip(partial.iter_mut()) {
        *t += f64::from(*p);
        *p = 0.0;
    }
}

/// Lower bounds of the initial distances of the rows in `rows` (at most
/// [`crate::linkage::ROWS_PER_TASK`] consecutive points) to every later point.
#[inline(always)]
fn initial_block(
    state: &ContinuousState,
    rows: Range<usize>,
    out: &mut Vec<(u32, u32, Candidate)>,
) {
    let (n, width) = (state.n, state.width);
    let first = rows.start;
    let columns = width - first;
    let mut total = vec![0.0f64; rows.len() * columns];
    let mut partial = vec![0.0f32; rows.len() * columns];
    let mut counts = vec![0usize; rows.len()];
    // The hypotheses preferred by at least one row, ascending.
    let m = state.bounds.len() / width.max(1);
    let mut preferred = vec![false; m];
    for i in rows.clone() {
        for &j in state.index[i].iter() {
            preferred[j as usize] = true;
        }
    }
    for j in (0..m).filter(|&j| preferred[j]) {
        let row = &state.bounds[j * width + first..(j + 1) * width];
        for (x, (sums, count)) in partial
            .chunks_exact_mut(columns)
            .zip(counts.iter_mut())
            .enumerate()
        {
            let q = row[x];
            if q != 0 {
                axpy_bounds(&mut sums[x + 1..], f32::from(q), &row[x + 1..]);
                *count += 1;
                if *count == CHUNK {
                    flush(&mut total[x * columns..(x + 1) * columns], sums);
                    *count = 0;
                }
            }
        }
    }
    flush(&mut total, &mut partial);
    for (x, sums) in total.chunks_exact(columns).enumerate() {
        let i = first + x;
        for k in i + 1..n {
            let candidate = state.lower_bound(sums[k - first], state.norms[i], state.norms[k]);
            if candidate.d < 1.0 {
                out.push((i as u32, k as u32, candidate));
            }
        }
    }
}

/// Bound sums `Σ_j q_cj · q_sj` of the (already merged) `cluster` with every
/// slot s, into `state.acc`.
#[inline(always)]
fn merged_sweep(state: &mut ContinuousState, cluster: usize) {
    let width = state.width;
    let mut multipliers = std::mem::take(&mut state.multipliers);
    multipliers.clear();
    multipliers.extend(
        state.index[cluster]
            .iter()
            .zip(state.value[cluster].iter())
            .map(|(&j, &v)| (j, f32::from(quantise(v)))),
    );
    state.acc.fill(0.0);
    for chunk in multipliers.chunks(CHUNK) {
        for &(j, q) in chunk {
            let row = &state.bounds[j as usize * width..(j as usize + 1) * width];
            axpy_bounds(&mut state.partial, q, row);
        }
        flush(&mut state.acc, &mut state.partial);
    }
    state.multipliers = multipliers;
}

/// [`initial_block`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn initial_block_avx2(
    state: &ContinuousState,
    rows: Range<usize>,
    out: &mut Vec<(u32, u32, Candidate)>,
) {
    initial_block(state, rows, out)
}

/// [`merged_sweep`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn merged_sweep_avx2(state: &mut ContinuousState, cluster: usize) {
    merged_sweep(state, cluster)
}

/// Whether the AVX2 versions of the bound kernels can run. They perform the
/// same operations in the same order as the portable ones (no fused
/// multiply-add), and bounds only decide which pairs get an exact distance
/// computed, never its value.
pub(super) fn avx2_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// [`initial_block`] with the AVX2 build when `state.avx2` is set.
pub(super) fn initial_bounds(
    state: &ContinuousState,
    rows: Range<usize>,
    out: &mut Vec<(u32, u32, Candidate)>,
) {
    #[cfg(target_arch = "x86_64")]
    if state.avx2 {
        // SAFETY: `avx2` is set only when the CPU supports AVX2.
        return unsafe { initial_block_avx2(state, rows, out) };
    }
    initial_block(state, rows, out)
}

/// [`merged_sweep`] with the AVX2 build when `state.avx2` is set.
pub(super) fn merged_bounds(state: &mut ContinuousState, cluster: usize) {
    #[cfg(target_arch = "x86_64")]
    if state.avx2 {
        // SAFETY: `avx2` is set only when the CPU supports AVX2.
        return unsafe { merged_sweep_avx2(state, cluster) };
    }
    merged_sweep(state, cluster)
}
