//! Two motions one F explains, kept apart: when the model of the group
//! being detected explains most of another group's matches, the pair is
//! kept apart if it is more meaningful than their union,
//!
//! `NFA(group without the other) · NFA(other | group) < NFA(group)`,
//!
//! the merging criterion of a-contrario grouping (Cao, Delon, Desolneux,
//! Musé & Sur, "A unified framework for detecting groups and application
//! to shape recognition", JMIV 2007), read as a split: two NFAs of the
//! detection's own form (`nfa::detect`), the second given the first
//! model's explained matches. A fundamental matrix has 7 degrees of
//! freedom, so one F often fits two small rigid objects about as well as
//! their own Fs do (results/notes/selection.md, "Exclusion"); T-Linkage
//! keeps their clusters apart when their hypotheses differ, and the test
//! keeps them apart when each is tighter under its own model than both are
//! under one.
//!
//! Only where every match was clustered ([`super::GroupOrigin::Clustered`]):
//! beyond a clustered subset a motion's matches lie in several groups, each
//! significant with its own fit, and the test splits one motion into its
//! fragments (results/notes/selection.md).

use super::nfa::{fit_given, Explained, Fitting, GroupFit, FITTED_MATCHES};
use super::uniqueness::Keypoints;

/// What the detection tests a group against: what its fits are made
/// with, the groups and the constants of `nfa::detect`.
pub(super) struct Context<'a> {
    pub fitting: &'a Fitting<'a>,
    pub groups: &'a [Vec<usize>],
    /// ln of the tests every NFA counts before its models and scopes.
    pub ln_tests: f64,
    pub keypoints: &'a Keypoints,
}

/// The group chosen for detection: its fit, the model of its smallest
/// NFA and that NFA.
pub(super) struct Chosen<'a> {
    pub group: usize,
    pub fit: &'a GroupFit,
    pub model: usize,
    pub ln_nfa: f64,
}

/// The groups of `remaining` to keep apart from the chosen group: those
/// of whose matches that count (given `explained`) its model explains
/// more than half, and for which the pair is more meaningful than the
/// union (both NFAs below 1 and their product below the chosen group's).
pub(super) fn kept_apart(
    ctx: &Context,
    remaining: &[usize],
    chosen: &Chosen,
    explained: &Explained,
) -> Vec<usize> {
    remaining
        .iter()
        .copied()
        .filter(|&h| h != chosen.group && mostly_explained(ctx, h, chosen, explained))
        .filter(|&h| pair_wins(ctx, h, chosen, explained))
        .collect()
}

/// Whether the chosen model explains more than half of the matches of
/// group `h` that count, and at least 8 of them count.
fn mostly_explained(ctx: &Context, h: usize, chosen: &Chosen, explained: &Explained) -> bool {
    let residuals = &chosen.fit.models[chosen.model].residuals;
    let own: Vec<usize> = explained.counting(&ctx.groups[h]).collect();
    let within = own
        .iter()
        .filter(|&&m| residuals[m] <= ctx.fitting.thr_px)
        .count();
    own.len() > FITTED_MATCHES && 2 * within > own.len()
}

/// `ln NFA(chosen without h) + ln NFA(h | chosen without h) < ln
/// NFA(chosen)`, both terms below 0: the chosen group scored with h's
/// matches barred (its best model and scope again), then h fitted and
/// scored given what that model explains outside h.
fn pair_wins(ctx: &Context, h: usize, chosen: &Chosen, explained: &Explained) -> bool {
    let group_h = &ctx.groups[h];
    let barred = explained.barring(group_h);
    let (alone, model) = chosen
        .fit
        .significance(&barred, ctx.ln_tests, ctx.fitting.thr_px);
    if !alone.is_significant() {
        return false;
    }
    let residuals = leaving_out(chosen.fit.models[model].residuals.clone(), group_h);
    let mut given = explained.clone();
    given.add(&residuals, ctx.fitting.thr_px, ctx.keypoints);
    let mut cache = None;
    let Some(fit) = fit_given(ctx.fitting, group_h, &given, &mut cache) else {
        return false;
    };
    let (other, _) = fit.significance(&given, ctx.ln_tests, ctx.fitting.thr_px);
    other.is_significant() && alone.ln_nfa + other.ln_nfa < chosen.ln_nfa
}

/// `residuals` with `matches` at +∞: a detection's distances that leave
/// the matches of the groups kept apart from it to their own tests.
pub(super) fn leaving_out<'a>(
    mut residuals: Vec<f64>,
    matches: impl IntoIterator<Item = &'a usize>,
) -> Vec<f64> {
    for &m in matches {
        residuals[m] = f64::INFINITY;
    }
    residuals
}

#[cfg(test)]
mod tests {
    use super::super::nfa::{detect, Detection};
    use super::super::tests::{
        background, camera, mover_at, one_motion_in_two_regions, Scene, THR_PX,
    };
    use super::super::{groups_of, refit_params, GroupOrigin};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// The background (400 matches over the image), a mover of 60 at
    /// `px` (median Sampson distance) from the background's F in a
    /// 140 × 140 px box, and 40 outliers.
    fn near_mover(px: f64, seed: u64) -> Scene {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut s = Scene::default();
        s.add_motion(&mut rng, &background(), 400, (-300.0, 300.0));
        let region = (60.0, 200.0);
        s.add_motion(&mut rng, &mover_at(seed, px, region), 60, region);
        s.add_outliers(&mut rng, 40);
        s
    }

    fn detect_in(s: &Scene, origin: GroupOrigin) -> Vec<Detection> {
        let (points, groups) = (s.points(), groups_of(&s.truth));
        let irls = refit_params(THR_PX);
        detect(&points, &groups, origin, &camera(), THR_PX, &irls)
    }

    #[test]
    fn a_mover_the_background_f_explains_is_kept_apart_where_every_match_was_clustered() {
        for seed in 0..6 {
            let s = near_mover(1.0, seed);
            let mover: Vec<usize> = (0..s.truth.len()).filter(|&m| s.truth[m] == 1).collect();
            // Without the test (beyond a clustered subset) the background's
            // F explains most of the mover, which is not detected.
            let extended = detect_in(&s, GroupOrigin::Extended);
            let explained = mover
                .iter()
                .filter(|&&m| extended[0].residuals[m] <= THR_PX)
                .count();
            assert!(2 * explained > mover.len(), "seed {seed}: {explained}");
            assert_eq!(extended.len(), 1, "seed {seed}");
            // With it, both are detected and the background's detection
            // leaves the mover's matches to it.
            let clustered = detect_in(&s, GroupOrigin::Clustered);
            let found: Vec<usize> = clustered.iter().map(|d| d.group).collect();
            assert_eq!(found, [0, 1], "seed {seed}");
            assert!(mover
                .iter()
                .all(|&m| clustered[0].residuals[m].is_infinite()));
        }
    }

    #[test]
    fn one_motion_in_two_groups_is_not_kept_apart() {
        let (s, _) = one_motion_in_two_regions();
        let found: Vec<usize> = detect_in(&s, GroupOrigin::Clustered)
            .iter()
            .map(|d| d.group)
            .collect();
        assert_eq!(found, [0]);
    }
}
