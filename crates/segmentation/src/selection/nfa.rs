//! A-contrario significance of a cluster's fundamental matrix: its number of
//! false alarms (NFA) against a background of matches that fall anywhere in
//! the images (Moisan & Stival, "A probabilistic criterion to detect rigid
//! point matches between two images and estimate the fundamental matrix",
//! IJCV 2004; Moisan, Moulon & Monasse, "Automatic homographic registration
//! of a pair of images, with a contrario elimination of outliers", IPOL 2012:
//! AC-RANSAC's threshold chosen per model), and the greedy detection of
//! several models that removes what each detected model explains before
//! testing the next (Rabin, Delon, Gousseau & Moisan, "MAC-RANSAC: a robust
//! algorithm for the recognition of multiple objects", 3DPVT 2010).

pub use super::background::{Background, ImageRect};
use super::binomial::ln_binomial_tail;
use super::block::{block_count, inside, smallest_block};
use super::coherence::ln_incoherence;
use super::exclusion::{kept_apart, leaving_out, Chosen, Context};
use super::semicalibrated::{semicalibrated_fit, SEMICALIBRATED_FITTED};
use super::uniqueness::Keypoints;
use super::{refit, sampson_residuals};
use super::{Camera, GroupOrigin};
use geometry::{Correspondences, IrlsParams};
use nalgebra::Matrix3;

/// The degrees of freedom of a fundamental matrix: a fit on k matches can
/// bring 7 of them onto its epipolar lines whatever they are (the 7-point
/// solver), so the NFA's binomial counts the other `k − 7` among the other
/// `n − 7` (AC-RANSAC's `k − s` exponent, Moisan & Stival 2004).
pub const FITTED_MATCHES: usize = 7;

/// Thresholds are tried at every support k up to this, then on a geometric
/// grid (ratio [`K_GRID_RATIO`]) and at the largest support.
const K_DENSE: usize = 64;
/// Ratio of consecutive supports tried above [`K_DENSE`].
const K_GRID_RATIO: f64 = 1.02;

/// A model's a-contrario score.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Significance {
    /// `ln NFA` at the best threshold (−∞ for an exact fit of many matches;
    /// +∞ with fewer than [`FITTED_MATCHES`] + 1 matches within `thr_px`).
    pub ln_nfa: f64,
    /// The threshold of the smallest NFA, px (the k-th smallest residual).
    pub threshold_px: f64,
    /// The number of matches within it.
    pub support: usize,
}

impl Significance {
    /// No support: never significant.
    const NONE: Self = Self {
        ln_nfa: f64::INFINITY,
        threshold_px: 0.0,
        support: 0,
    };

    /// `NFA < 1`: the model is meaningful.
    pub fn is_significant(&self) -> bool {
        self.ln_nfa < 0.0
    }
}

/// The smallest `ln NFA` of a model over its thresholds (AC-RANSAC):
/// `sorted` holds the Sampson distances (px) of the `n = sorted.len()`
/// matches tested, increasing; for a support k the threshold is the k-th
/// smallest distance `eps_k ≤ max_threshold_px` and
/// `NFA(k) = tests · P(Bin(n − 7, p(eps_k)) ≥ k − 7)` with `p` the
/// [`Background`]'s and `ln_tests = ln(number of tests)`.
pub fn significance(
    sorted: &[f64],
    ln_tests: f64,
    background: &Background,
    max_threshold_px: f64,
) -> Significance {
    significance_fitted(
        sorted,
        ln_tests,
        background,
        max_threshold_px,
        FITTED_MATCHES,
    )
}

/// [`significance`] of a model that fits `fitted` matches exactly.
pub fn significance_fitted(
    sorted: &[f64],
    ln_tests: f64,
    background: &Background,
    max_threshold_px: f64,
    fitted: usize,
) -> Significance {
    let n = sorted.len();
    let within = sorted.partition_point(|&r| r <= max_threshold_px);
    if within <= fitted {
        return Significance::NONE;
    }
    let s = fitted as u64;
    let mut best = Significance::NONE;
    let mut k = fitted + 1;
    loop {
        let eps = sorted[k - 1];
        let p = background.probability(eps);
        let ln_nfa = ln_tests + ln_binomial_tail(n as u64 - s, k as u64 - s, p);
        if ln_nfa < best.ln_nfa {
            best = Significance {
                ln_nfa,
                threshold_px: eps,
                support: k,
            };
        }
        if k == within {
            return best;
        }
        k = if k < K_DENSE {
            k + 1
        } else {
            ((k as f64 * K_GRID_RATIO).ceil() as usize).min(within)
        };
    }
}

