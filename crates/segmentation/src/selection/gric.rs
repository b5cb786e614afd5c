//! Two clusters, one motion or two? Torr's Geometric Robust Information
//! Criterion (P. H. S. Torr, "Geometric motion segmentation and model
//! selection", Phil. Trans. R. Soc. A 356, 1998; "An assessment of
//! information criteria for motion model selection", CVPR 1997):
//!
//! `GRIC = Σ ρ(e_i² / σ²) + λ1 d n + λ2 k`, `ρ(x) = min(x, λ3 (r − d))`,
//!
//! for n matches in `r = 4` dimensions, a model manifold of dimension
//! `d = 3` and `k = 7` parameters per fundamental matrix, `λ1 = ln r`,
//! `λ2 = ln(r n)`, `λ3 = 2`; `e_i` is the Sampson distance (the first-order
//! distance to the manifold) and σ the noise level. Two clusters merge when
//! one F for both has the smaller GRIC than one F each (the `λ1 d n` term is
//! the same for both and cancels).

use super::{refit, sampson_residuals};
use geometry::{Correspondences, IrlsParams};

/// Dimension of the data: a match is a point of R⁴.
const R: f64 = 4.0;
/// Dimension of the fundamental-matrix manifold in R⁴.
const D: f64 = 3.0;
/// Parameters of a fundamental matrix.
const K: f64 = 7.0;
/// Torr's λ3: the robust cap of a residual's cost is `λ3 (r − d)`.
const LAMBDA3: f64 = 2.0;
/// 1.4826: the MAD's consistency factor for a Gaussian.
const MAD_TO_SIGMA: f64 = 1.4826;
/// A numerical floor under σ, px (noise-free data).
const SIGMA_FLOOR_PX: f64 = 1e-6;

/// Σ ρ(e²/σ²) over `residuals` (Sampson distances, px).
fn robust_cost(residuals: impl Iterator<Item = f64>, sigma: f64) -> f64 {
    residuals
        .map(|e| (e * e / (sigma * sigma)).min(LAMBDA3 * (R - D)))
        .sum()
}

/// The noise level of two clusters under two models: the MAD-based scale of
/// their own residuals, `1.4826 · median |e|`, corrected for the `2 k`
/// parameters fitted on n matches (`· √(n / (n − 2k))`).
fn pooled_sigma(own: &[f64]) -> f64 {
    let mut abs: Vec<f64> = own.iter().map(|e| e.abs()).collect();
    abs.sort_by(f64::total_cmp);
    let n = abs.len() as f64;
    let median = if abs.is_empty() {
        0.0
    } else if abs.len() % 2 == 1 {
        abs[abs.len() / 2]
    } else {
        0.5 * (abs[abs.len() / 2 - 1] + abs[abs.len() / 2])
    };
    let dof = if n > 2.0 * K + 1.0 {
        (n / (n - 2.0 * K)).sqrt()
    } else {
        1.0
    };
    (MAD_TO_SIGMA * median * dof).max(SIGMA_FLOOR_PX)
}

/// `GRIC(one F) − GRIC(two Fs)` for clusters a and b: their residuals to
/// their own Fs and to the F of their union. Negative: one motion.
pub fn gric_difference(own_a: &[f64], own_b: &[f64], union: &[f64]) -> f64 {
    let own: Vec<f64> = own_a.iter().chain(own_b).copied().collect();
    let sigma = pooled_sigma(&own);
    let n = own.len() as f64;
    let lambda2 = (R * n).ln();
    let one = robust_cost(union.iter().copied(), sigma) + lambda2 * K;
    let two = robust_cost(own.into_iter(), sigma) + 2.0 * lambda2 * K;
    one - two
}

/// A cluster during the merges: its matches and their residuals to its F.
struct Group {
    members: Vec<usize>,
    residuals: Vec<f64>,
}

impl Group {
    fn fit(points: &Correspondences, members: Vec<usize>, irls: &IrlsParams) -> Option<Self> {
        let f = refit(points, &members, irls)?;
        let all = sampson_residuals(points, &f);
        let residuals = members.iter().map(|&m| all[m]).collect();
        Some(Self { members, residuals })
    }
}

/// The groups merged by GRIC, largest first: each group (largest first)
/// joins the kept group with which it has the most negative
/// [`gric_difference`] (one F refitted by IRLS-Tukey on the union), or is
/// kept on its own when none is negative. Groups whose F cannot be fitted
/// (fewer than 8 matches, degenerate) are dropped: their matches become
/// outliers. Returns the kept groups' matches, increasing.
pub fn merge_by_gric(
    points: &Correspondences,
    groups: &[Vec<usize>],
    irls: &IrlsParams,
) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..groups.len()).collect();
    order.sort_by_key(|&i| (std::cmp::Reverse(groups[i].len()), i));
    let mut kept: Vec<Group> = Vec::new();
    for i in order {
        let Some(g) = Group::fit(points, groups[i].clone(), irls) else {
            continue;
        };
        let best = kept
            .iter()
            .enumerate()
            .filter_map(|(h, k)| {
                let mut union: Vec<usize> = k.members.iter().chain(&g.members).copied().collect();
                union.sort_unstable();
                let merged = Group::fit(points, union, irls)?;
                let delta = gric_difference(&k.residuals, &g.residuals, &merged.residuals);
                (delta < 0.0).then_some((delta, h, merged))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        match best {
            Some((_, h, merged)) => kept[h] = merged,
            None => kept.push(g),
        }
    }
    kept.into_iter().map(|g| g.members).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_residuals_merge_and_misfit_ones_do_not() {
        let a: Vec<f64> = (0..200).map(|i| 0.5 * ((i as f64) * 0.37).sin()).collect();
        let b: Vec<f64> = (0..100).map(|i| 0.5 * ((i as f64) * 0.91).cos()).collect();
        let same: Vec<f64> = a.iter().chain(&b).copied().collect();
        assert!(gric_difference(&a, &b, &same) < 0.0);
        // The union's F misses b by 5 px: 100 capped costs of 2 outweigh 7 ln(1200).
        let off: Vec<f64> = a.iter().copied().chain(b.iter().map(|e| e + 5.0)).collect();
        assert!(gric_difference(&a, &b, &off) > 0.0);
        // ... but 10 such matches do not: a cluster that small is cheaper as outliers.
        let (b10, off10): (Vec<f64>, Vec<f64>) =
            (b[..10].to_vec(), b[..10].iter().map(|e| e + 5.0).collect());
        let union10: Vec<f64> = a.iter().copied().chain(off10).collect();
        assert!(gric_difference(&a, &b10, &union10) < 0.0);
    }
}
