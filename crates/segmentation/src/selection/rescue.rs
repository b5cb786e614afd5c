//! Motions no cluster stands for: after the clusters' detection
//! ([`super::nfa::detect`]), the hypotheses themselves are candidates on
//! the matches no detected F explains, as MAC-RANSAC detects models one
//! after another (Rabin, Delon, Gousseau & Moisan 2010). Each round takes
//! the hypothesis that explains the most of those matches within
//! `thr_px`, refits it on them (and on its whole support,
//! [`super::nfa::polish_on_support`]) and detects it when its NFA over the
//! unexplained matches is below 1; the number of tests is `M (N − 7)`, M
//! the hypotheses it chooses among, and each support k also counts the
//! `C(k, 7)` matches its F could have been fitted to (ORSA's count, Moisan
//! & Stival 2004): the F was searched for on the tested matches.

use super::nfa::{polish_on_support, significance_counting, Background, Explained, FITTED_MATCHES};
use super::{refit, sampson_residuals};
use geometry::{Correspondences, IrlsParams};
use nalgebra::Matrix3;

/// The F of the motions found among `candidates` on the matches that no F
/// of `detected` explains within `thr_px`, in the order found.
pub fn rescue(
    points: &Correspondences,
    candidates: &[Matrix3<f64>],
    detected: &[Matrix3<f64>],
    image_size: (u32, u32),
    thr_px: f64,
    irls: &IrlsParams,
) -> Vec<Matrix3<f64>> {
    let n = points.len();
    let mut explained = Explained::none(n);
    for f in detected {
        explained.add(&sampson_residuals(points, f), thr_px);
    }
    if candidates.is_empty() || n <= FITTED_MATCHES {
        return Vec::new();
    }
    let ln_tests = (candidates.len() as f64).ln() + ((n - FITTED_MATCHES) as f64).ln();
    let mut found = Vec::new();
    while let Some(support) = best_support(points, candidates, &explained, thr_px) {
        let Some(f) = refit(points, &support, irls) else {
            break;
        };
        let f = polish_on_support(points, f, &explained, thr_px, irls);
        let residuals = sampson_residuals(points, &f);
        let mut r: Vec<f64> = residuals
            .iter()
            .enumerate()
            .filter(|&(m, _)| !explained.contains(m))
            .map(|(_, &r)| r)
            .collect();
        r.sort_by(f64::total_cmp);
        let background = Background::new(&f, image_size);
        if !significance_counting(&r, ln_tests, &background, thr_px, true).is_significant() {
            break;
        }
        explained.add(&residuals, thr_px);
        found.push(f);
    }
    found
}

/// The unexplained matches within `thr_px` of the candidate that explains
/// the most of them (the first on ties); None when no candidate explains
/// more than [`FITTED_MATCHES`].
fn best_support(
    points: &Correspondences,
    candidates: &[Matrix3<f64>],
    explained: &Explained,
    thr_px: f64,
) -> Option<Vec<usize>> {
    let mut best: Option<Vec<usize>> = None;
    for f in candidates {
        let support: Vec<usize> = sampson_residuals(points, f)
            .iter()
            .enumerate()
            .filter(|&(m, &r)| r <= thr_px && !explained.contains(m))
            .map(|(m, _)| m)
            .collect();
        if support.len() > best.as_ref().map_or(FITTED_MATCHES, Vec::len) {
            best = Some(support);
        }
    }
    best
}
