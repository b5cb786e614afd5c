//! Detections that are one motion: two detected Fs are replaced by the F of
//! their joint support when that one F is more meaningful than the two
//! (Cao, Delon, Desolneux, Musé & Sur, "A unified framework for detecting
//! groups and application to shape recognition", JMIV 2007: a group is
//! merged when the union's NFA is below the NFA of the pair). A motion seen
//! by the clustering as two spatial pieces gives two Fs, each fitted on its
//! piece; the F of both pieces explains the two with 7 fitted matches and
//! one test instead of 14 and two, so its NFA is below the product of
//! theirs; two motions whose matches one F cannot bring within the
//! thresholds their own Fs do are not.

use super::nfa::{significance, Background, Detection, Significance};
use super::{refit, sampson_residuals};
use geometry::{Correspondences, IrlsParams};

/// The detections after merging, greedily, the pair whose union gains the
/// most (`ln NFA(a) + ln NFA(b) − ln NFA(a ∪ b) > 0`) until no pair gains.
/// Each NFA is over the matches no other detection explains (within
/// `thr_px`), with `ln_tests` as in [`super::nfa::detect`]; the union's F
/// is refitted by IRLS-Tukey on the matches within `thr_px` of either F.
pub fn merge_detections(
    points: &Correspondences,
    mut detections: Vec<Detection>,
    image_size: (u32, u32),
    thr_px: f64,
    ln_tests: f64,
    irls: &IrlsParams,
) -> Vec<Detection> {
    while let Some((a, b, union)) =
        best_union(points, &detections, image_size, thr_px, ln_tests, irls)
    {
        let gone = detections.remove(b);
        let kept = &mut detections[a];
        kept.groups.extend(gone.groups);
        kept.f = union.f;
        kept.residuals = union.residuals;
        kept.significance = union.significance;
    }
    detections
}

/// One F for two detections.
struct Union {
    f: nalgebra::Matrix3<f64>,
    residuals: Vec<f64>,
    significance: Significance,
}

/// The pair (a < b) of largest gain, with its union; None when no pair
/// gains.
fn best_union(
    points: &Correspondences,
    detections: &[Detection],
    image_size: (u32, u32),
    thr_px: f64,
    ln_tests: f64,
    irls: &IrlsParams,
) -> Option<(usize, usize, Union)> {
    let mut best: Option<(f64, usize, usize, Union)> = None;
    for a in 0..detections.len() {
        for b in a + 1..detections.len() {
            let counts = counted(detections, &[a, b], thr_px);
            let score = |r: &[f64], bg: &Background| {
                significance(&sorted_counted(r, &counts), ln_tests, bg, thr_px)
            };
            let (da, db) = (&detections[a], &detections[b]);
            let sa = score(&da.residuals, &Background::new(&da.f, image_size));
            let sb = score(&db.residuals, &Background::new(&db.f, image_size));
            let support: Vec<usize> = (0..points.len())
                .filter(|&m| counts[m] && (da.residuals[m] <= thr_px || db.residuals[m] <= thr_px))
                .collect();
            let Some(f) = refit(points, &support, irls) else {
                continue;
            };
            let residuals = sampson_residuals(points, &f);
            let su = score(&residuals, &Background::new(&f, image_size));
            let gain = sa.ln_nfa + sb.ln_nfa - su.ln_nfa;
            if gain > 0.0 && best.as_ref().map_or(true, |(g, ..)| gain > *g) {
                best = Some((
                    gain,
                    a,
                    b,
                    Union {
                        f,
                        residuals,
                        significance: su,
                    },
                ));
            }
        }
    }
    best.map(|(_, a, b, u)| (a, b, u))
}

/// Per match: true when no detection but those in `pair` explains it.
fn counted(detections: &[Detection], pair: &[usize], thr_px: f64) -> Vec<bool> {
    let n = detections[0].residuals.len();
    (0..n)
        .map(|m| {
            detections
                .iter()
                .enumerate()
                .all(|(d, det)| pair.contains(&d) || det.residuals[m] > thr_px)
        })
        .collect()
}

/// The residuals of the counted matches, increasing.
fn sorted_counted(residuals: &[f64], counts: &[bool]) -> Vec<f64> {
    let mut r: Vec<f64> = residuals
        .iter()
        .zip(counts)
        .filter(|(_, &c)| c)
        .map(|(&r, _)| r)
        .collect();
    r.sort_by(f64::total_cmp);
    r
}