/// A group of matches detected as a motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Detection {
    /// Index of the group in the input.
    pub group: usize,
    /// Its F: of its two models (its F refitted by IRLS-Tukey on its
    /// matches not explained by the detections before it, and its
    /// semi-calibrated F) the one of smaller NFA, polished on its support
    /// unless it is the semi-calibrated one of a [`GroupOrigin::Clustered`]
    /// group.
    pub f: Matrix3<f64>,
    /// Its score given the detections before it.
    pub significance: Significance,
    /// The Sampson distances (px) of every match to `f`; +∞ for the
    /// matches of the groups kept apart from it ([`super::exclusion`]).
    pub residuals: Vec<f64>,
}

/// The groups (lists of match indices) that are motions, greedily, the
/// most meaningful first (MAC-RANSAC's order): in each round every group
/// not yet detected is scored given the detections so far, and the one of
/// smallest NFA is detected when that NFA is below 1 and its matches are
/// coherent (image-1 neighbours stay neighbours along the epipolar lines,
/// [`super::coherence`]; a group that is not is passed over for good);
/// when the smallest NFA is not below 1 the detection ends.
///
/// Given the detections, a match does not count (neither in n nor in k)
/// when a detected F explains it: when it lies within `thr_px` of it (the
/// inlier threshold of the preferences, Eq. 38; AC-RANSAC's own threshold
/// of the detected F, smaller, would leave its noise tail to support a
/// copy of it), or when it shares a keypoint with a match the detected F
/// newly explained and lies beyond `thr_px` of that F (a keypoint has one
/// correspondence, [`super::uniqueness`]). A group is scored with two
/// models fitted on its matches that count (`fit_given`; the fits are
/// reused while none of them becomes explained): its F refitted by
/// IRLS-Tukey, 7 fitted matches,
/// and its semi-calibrated F `K⁻ᵀ E K⁻¹` at `camera.focal_px`, the best of
/// its five-point candidates ([`semicalibrated_fit`]), 5 fitted matches;
/// each model is tested over every match and, when the group's image-1
/// points lie in a block of the image ([`super::block`]), over the
/// matches of that block alone (x₁ uniform over it,
/// [`Background::with_x1_in`]); the group's NFA is the smallest of these.
/// A detected refitted F is polished on its support
/// (`polish_on_support`); a detected semi-calibrated F only
/// when the groups are [`GroupOrigin::Extended`], where a motion's matches
/// beyond the clustered subset may lie in another group: polished into a
/// free F on its support, a semi-calibrated F that every match was
/// clustered for would reach into a neighbouring object's matches
/// (results/notes/selection.md). So a fragment of a detected motion
/// keeps no more than the few matches of its noise tail, and a mover
/// beyond `thr_px` of the background's F keeps the matches there. Where
/// every match was clustered, a group not yet detected most of whose
/// matches the detected model explains is kept apart from it when the
/// pair is more meaningful than the union ([`super::exclusion`]): the
/// detection is scored, polished and explains without that group's
/// matches, which are left to its own test.
///
/// The number of tests is `G · (N − 7) · 2 · 2`, times the candidates for
/// the semi-calibrated model and the [`block_count`] blocks for a test
/// over a block: G groups of at least 8 matches, N − 7 thresholds each,
/// two models, two scopes (the image, a block) weighted equally (a union
/// bound).
pub fn detect(
    points: &Correspondences,
    groups: &[Vec<usize>],
    origin: GroupOrigin,
    camera: &Camera,
    thr_px: f64,
    irls: &IrlsParams,
) -> Vec<Detection> {
    let fits = groups.iter().map(|_| None).collect();
    let fitting = Fitting {
        points,
        camera,
        thr_px,
        irls,
    };
    detect_fitted(&fitting, groups, fits, origin)
}

