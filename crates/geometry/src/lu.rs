//! Gaussian elimination with partial pivoting for the small dense systems
//! of the minimal solvers (the 5-point elimination template): the answers
//! of nalgebra's `LU::new` followed by `LU::solve`, bit for bit, computed
//! on the augmented rows `[A | B]` with full-width row updates that the
//! compiler vectorises.
//!
//! Every entry that is read goes through the same floating-point
//! operations, in the same order, as in nalgebra 0.33: the same pivots, the
//! multipliers `a_ri · (1 / a_ii)`, the updates `a_rk − a_ik · l_r` (forward
//! substitution of `B` included: each row of `B` receives the updates of
//! the rows above it in the order nalgebra's substitution applies them),
//! and back substitution dividing by the pivot
//! (`tests::equals_nalgebra_bit_for_bit`).

use crate::simd::dispatch;

/// The columns of a row of the 5-point template: the 10 × 10 block that is
/// eliminated, then the 10 right-hand sides.
pub(crate) const TEMPLATE_WIDTH: usize = 20;

dispatch! {
    /// [`lu_solve_kernel`] on the 10 × 20 template of the 5-point solver,
    /// in the build [`crate::simd::avx2`] chooses.
    pub(crate) fn lu_solve_template(rows: [[f64; TEMPLATE_WIDTH]; 10]) -> Option<[[f64; TEMPLATE_WIDTH]; 10]>
        => lu_solve_kernel
}

/// `X = A⁻¹ B` for the augmented rows `[A | B]` (`A` the first `N`
/// columns, `B` the other `W − N`), by LU factorisation with partial
/// pivoting (Golub & Van Loan, *Matrix Computations*, Alg. 3.4.1):
///
/// * step `i`: the row `r ≥ i` of largest `|a_ri|` (the first on ties) is
///   swapped with row `i`; each row below becomes `row − pivot_row · l_r`
///   with `l_r = a_ri · (1 / a_ii)` (columns `≤ i` are left as rounding
///   residue and never read again); a column without a non-zero candidate
///   is skipped;
/// * back substitution on `B`: `x_i = b_i / u_ii`, `b_j ← b_j − x_i u_ji`
///   for `j < i`.
///
/// Returns the rows with `X` in columns `N..W`, or `None` when a pivot
/// `u_ii` is zero (a singular `A`), as nalgebra's `LU::solve`. Non-finite
/// input is not checked: it flows through.
#[inline(always)]
pub(crate) fn lu_solve_kernel<const N: usize, const W: usize>(
    mut rows: [[f64; W]; N],
) -> Option<[[f64; W]; N]> {
    for i in 0..N {
        let pivot = pivot_row(&rows, i);
        let diag = rows[pivot][i];
        if diag == 0.0 {
            continue;
        }
        rows.swap(i, pivot);
        let inverse = 1.0 / diag;
        // A copy: the compiler then knows it is not one of the rows below,
        // and vectorises their updates.
        let pivot = rows[i];
        for row in &mut rows[i + 1..] {
            let l = row[i] * inverse;
            for (entry, &p) in row.iter_mut().zip(&pivot) {
                *entry -= p * l;
            }
        }
    }
    if (0..N).any(|i| rows[i][i] == 0.0) {
        return None;
    }
    for i in (0..N).rev() {
        let diag = rows[i][i];
        rows[i][N..].iter_mut().for_each(|v| *v /= diag);
        let solved = rows[i];
        for row in &mut rows[..i] {
            let u = row[i];
            for (entry, &x) in row[N..].iter_mut().zip(&solved[N..]) {
                *entry -= x * u;
            }
        }
    }
    Some(rows)
}

/// The row `r ≥ i` of largest `|a_ri|`, the first on ties (a NaN never
/// wins a comparison), as nalgebra's `icamax`.
#[inline(always)]
fn pivot_row<const N: usize, const W: usize>(rows: &[[f64; W]; N], i: usize) -> usize {
    let mut best = i;
    let mut largest = rows[i][i].abs();
    for (r, row) in rows.iter().enumerate().skip(i + 1) {
        if row[i].abs() > largest {
            largest = row[i].abs();
            best = r;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::with_portable;
    use nalgebra::SMatrix;

    type Rows = [[f64; TEMPLATE_WIDTH]; 10];

    /// nalgebra's `LU::new(A).solve(B)` for the augmented rows `[A | B]`.
    fn nalgebra_solve(rows: &Rows) -> Option<Vec<u64>> {
        let a = SMatrix::<f64, 10, 10>::from_fn(|r, c| rows[r][c]);
        let b = SMatrix::<f64, 10, 10>::from_fn(|r, c| rows[r][10 + c]);
        let x = a.lu().solve(&b)?;
        Some(
            (0..10)
                .flat_map(|r| (0..10).map(move |c| x[(r, c)].to_bits()))
                .collect(),
        )
    }

    /// The `X` part of [`lu_solve_template`]'s answer, as bits (NaNs and
    /// signed zeros compare too).
    fn ours(rows: Rows) -> Option<Vec<u64>> {
        let x = lu_solve_template(rows)?;
        Some(
            x.iter()
                .flat_map(|row| row[10..].iter().map(|v| v.to_bits()))
                .collect(),
        )
    }

    /// A deterministic pseudo-random value in [-1, 1) from a counter.
    fn value(k: u64) -> f64 {
        let x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (k >> 7);
        let x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn random(seed: u64) -> Rows {
        std::array::from_fn(|r| std::array::from_fn(|c| value(seed * 1000 + (20 * r + c) as u64)))
    }

    #[test]
    fn equals_nalgebra_bit_for_bit() {
        let mut singular = 0;
        for seed in 0..250 {
            let mut rows = random(seed);
            match seed % 5 {
                // Small integers: ties between pivot candidates.
                1 => rows
                    .iter_mut()
                    .flatten()
                    .for_each(|v| *v = (*v * 3.0).round()),
                // A zero column: a skipped step and a zero pivot (None).
                2 => rows.iter_mut().for_each(|row| row[3] = 0.0),
                // Rank 9 up to rounding.
                3 => rows[9] = std::array::from_fn(|c| rows[0][c] + 0.5 * rows[4][c]),
                // Scales ten orders apart.
                4 => rows.iter_mut().enumerate().for_each(|(r, row)| {
                    row.iter_mut().for_each(|v| *v *= 10f64.powi(r as i32 - 5))
                }),
                _ => {}
            }
            let expected = nalgebra_solve(&rows);
            singular += usize::from(expected.is_none());
            assert_eq!(
                ours(rows),
                expected,
                "seed {seed}, AVX2 build where the CPU has it"
            );
            assert_eq!(
                with_portable(|| ours(rows)),
                expected,
                "seed {seed}, baseline build"
            );
        }
        assert!(singular >= 50, "the zero-column cases are singular");
    }

    #[test]
    fn solves_a_known_system() {
        // A permutation of a diagonal matrix: pivoting is needed at once.
        let rows = [
            [0.0, 0.0, 2.0, 2.0],
            [4.0, 0.0, 0.0, 8.0],
            [0.0, -1.0, 0.0, 3.0],
        ];
        let x = lu_solve_kernel(rows).unwrap();
        assert_eq!(x.map(|row| row[3]), [2.0, -3.0, 1.0]);
        assert_eq!(lu_solve_kernel([[0.0, 0.0, 1.0]; 2]), None);
    }
}
