//! A cluster split in the two clusters whose merge made it, when they are
//! two motions: T-Linkage joins two small objects that hypotheses drawn
//! or refitted across both fit within `thr_px`, though neither object's
//! own F explains the other (results/notes/selection.md, ninth round).
//!
//! The sides of a group (the last merge of two clusters of more than
//! [`FITTED_MATCHES`] matches, [`clustering::dendrogram::last_sides`]) replace
//! it when
//! 1. each side is significant alone (its best model's NFA < 1 over every
//!    match, as in [`super::nfa::detect`]);
//! 2. neither side's model explains (within `thr_px`) more than half of
//!    the other side's matches;
//! 3. one F for both fits them worse than one F each beyond chance:
//!    Chow's test (Chow 1960) of the union's refitted F against the sides'
//!    (`chow_p`), p < [`SPLIT_ALPHA`].

use super::nfa::{fit_given, Cached, Explained, Fitting, GroupFit, FITTED_MATCHES};
use super::refit;
use clustering::dendrogram::Sides;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

/// The level of Chow's test. With α 10⁻³ the wide validation's mean ME
/// was 6.052, with 10⁻⁶ 6.019 (every family no worse than without the
/// split), against 6.184 without it; without the test 6.602, one
/// motion's two halves split (results/notes/selection.md, ninth round).
pub const SPLIT_ALPHA: f64 = 1e-6;

/// `groups`, each replaced by its two sides (`sides[g]`, indices into the
/// matches; one entry per group) where they are two motions (the module's
/// three conditions); with the fits made on the way (nothing explained),
/// which the detection reuses.
pub(super) fn split_groups(
    fitting: &Fitting,
    groups: &[Vec<usize>],
    sides: &[Option<Sides>],
) -> (Vec<Vec<usize>>, Vec<Option<Cached>>) {
    let n = fitting.points.len();
    if n <= FITTED_MATCHES {
        return (groups.to_vec(), groups.iter().map(|_| None).collect());
    }
    // The tests: every group and side that may be scored, N − 7 thresholds.
    let candidates = sides.iter().flatten().count();
    let eligible = groups.iter().filter(|g| g.len() > FITTED_MATCHES).count();
    let ln_tests = ((eligible + 2 * candidates) as f64).ln() + ((n - FITTED_MATCHES) as f64).ln();
    let mut out = Vec::with_capacity(groups.len() + candidates);
    let mut fits = Vec::with_capacity(groups.len() + candidates);
    for (group, sides) in groups.iter().zip(sides) {
        let mut cached: [Option<Cached>; 3] = [None, None, None];
        match sides {
            Some([a, b]) if are_two_motions(fitting, group, [a, b], ln_tests, &mut cached) => {
                let [_, fa, fb] = cached;
                out.extend([a.clone(), b.clone()]);
                fits.extend([fa, fb]);
            }
            _ => {
                let [fu, _, _] = cached;
                out.push(group.clone());
                fits.push(fu);
            }
        }
    }
    (out, fits)
}

/// The module's three conditions for `group` and its two sides; the fits
/// made (nothing explained) in `cached`: the group's, then the sides'.
fn are_two_motions(
    fitting: &Fitting,
    group: &[usize],
    sides: [&[usize]; 2],
    ln_tests: f64,
    cached: &mut [Option<Cached>; 3],
) -> bool {
    if !passes_screen(fitting, group, sides) {
        return false;
    }
    let none = Explained::none(fitting.points.len());
    let [union_fit, a_fit, b_fit] = cached;
    let residuals =
        |g: &[usize], cache: &mut Option<Cached>, pick: &dyn Fn(&GroupFit) -> Option<usize>| {
            let fitted = fit_given(fitting, g, &none, cache)?;
            pick(fitted).map(|m| fitted.models[m].residuals.clone())
        };
    // 1: each side's best model, when significant alone.
    let best = |fit: &GroupFit| {
        let (significance, model) = fit.significance(&none, ln_tests, fitting.thr_px);
        significance.is_significant().then_some(model)
    };
    let Some(ra) = residuals(sides[0], a_fit, &best) else {
        return false;
    };
    let Some(rb) = residuals(sides[1], b_fit, &best) else {
        return false;
    };
    // 2: neither explains most of the other.
    let explains = |r: &[f64], s: &[usize]| {
        2 * s.iter().filter(|&&i| r[i] <= fitting.thr_px).count() > s.len()
    };
    if explains(&ra, sides[1]) || explains(&rb, sides[0]) {
        return false;
    }
    // 3: the union's first model (its refitted F, or where the refit
    // fails its semi-calibrated F) against the sides'.
    let Some(ru) = residuals(group, union_fit, &|_| Some(0)) else {
        return false;
    };
    chow_p(&ru, [(sides[0], &ra), (sides[1], &rb)], fitting.thr_px) < SPLIT_ALPHA
}