/// What every fit and score of a group is made with: the matches, the
/// camera, the inlier threshold `thr_px` and the refit's parameters.
pub(super) struct Fitting<'a> {
    pub points: &'a Correspondences,
    pub camera: &'a Camera,
    pub thr_px: f64,
    pub irls: &'a IrlsParams,
}

/// [`detect`] with some groups' fits given nothing explained already made
/// (`fits[g]`, by [`fit_given`] with [`Explained::none`]; None: not made).
pub(super) fn detect_fitted(
    fitting: &Fitting,
    groups: &[Vec<usize>],
    mut fits: Vec<Option<Cached>>,
    origin: GroupOrigin,
) -> Vec<Detection> {
    let &Fitting {
        points,
        thr_px,
        irls,
        ..
    } = fitting;
    let n = points.len();
    let mut remaining: Vec<usize> = (0..groups.len())
        .filter(|&i| groups[i].len() > FITTED_MATCHES)
        .collect();
    if remaining.is_empty() || n <= FITTED_MATCHES {
        return Vec::new();
    }
    let ln_groups = (remaining.len() as f64).ln();
    let ln_tests = ln_groups + ((n - FITTED_MATCHES) as f64).ln();
    let keypoints = Keypoints::new(points);
    let mut explained = Explained::none(n);
    let mut detections = Vec::new();
    let ctx = Context {
        fitting,
        groups,
        ln_tests,
        keypoints: &keypoints,
    };
    loop {
        let best = remaining
            .iter()
            .enumerate()
            .filter_map(|(pos, &i)| {
                let fit = fit_given(fitting, &groups[i], &explained, &mut fits[i])?;
                let (significance, model) = fit.significance(&explained, ln_tests, thr_px);
                Some((pos, i, significance, model))
            })
            .min_by(|a, b| a.2.ln_nfa.total_cmp(&b.2.ln_nfa).then(a.1.cmp(&b.1)));
        let Some((pos, group, significance, model)) = best else {
            break;
        };
        if !significance.is_significant() {
            break;
        }
        remaining.swap_remove(pos);
        let fit = fits[group]
            .take()
            .and_then(|c| c.fit)
            .expect("a scored group has its fit");
        let apart = match origin {
            GroupOrigin::Clustered => {
                let chosen = Chosen {
                    group,
                    fit: &fit,
                    model,
                    ln_nfa: significance.ln_nfa,
                };
                kept_apart(&ctx, &remaining, &chosen, &explained)
            }
            GroupOrigin::Extended => Vec::new(),
        };
        let apart_matches = || apart.iter().flat_map(|&h| &groups[h]);
        // What the detection may explain: all but the kept-apart matches.
        let barred = (!apart.is_empty()).then(|| explained.barring(apart_matches()));
        let (significance, model) = match &barred {
            Some(barred) => fit.significance(barred, ln_tests, thr_px),
            None => (significance, model),
        };
        let support = barred.as_ref().unwrap_or(&explained);
        let model = fit.models.into_iter().nth(model).expect("a scored model");
        if !is_coherent(points, &groups[group], &explained, &model.f, ln_groups) {
            continue;
        }
        let (f, residuals) = match (model.kind, origin) {
            (ModelKind::Semicalibrated, GroupOrigin::Clustered) => (model.f, model.residuals),
            _ => polish_on_support(points, model.f, model.residuals, support, thr_px, irls),
        };
        let residuals = leaving_out(residuals, apart_matches());
        explained.add(&residuals, thr_px, &keypoints);
        detections.push(Detection {
            group,
            f,
            significance,
            residuals,
        });
    }
    detections
}

/// Whether the matches of `group` that count map image-1 neighbours to
/// neighbours along the epipolar lines of `f` beyond chance, given `G`
/// groups tested (`ln_groups = ln G`): `G · P(R ≤ r) < 1`
/// ([`ln_incoherence`], a rank sum).
fn is_coherent(
    points: &Correspondences,
    group: &[usize],
    explained: &Explained,
    f: &Matrix3<f64>,
    ln_groups: f64,
) -> bool {
    let own: Vec<usize> = explained.counting(group).collect();
    ln_groups + ln_incoherence(points, &own, f) < 0.0
}

/// Rounds of [`polish_on_support`].
const POLISH_ROUNDS: usize = 2;

