//! A cluster split in two, when it holds two motions: T-Linkage joins two
//! small objects that hypotheses drawn or refitted across both fit within
//! `thr_px`, though neither object's own F explains the other
//! (results/notes/selection.md, ninth to eleventh rounds).
//!
//! A group has up to three candidate splits: where every match was
//! clustered, the two clusters of its last merge of two clusters of more
//! than [`FITTED_MATCHES`] matches
//! ([`clustering::dendrogram::last_sides`]); then, also beyond a clustered
//! subset, its matches in two by
//! where they lie ([`two_means`]: objects are compact, and a motion merged
//! into another's cluster rarely forms a sizeable cluster of its own
//! before it joins, so no merge of the dendrogram separates it), and in
//! two by how they move ([`two_means_by_displacement`]: two objects side
//! by side, which the split by place may cut across, differ in their
//! displacements). The first
//! candidate whose two sides pass replaces the group, when
//! 1. each side is significant alone (its best model's NFA < 1 over every
//!    match, as in [`super::nfa::detect`]);
//! 2. neither side's model explains (within `thr_px`) more than half of
//!    the other side's matches;
//! 3. one F for both fits them worse than one F each beyond chance:
//!    Chow's test (Chow 1960) of the union's refitted F against the sides'
//!    (`chow_p`), p < [`SPLIT_ALPHA`].
//!
//! Every candidate's sides count as tests of condition 1.

use super::nfa::{fit_given, Cached, Explained, Fitting, GroupFit, FITTED_MATCHES};
use super::refit;
use super::two_means::{two_means, two_means_by_displacement};
use clustering::dendrogram::Sides;
use nalgebra::Matrix3;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

/// The level of Chow's test. With α 10⁻³ the wide validation's mean ME
/// was 6.052, with 10⁻⁶ 6.019 (every family no worse than without the
/// split), against 6.184 without it; without the test 6.602, one
/// motion's two halves split (results/notes/selection.md, ninth round).
pub const SPLIT_ALPHA: f64 = 1e-6;

/// `groups`, each replaced by the two sides of its first candidate split
/// (`sides[g]`, indices into the matches, one entry per group; then the
/// group's [`two_means`], then its [`two_means_by_displacement`]) where
/// they are two motions (the module's three
/// conditions); with the fits made on the way (nothing explained), which
/// the detection reuses.
pub(super) fn split_groups(
    fitting: &Fitting,
    groups: &[Vec<usize>],
    sides: &[Option<Sides>],
) -> (Vec<Vec<usize>>, Vec<Option<Cached>>) {
    let n = fitting.points.len();
    if n <= FITTED_MATCHES {
        return (groups.to_vec(), groups.iter().map(|_| None).collect());
    }
    let candidates: Vec<Vec<Sides>> = groups
        .iter()
        .zip(sides)
        .map(|(group, sides)| {
            let min = FITTED_MATCHES + 1;
            let by_place = two_means(fitting.points, group, min);
            let by_displacement = two_means_by_displacement(fitting.points, group, min);
            let by_merge = sides.iter().cloned();
            by_merge.chain(by_place).chain(by_displacement).collect()
        })
        .collect();
    // The tests: every group and side that may be scored, N − 7 thresholds.
    let count = candidates.iter().map(Vec::len).sum::<usize>();
    let eligible = groups.iter().filter(|g| g.len() > FITTED_MATCHES).count();
    let ln_tests = ((eligible + 2 * count) as f64).ln() + ((n - FITTED_MATCHES) as f64).ln();
    let mut out = Vec::with_capacity(groups.len() + count);
    let mut fits = Vec::with_capacity(groups.len() + count);
    for (group, candidates) in groups.iter().zip(candidates) {
        let mut union = Union::new(group);
        let split = candidates.into_iter().find_map(|[a, b]| {
            let mut side_fits = [None, None];
            are_two_motions(fitting, &mut union, [&a, &b], ln_tests, &mut side_fits)
                .then_some(([a, b], side_fits))
        });
        match split {
            Some((sides, side_fits)) => {
                out.extend(sides);
                fits.extend(side_fits);
            }
            None => {
                out.push(group.clone());
                fits.push(union.fit);
            }
        }
    }
    (out, fits)
}