/// The level of the screen before the three conditions: Chow's test with
/// the refitted Fs alone (each side's and the union's, no background
/// integral to make). A side's refitted F fits it about as closely as its
/// best model, so the screen passes almost wherever condition 3 would (on
/// the wide validation it changes 2 of 3 180 runs, the mean ME 6.019 →
/// 6.021), and it saves most of the split's cost: the sides' models and
/// their backgrounds (5.8 → 1.6 ms per AdelaideRMF scene).
const SCREEN_ALPHA: f64 = 1e-2;

/// Whether Chow's test with the refitted Fs of `group` and its `sides`
/// gives p < [`SCREEN_ALPHA`].
fn passes_screen(fitting: &Fitting, group: &[usize], sides: [&[usize]; 2]) -> bool {
    let n = fitting.points.len();
    let distances = |f: Option<nalgebra::Matrix3<f64>>, at: &[&[usize]]| {
        let mut r = vec![f64::INFINITY; n];
        if let Some(f) = f {
            for &i in at.iter().copied().flatten() {
                let (p1, p2) = (fitting.points.point1(i), fitting.points.point2(i));
                r[i] = geometry::sampson_distance(&f, p1, p2);
            }
        }
        r
    };
    let fit = |g: &[usize]| refit(fitting.points, g, fitting.irls);
    let ru = distances(fit(group), &sides);
    let ra = distances(fit(sides[0]), &sides[..1]);
    let rb = distances(fit(sides[1]), &sides[1..]);
    chow_p(&ru, [(sides[0], &ra), (sides[1], &rb)], fitting.thr_px) < SCREEN_ALPHA
}

/// Chow's test (Chow 1960) of one F for both sides against one F each,
/// over the matches within `thr_px` of the union's F and of their side's:
/// with `SSR` the sums of squared Sampson distances and `n` those matches,
/// `((SSR_union − SSR_sides) / 7) / (SSR_sides / (n − 14)) ~ F(7, n − 14)`
/// under one motion (each F has 7 degrees of freedom). Returns the
/// p-value, 1 when fewer than 15 matches count or the sides fit exactly.
pub(super) fn chow_p(union: &[f64], sides: [(&[usize], &[f64]); 2], thr_px: f64) -> f64 {
    let (mut ssr_union, mut ssr_sides, mut n) = (0.0, 0.0, 0usize);
    for (side, r) in sides {
        for &i in side
            .iter()
            .filter(|&&i| union[i] <= thr_px && r[i] <= thr_px)
        {
            ssr_union += union[i] * union[i];
            ssr_sides += r[i] * r[i];
            n += 1;
        }
    }
    if n <= 2 * FITTED_MATCHES || ssr_sides <= 0.0 {
        return 1.0;
    }
    let dof = (n - 2 * FITTED_MATCHES) as f64;
    let stat = ((ssr_union - ssr_sides).max(0.0) / 7.0) / (ssr_sides / dof);
    FisherSnedecor::new(7.0, dof).map_or(1.0, |d| d.sf(stat))
}

#[cfg(test)]
mod tests {
    use super::super::tests::{
        background, camera, one_motion_in_two_regions, Motion, Scene, THR_PX,
    };
    use super::super::{groups_of, select_clustered};
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use statrs::function::beta::beta_reg;