/// A detected F refitted by IRLS-Tukey on every match within `thr_px` of
/// it that no earlier detection explains, [`POLISH_ROUNDS`] times: the
/// local optimisation of LO-RANSAC (Chum, Matas & Kittler, DAGM 2003). A
/// group's F is fitted on the group's matches alone, which beyond a
/// clustered subset are few; refitted on its whole support it explains
/// the whole motion, whose remainder would otherwise be detected again.
/// The significance is that of the F before; the polish changes what the
/// detection explains and how it labels. Keeps `f` when a refit fails.
fn polish_on_support(
    points: &Correspondences,
    mut f: Matrix3<f64>,
    mut residuals: Vec<f64>,
    explained: &Explained,
    thr_px: f64,
    irls: &IrlsParams,
) -> (Matrix3<f64>, Vec<f64>) {
    for _ in 0..POLISH_ROUNDS {
        let support: Vec<usize> = residuals
            .iter()
            .enumerate()
            .filter(|&(m, &r)| r <= thr_px && !explained.0[m])
            .map(|(m, _)| m)
            .collect();
        match refit(points, &support, irls) {
            Some(refitted) => {
                f = refitted;
                residuals = sampson_residuals(points, &f);
            }
            None => break,
        }
    }
    (f, residuals)
}

/// The matches the detections so far explain: within `thr_px` of a
/// detected F, or sharing a keypoint with a match a detection explained
/// when that detection's F leaves it beyond `thr_px` ([`super::uniqueness`]).
#[derive(Debug, Clone)]
pub struct Explained(Vec<bool>);

impl Explained {
    /// Nothing explained among `n` matches.
    pub(super) fn none(n: usize) -> Self {
        Self(vec![false; n])
    }

    /// These, and `matches` too.
    pub(super) fn barring<'a>(&self, matches: impl IntoIterator<Item = &'a usize>) -> Self {
        let mut barred = self.clone();
        for &m in matches {
            barred.0[m] = true;
        }
        barred
    }

    /// The matches of `group` that count: those no detection explains.
    pub(super) fn counting<'a>(&'a self, group: &'a [usize]) -> impl Iterator<Item = usize> + 'a {
        group.iter().copied().filter(|&m| !self.0[m])
    }

    /// The matches a detected F of Sampson distances `residuals` explains,
    /// and those that share a keypoint with one it newly explains and
    /// that it does not explain (a keypoint has one correspondence).
    pub(super) fn add(&mut self, residuals: &[f64], thr_px: f64, keypoints: &Keypoints) {
        let newly: Vec<usize> = (0..residuals.len())
            .filter(|&m| residuals[m] <= thr_px && !self.0[m])
            .collect();
        for &m in &newly {
            for j in keypoints.sharing(m) {
                self.0[j] |= residuals[j] > thr_px;
            }
        }
        for (e, &r) in self.0.iter_mut().zip(residuals) {
            *e |= r <= thr_px;
        }
    }
}

/// The models a group is scored with, fitted on its matches that count:
/// its F refitted by IRLS-Tukey and its semi-calibrated F
/// ([`semicalibrated_fit`]), and the block those matches lie in. They
/// change only when one of those matches becomes explained, so a round
/// reuses the last round's fit of a group none of whose matches the last
/// detection explained.
pub(super) struct GroupFit {
    pub(super) models: Vec<Model>,
    /// Per match: whether it lies in the group's block (None: no block
    /// holds the group).
    block: Option<Vec<bool>>,
}

/// Which matches a model is tested over.
#[derive(Debug, Clone, Copy)]
enum Scope<'a> {
    /// Every match.
    Image,
    /// The matches of the group's block (the mask of [`inside`]).
    Block(&'a [bool]),
}

/// The scopes of a group's tests: the image and a block.
const SCOPES: f64 = 2.0;

/// The two models of a group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ModelKind {
    /// Its F refitted by IRLS-Tukey: 7 fitted matches, one candidate.
    Refitted,
    /// `K⁻ᵀ E K⁻¹` at the focal prior: 5 fitted matches, chosen among its
    /// five-point candidates.
    Semicalibrated,
}