/// A group whose candidate splits are tested, with what their tests
/// share, each made once: its fit (nothing explained) and its refitted F.
struct Union<'g> {
    group: &'g [usize],
    fit: Option<Cached>,
    refitted: Option<Option<Matrix3<f64>>>,
}

impl<'g> Union<'g> {
    fn new(group: &'g [usize]) -> Self {
        Self {
            group,
            fit: None,
            refitted: None,
        }
    }

    /// Its F refitted by IRLS-Tukey (None where the refit fails).
    fn refitted(&mut self, fitting: &Fitting) -> Option<Matrix3<f64>> {
        *self
            .refitted
            .get_or_insert_with(|| refit(fitting.points, self.group, fitting.irls))
    }
}

/// The module's three conditions for a group and two sides of it; the
/// sides' fits made (nothing explained) in `side_fits`.
fn are_two_motions(
    fitting: &Fitting,
    union: &mut Union,
    sides: [&[usize]; 2],
    ln_tests: f64,
    side_fits: &mut [Option<Cached>; 2],
) -> bool {
    if !passes_screen(fitting, union.refitted(fitting), sides) {
        return false;
    }
    let none = Explained::none(fitting.points.len());
    let [a_fit, b_fit] = side_fits;
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
    let thr_px = fitting.thr_px;
    if explains(&ra, sides[1], thr_px) || explains(&rb, sides[0], thr_px) {
        return false;
    }
    // 3: the union's first model (its refitted F, or where the refit
    // fails its semi-calibrated F) against the sides'.
    let Some(ru) = residuals(union.group, &mut union.fit, &|_| Some(0)) else {
        return false;
    };
    chow_p(&ru, [(sides[0], &ra), (sides[1], &rb)], fitting.thr_px) < SPLIT_ALPHA
}

/// The level of the screen before the three conditions: conditions 2 and
/// 3 with the refitted Fs alone (each side's and the union's, no
/// background integral to make), Chow's test at this level. A side's
/// refitted F fits it about as closely as its best model, so the screen
/// passes almost wherever the conditions would (Chow's part changed 2 of
/// the wide validation's 3 180 runs, the mean ME 6.019 → 6.021), and it
/// saves most of the split's cost: the sides' models and their
/// backgrounds (5.8 → 1.6 ms per AdelaideRMF scene with Chow's part
/// alone; condition 2 added when the split by place came, which tries a
/// second candidate, two regions of one motion, on most clusters).
const SCREEN_ALPHA: f64 = 1e-2;