    #[test]
    fn chow_p_is_one_when_one_f_fits_both_sides_as_well_as_two() {
        let r: Vec<f64> = (0..40).map(|i| 0.05 * i as f64).collect();
        let (a, b): (Vec<usize>, Vec<usize>) = (0..40).partition(|&i| i % 2 == 0);
        assert_eq!(chow_p(&r, [(&a, &r), (&b, &r)], THR_PX), 1.0);
    }

    #[test]
    fn chow_p_is_the_f_tail_of_the_matches_within_thr_px() {
        // 30 matches at 0.5 px from their side's F and 1 px from the
        // union's, and one at 3 px from the union's (beyond thr_px: not
        // counted). SSR 7.5 and 30 over n = 30: F = (22.5 / 7) / (7.5 / 16).
        let mut union = vec![1.0; 31];
        union[30] = 3.0;
        let sides = vec![0.5; 31];
        let (a, b): (Vec<usize>, Vec<usize>) = (0..31).partition(|&i| i < 15);
        let p = chow_p(&union, [(&a, &sides), (&b, &sides)], THR_PX);
        let stat = (22.5 / 7.0) / (7.5 / 16.0);
        // The F(d₁, d₂) tail: I_{d₂ / (d₂ + d₁ x)}(d₂ / 2, d₁ / 2).
        let expected = beta_reg(8.0, 3.5, 16.0 / (16.0 + 7.0 * stat));
        assert!((p - expected).abs() < 1e-12, "{p} vs {expected}");
        assert!(p < 1e-3);
    }

    /// The background and two objects of 40 matches side by side, moving
    /// apart; with the objects' matches (truth 1 and 2).
    fn two_objects() -> (Scene, Vec<usize>, Vec<usize>) {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut s = Scene::default();
        s.add_motion(&mut rng, &background(), 200, (-300.0, 300.0));
        let left = Motion::new([0.0, -0.1, 0.02], [0.4, 0.0, -0.3]);
        let right = Motion::new([0.05, 0.08, 0.0], [-0.2, 0.3, 0.1]);
        s.add_motion(&mut rng, &left, 40, (-200.0, -80.0));
        s.add_motion(&mut rng, &right, 40, (-80.0, 40.0));
        let of = |t| (0..s.truth.len()).filter(|&i| s.truth[i] == t).collect();
        let (a, b) = (of(1), of(2));
        (s, a, b)
    }

    #[test]
    fn two_objects_one_cluster_holds_are_split_by_their_last_merge() {
        let (s, a, b) = two_objects();
        let background: Vec<usize> = (0..s.truth.len()).filter(|&i| s.truth[i] == 0).collect();
        let union: Vec<usize> = a.iter().chain(&b).copied().collect();
        let groups = vec![background, union];
        let split = select_clustered(
            &s.points(),
            &groups,
            &[None, Some([a.clone(), b.clone()])],
            camera(),
            THR_PX,
        )
        .unwrap();
        assert_eq!(split.motions, 3);
        let kept = select_clustered(&s.points(), &groups, &[None, None], camera(), THR_PX).unwrap();
        assert!(kept.motions < 3, "without the sides: {}", kept.motions);
    }

    #[test]
    fn sides_for_another_number_of_groups_are_an_error() {
        let (s, a, b) = two_objects();
        let groups = vec![a.clone(), b.clone()];
        let err = select_clustered(&s.points(), &groups, &[None], camera(), THR_PX).unwrap_err();
        assert_eq!(
            err,
            super::super::SelectionError::SidesMismatch {
                sides: 1,
                groups: 2
            }
        );
    }

    #[test]
    fn one_motion_in_two_regions_is_not_split() {
        // add_motion labels the two regions 0 and 1: one motion, one F.
        let (s, _) = one_motion_in_two_regions();
        let sides = groups_of(&s.truth);
        let union: Vec<usize> = sides.concat();
        let sides = [sides[0].clone(), sides[1].clone()];
        let sel =
            select_clustered(&s.points(), &[union], &[Some(sides)], camera(), THR_PX).unwrap();
        assert_eq!(sel.motions, 1);
    }
}