impl ModelKind {
    /// The matches its fit brings onto their lines whatever they are.
    fn fitted(self) -> usize {
        match self {
            Self::Refitted => FITTED_MATCHES,
            Self::Semicalibrated => SEMICALIBRATED_FITTED,
        }
    }
}

/// One model of a group, with what its NFA needs.
pub(super) struct Model {
    kind: ModelKind,
    f: Matrix3<f64>,
    /// Sampson distances (px) of every match to `f`.
    pub(super) residuals: Vec<f64>,
    /// The matches by increasing distance, so that each significance
    /// takes the distances of the matches that count in order.
    by_distance: Vec<u32>,
    background: Background,
    /// Its background over the group's block, when one holds the group.
    block_background: Option<Background>,
    /// ln of the number of candidates it was chosen among (0 for the
    /// refitted F, one candidate).
    ln_candidates: f64,
}

impl Model {
    fn new(
        points: &Correspondences,
        image: &ImageRect,
        block: Option<&ImageRect>,
        kind: ModelKind,
        f: Matrix3<f64>,
        candidates: usize,
    ) -> Self {
        let residuals = sampson_residuals(points, &f);
        let mut by_distance: Vec<u32> = (0..residuals.len() as u32).collect();
        by_distance.sort_unstable_by(|&a, &b| {
            residuals[a as usize]
                .total_cmp(&residuals[b as usize])
                .then(a.cmp(&b))
        });
        Self {
            kind,
            f,
            residuals,
            by_distance,
            background: Background::new(&f, image),
            block_background: block.map(|b| Background::with_x1_in(&f, b, image)),
            ln_candidates: (candidates as f64).ln(),
        }
    }

    /// Its significance over the matches of `scope` that count,
    /// `ln_tests` the tests beyond its own candidates and the blocks.
    fn significance(
        &self,
        explained: &Explained,
        ln_tests: f64,
        thr_px: f64,
        scope: Scope,
    ) -> Significance {
        let (background, mask, ln_scope) = match (scope, &self.block_background) {
            (Scope::Image, _) => (&self.background, None, 0.0),
            (Scope::Block(mask), Some(b)) => (b, Some(mask), (block_count() as f64).ln()),
            (Scope::Block(_), None) => return Significance::NONE,
        };
        // The distances that count, increasing: the sort of them.
        let r: Vec<f64> = self
            .by_distance
            .iter()
            .map(|&m| m as usize)
            .filter(|&m| !explained.0[m] && mask.map_or(true, |inside| inside[m]))
            .map(|m| self.residuals[m])
            .collect();
        let ln_tests = ln_tests + self.ln_candidates + ln_scope;
        let fitted = self.kind.fitted();
        significance_fitted(&r, ln_tests, background, thr_px, fitted)
    }
}

impl GroupFit {
    /// The smallest significance of its models over the image and its
    /// block, each NFA counting the models and the scopes as tests (a union
    /// bound), and which model it is.
    pub(super) fn significance(
        &self,
        explained: &Explained,
        ln_tests: f64,
        thr_px: f64,
    ) -> (Significance, usize) {
        let ln_tests = ln_tests + (self.models.len() as f64 * SCOPES).ln();
        let scopes = [Some(Scope::Image), self.block.as_deref().map(Scope::Block)];
        self.models
            .iter()
            .enumerate()
            .flat_map(|(i, m)| {
                scopes
                    .iter()
                    .flatten()
                    .map(move |&scope| (m.significance(explained, ln_tests, thr_px, scope), i))
            })
            .min_by(|a, b| a.0.ln_nfa.total_cmp(&b.0.ln_nfa).then(a.1.cmp(&b.1)))
            .expect("a group fit has a model")
    }
}

/// A group's last refit: how many of its matches counted, and the fit
/// (None when the refit failed, which is then not tried again until that
/// number changes).
pub(super) struct Cached {
    own: usize,
    fit: Option<GroupFit>,
}