/// Whether neither side's refitted F explains most of the other side's
/// matches and Chow's test with the refitted Fs of a group (`union`, None
/// where its refit failed) and its `sides` gives p < [`SCREEN_ALPHA`].
fn passes_screen(fitting: &Fitting, union: Option<Matrix3<f64>>, sides: [&[usize]; 2]) -> bool {
    let n = fitting.points.len();
    let distances = |f: Option<Matrix3<f64>>, at: &[&[usize]]| {
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
    let ra = distances(fit(sides[0]), &sides);
    let rb = distances(fit(sides[1]), &sides);
    if explains(&ra, sides[1], fitting.thr_px) || explains(&rb, sides[0], fitting.thr_px) {
        return false;
    }
    let ru = distances(union, &sides);
    chow_p(&ru, [(sides[0], &ra), (sides[1], &rb)], fitting.thr_px) < SCREEN_ALPHA
}

/// Whether the model of Sampson distances `r` explains (within `thr_px`)
/// more than half of `side`'s matches.
fn explains(r: &[f64], side: &[usize], thr_px: f64) -> bool {
    2 * side.iter().filter(|&&i| r[i] <= thr_px).count() > side.len()
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
        background, camera, kept_together, one_motion_in_two_regions, Motion, Scene, THR_PX,
    };
    use super::super::{groups_of, select_clustered, select_groups, GroupOrigin};
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

    /// The background's group and the objects' union of [`two_objects`].
    fn background_and_union(s: &Scene, a: &[usize], b: &[usize]) -> Vec<Vec<usize>> {
        let background: Vec<usize> = (0..s.truth.len()).filter(|&i| s.truth[i] == 0).collect();
        vec![background, a.iter().chain(b).copied().collect()]
    }

    #[test]
    fn two_objects_one_cluster_holds_are_split_by_their_last_merge() {
        let (s, a, b) = two_objects();
        let groups = background_and_union(&s, &a, &b);
        let split = select_clustered(
            &s.points(),
            &groups,
            &[None, Some([a.clone(), b.clone()])],
            camera(),
            THR_PX,
        )
        .unwrap();
        assert_eq!(split.motions, 3);
        // The last merge's sides are the first candidate: the groups are
        // the objects exactly, not the sides of a 2-means.
        let (points, irls) = (s.points(), super::super::refit_params(THR_PX));
        let fitting = Fitting {
            points: &points,
            camera: &camera(),
            thr_px: THR_PX,
            irls: &irls,
        };
        let (out, _) = split_groups(&fitting, &groups, &[None, Some([a.clone(), b.clone()])]);
        assert_eq!(out, [groups[0].clone(), a, b]);
    }

    #[test]
    fn two_objects_side_by_side_are_split_by_their_displacements() {
        let (s, a, b) = two_objects();
        let groups = background_and_union(&s, &a, &b);
        // The objects lie side by side over the image's height: 2-means
        // over the points cuts across both, over the displacements it
        // finds them.
        let points = s.points();
        let by_place = two_means(&points, &groups[1], FITTED_MATCHES + 1).unwrap();
        let holds_both = |side: &Vec<usize>| {
            let of_a = side.iter().filter(|i| a.contains(i)).count();
            of_a >= 5 && side.len() - of_a >= 5
        };
        assert!(by_place.iter().all(holds_both), "{by_place:?}");
        let sel = select_clustered(&points, &groups, &[None, None], camera(), THR_PX).unwrap();
        assert_eq!(sel.motions, 3);
        for t in 1..=2 {
            assert!(kept_together(&s.truth, &sel.labels, t) > 0.9, "object {t}");
        }
    }

    /// The background and two objects of 40 matches in boxes apart, moving
    /// apart; with the groups: the background's and the objects' union.
    fn two_objects_apart() -> (Scene, Vec<Vec<usize>>) {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut s = Scene::default();
        s.add_motion(&mut rng, &background(), 200, (-300.0, 300.0));
        let left = Motion::new([0.0, -0.1, 0.02], [0.4, 0.0, -0.3]);
        let right = Motion::new([0.05, 0.08, 0.0], [-0.2, 0.3, 0.1]);
        s.add_motion_in(&mut rng, &left, 40, (-280.0, -160.0), (-200.0, -60.0));
        s.add_motion_in(&mut rng, &right, 40, (80.0, 200.0), (60.0, 200.0));
        let truth = &s.truth;
        let of = |t| (0..truth.len()).filter(move |&i| truth[i] == t);
        let union: Vec<usize> = of(1).chain(of(2)).collect();
        let groups = vec![of(0).collect(), union];
        (s, groups)
    }

    #[test]
    fn two_objects_apart_one_cluster_holds_are_split_by_place() {
        let (s, groups) = two_objects_apart();
        // No merge given: the candidate is the group's two_means.
        let sel = select_clustered(&s.points(), &groups, &[None, None], camera(), THR_PX).unwrap();
        assert_eq!(sel.motions, 3);
        for t in 1..=2 {
            assert!(kept_together(&s.truth, &sel.labels, t) > 0.9, "object {t}");
        }
    }

    #[test]
    fn groups_beyond_a_clustered_subset_are_split_by_place_too() {
        let (s, groups) = two_objects_apart();
        let sel = select_groups(
            &s.points(),
            &groups,
            GroupOrigin::Extended,
            camera(),
            THR_PX,
        )
        .unwrap();
        assert_eq!(sel.motions, 3);
        for t in 1..=2 {
            assert!(kept_together(&s.truth, &sel.labels, t) > 0.9, "object {t}");
        }
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
        let sel = select_clustered(
            &s.points(),
            std::slice::from_ref(&union),
            &[Some(sides)],
            camera(),
            THR_PX,
        )
        .unwrap();
        assert_eq!(sel.motions, 1);
        // Nor by place: 2-means finds the two regions, and each one's F
        // explains the other's matches.
        let by_place = two_means(&s.points(), &union, FITTED_MATCHES + 1).unwrap();
        assert!(
            by_place.iter().all(|side| side.len() >= 140),
            "{by_place:?}"
        );
        let sel = select_clustered(&s.points(), &[union], &[None], camera(), THR_PX).unwrap();
        assert_eq!(sel.motions, 1);
    }
}