/// The fit of `group` given `explained`, from `cache` when none of its
/// matches became explained since; None when fewer than 8 of its matches
/// count or the fit fails.
pub(super) fn fit_given<'a>(
    fitting: &Fitting,
    group: &[usize],
    explained: &Explained,
    cache: &'a mut Option<Cached>,
) -> Option<&'a GroupFit> {
    let &Fitting {
        points,
        camera,
        thr_px,
        irls,
    } = fitting;
    let own_len = explained.counting(group).count();
    if own_len <= FITTED_MATCHES {
        *cache = None;
        return None;
    }
    if cache.as_ref().map(|c| c.own) != Some(own_len) {
        let own: Vec<usize> = explained.counting(group).collect();
        let image = &camera.image;
        let block = smallest_block(points, &own, image);
        let model =
            |kind, f, candidates| Model::new(points, image, block.as_ref(), kind, f, candidates);
        let refitted = refit(points, &own, irls).map(|f| model(ModelKind::Refitted, f, 1));
        let semicalibrated = semicalibrated_fit(points, &own, camera.focal_px, thr_px)
            .map(|s| model(ModelKind::Semicalibrated, s.f, s.candidates));
        let models: Vec<Model> = refitted.into_iter().chain(semicalibrated).collect();
        let block = block.map(|b| inside(points, &b));
        let fit = (!models.is_empty()).then_some(GroupFit { models, block });
        *cache = Some(Cached { own: own_len, fit });
    }
    cache.as_ref().and_then(|c| c.fit.as_ref())
}

#[cfg(test)]
mod tests {
    use super::super::tests::{camera, compact_object, THR_PX};
    use super::super::{groups_of, refit_params};
    use super::*;

    #[test]
    fn a_compact_small_object_is_found_over_its_block_and_not_over_the_image() {
        // Objects of 9 and 10 matches in an 80 × 80 px box (objects of 11
        // or more at 8 px are significant over the image too).
        for (k, seed) in [(9, 1), (10, 0), (10, 3)] {
            let s = compact_object(k, seed);
            let (points, groups) = (s.points(), groups_of(&s.truth));
            let (camera, irls) = (camera(), refit_params(THR_PX));
            let detections = detect(
                &points,
                &groups,
                GroupOrigin::Clustered,
                &camera,
                THR_PX,
                &irls,
            );
            let found: Vec<usize> = detections.iter().map(|d| d.group).collect();
            assert_eq!(found, [0, 1], "k {k} seed {seed}");
            // Given the background's F, each of the object's models over
            // every match: NFA ≥ 1 (the tests of detect: 2 groups, N − 7
            // thresholds, 2 models, 2 scopes).
            let mut explained = Explained::none(points.len());
            explained.add(&detections[0].residuals, THR_PX, &Keypoints::new(&points));
            let mut cache = None;
            let fitting = Fitting {
                points: &points,
                camera: &camera,
                thr_px: THR_PX,
                irls: &irls,
            };
            let fit = fit_given(&fitting, &groups[1], &explained, &mut cache)
                .expect("the object is fitted");
            assert!(fit.block.is_some(), "k {k} seed {seed}: a block holds it");
            let ln_tests = (2.0 * (points.len() - 7) as f64 * 4.0).ln();
            for m in &fit.models {
                let image = m.significance(&explained, ln_tests, THR_PX, Scope::Image);
                assert!(!image.is_significant(), "k {k} seed {seed}: {image:?}");
            }
        }
    }

    #[test]
    fn exact_support_is_meaningful_and_chance_support_is_not() {
        let image = ImageRect::centred((640, 480));
        // 100 matches at 0.1 px among 1000 spread up to 100 px: meaningful.
        let mut r: Vec<f64> = (0..1000).map(|i| 0.1 * i as f64).collect();
        r[..100].iter_mut().for_each(|v| *v = 0.1);
        r.sort_by(f64::total_cmp);
        let bg = Background::new(
            &Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0),
            &image,
        );
        let s = significance(&r, (1000f64).ln(), &bg, 2.5);
        assert!(s.is_significant() && s.support >= 100, "{s:?}");
        // Distances uniform in [0, 320] px: the fraction within eps is about
        // what the band predicts, never meaningful.
        let r: Vec<f64> = (0..1000).map(|i| 0.32 * i as f64).collect();
        let s = significance(&r, (1000f64).ln(), &bg, 2.5);
        assert!(!s.is_significant(), "{s:?}");
        // Seven matches within thr_px are what any F fits: no test.
        assert_eq!(significance(&r[..7], 0.0, &bg, 2.5), Significance::NONE);
    }
}
