//! Model selection after the clustering: which of T-Linkage's clusters are
//! motions, by a principle instead of size rules (`min_cluster_size`, a
//! share of N, the merge's share of a cluster explained): a cluster is a
//! motion when the number of false alarms of its F, or of its
//! semi-calibrated F ([`semicalibrated`]), over every match or over the
//! matches of the block of the image its matches lie in ([`block`]), is
//! below 1, given the motions detected before it and the keypoints their
//! matches hold ([`nfa::detect`]: Moisan & Stival 2004, AC-RANSAC 2012,
//! MAC-RANSAC 2010; [`uniqueness`]), and its matches keep image-1
//! neighbours near along the epipolar lines ([`coherence`]); two clusters
//! one detected F explains are kept apart when the pair is more
//! meaningful than the union ([`exclusion`], Cao et al. 2007). GRIC merges
//! (Torr 1998), alone or with the NFA, were measured and not adopted
//! (results/README.md, "Tried and not adopted").
//!
//! Matches of no motion are outliers. Pure functions of the matches
//! (principal-point-centred, as [`crate::segment`] uses them), the
//! clustering's labels or groups and where they come from
//! ([`GroupOrigin`]), the camera ([`Camera`]: the image's rectangle in that
//! frame and the focal prior) and `thr_px`; every cluster's F is refitted
//! here by IRLS-Tukey (docs/method.md, Algorithm 1 step 3;
//! [`CLUSTER_REFIT_ITERS`] iterations) on its matches alone.

mod background;
mod binomial;
pub mod block;
pub mod coherence;
#[cfg(test)]
mod default_tests;
pub mod exclusion;
pub mod nfa;
pub mod semicalibrated;
pub mod split;
#[cfg(test)]
mod tests;
pub mod two_means;
pub mod uniqueness;
mod vote;

pub use background::{Background, ImageRect};
pub use binomial::ln_binomial_tail;

use clustering::dendrogram::Sides;
use geometry::{sampson_distances_squared, Correspondences, IrlsParams, IrlsWorkspace};
use nalgebra::Matrix3;
use thiserror::Error;

/// IRLS-Tukey iterations of each cluster's refit: the thesis's
/// `irls_iters` (Table 1), whatever the profile's.
pub const CLUSTER_REFIT_ITERS: usize = 5;

/// Input that cannot be selected from.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SelectionError {
    /// Labels and matches differ in number.
    #[error("selection: {labels} labels for {points} matches")]
    LengthMismatch {
        /// Number of labels.
        labels: usize,
        /// Number of matches.
        points: usize,
    },
    /// A group names a match beyond the last.
    #[error("selection: a group names match {index}, but there are {points} matches")]
    BadIndex {
        /// The index.
        index: usize,
        /// Number of matches.
        points: usize,
    },
    /// The split's sides and the groups differ in number.
    #[error("selection: {sides} entries of sides for {groups} groups (one per group, None where a group has none)")]
    SidesMismatch {
        /// Number of entries of sides.
        sides: usize,
        /// Number of groups.
        groups: usize,
    },
    /// A label below −1.
    #[error("selection: label {label} of match {index} is below -1 (the outlier label)")]
    BadLabel {
        /// The match.
        index: usize,
        /// Its label.
        label: i32,
    },
    /// `thr_px` not finite and positive.
    #[error("selection: thr_px must be a finite number > 0, got {0}")]
    BadThreshold(f64),
    /// An image rectangle with a side of zero (or negative, or not finite)
    /// length: an image with a zero side, or a principal point not finite.
    #[error("selection: the image spans [{}, {}] x [{}, {}] px around the principal point, which has no area", .0.min[0], .0.max[0], .0.min[1], .0.max[1])]
    BadImage(ImageRect),
    /// A focal prior not finite and positive.
    #[error("selection: the focal prior must be a finite number of px > 0, got {0}")]
    BadFocal(f64),
}

/// Where the groups come from: it decides whether a detected
/// semi-calibrated F is polished on its support ([`nfa::detect`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupOrigin {
    /// Every match was clustered: a group holds its motion's matches.
    Clustered,
    /// A subset was clustered and the other matches joined its clusters by
    /// preference ([`crate::extend_labels`]): a motion's matches may lie
    /// in several groups.
    Extended,
}

/// What the selection knows of the camera that took both images.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// The images' rectangle around the principal point: the domain of the
    /// NFA's background.
    pub image: ImageRect,
    /// The focal prior (px) of each group's semi-calibrated model
    /// ([`semicalibrated`]); max(W, H) by default, and 0.5–4× the true
    /// focal costs little (docs/method.md).
    pub focal_px: f64,
}

impl Camera {
    /// A camera of images of `size` (W, H) px, principal point at the
    /// centre, focal prior max(W, H).
    ///
    /// ```
    /// use segmentation::selection::{Camera, ImageRect};
    /// let c = Camera::centred((640, 480));
    /// assert_eq!((c.image, c.focal_px), (ImageRect::centred((640, 480)), 640.0));
    /// ```
    pub fn centred(size: (u32, u32)) -> Self {
        Self {
            image: ImageRect::centred(size),
            focal_px: f64::from(size.0.max(size.1)),
        }
    }
}

/// The clusters that are motions.
#[derive(Debug, Clone, PartialEq)]
pub struct Selection {
    /// Per match: its motion 0, 1, … (numbered by first appearance) or −1.
    pub labels: Vec<i32>,
    /// Number of motions.
    pub motions: usize,
}

impl Selection {
    /// `labels` (motions numbered 0, 1, …, −1 outliers) with their number
    /// of motions.
    fn of(labels: Vec<i32>) -> Self {
        let motions = labels.iter().map(|&l| l + 1).max().unwrap_or(0) as usize;
        Self { labels, motions }
    }
}

/// The IRLS-Tukey parameters of every cluster refit of the selection:
/// [`CLUSTER_REFIT_ITERS`] iterations, `thr_px` the inlier bound.
fn refit_params(thr_px: f64) -> IrlsParams {
    IrlsParams {
        thr_px,
        max_iters: CLUSTER_REFIT_ITERS,
        ..IrlsParams::default()
    }
}

/// Motions and outliers from the clustering's `labels` (−1 outliers) of
/// the principal-point-centred `points`, every match clustered:
/// [`select_groups`] of the labels' clusters ([`GroupOrigin::Clustered`]);
/// `camera` holds the images' rectangle in the points' frame (the
/// background's domain) and the focal prior, `thr_px` is the inlier
/// threshold (the NFA's largest threshold and the refits' inlier bound).
pub fn select(
    points: &Correspondences,
    labels: &[i32],
    camera: Camera,
    thr_px: f64,
) -> Result<Selection, SelectionError> {
    check(points, labels, camera, thr_px)?;
    let groups = groups_of(labels);
    let no_merges = vec![None; groups.len()];
    let labels = by_nfa(
        points,
        &groups,
        &no_merges,
        GroupOrigin::Clustered,
        &camera,
        thr_px,
    );
    Ok(Selection::of(labels))
}

fn check(
    points: &Correspondences,
    labels: &[i32],
    camera: Camera,
    thr_px: f64,
) -> Result<(), SelectionError> {
    if labels.len() != points.len() {
        return Err(SelectionError::LengthMismatch {
            labels: labels.len(),
            points: points.len(),
        });
    }
    if let Some((index, &label)) = labels.iter().enumerate().find(|(_, &l)| l < -1) {
        return Err(SelectionError::BadLabel { index, label });
    }
    check_scene(camera, thr_px)
}

fn check_scene(camera: Camera, thr_px: f64) -> Result<(), SelectionError> {
    if !(thr_px.is_finite() && thr_px > 0.0) {
        return Err(SelectionError::BadThreshold(thr_px));
    }
    if !camera.image.is_valid() {
        return Err(SelectionError::BadImage(camera.image));
    }
    if !(camera.focal_px.is_finite() && camera.focal_px > 0.0) {
        return Err(SelectionError::BadFocal(camera.focal_px));
    }
    Ok(())
}

/// The motions among `groups` (lists of indices into the
/// principal-point-centred `points`, e.g. T-Linkage's clusters, or those of
/// a subset of the matches, `origin` saying which) by a-contrario
/// detection over every match ([`nfa::detect`]; `camera` gives the
/// background's domain and the focal prior of each group's semi-calibrated
/// model), each group first split in two by place or by displacement
/// where it holds two motions ([`split`], [`two_means::two_means`],
/// [`two_means::two_means_by_displacement`]), labelled so: a match
/// of a detected group takes its motion; a group not detected joins, as a
/// whole, the detected F that explains most of its matches within
/// `thr_px` (those it explains take its label, the others the nearest
/// detected F within `thr_px`, or −1); a match of no group takes the
/// nearest detected F within `thr_px`, or −1. The cost is linear in the
/// number of matches for a given number of groups.
///
/// ```
/// use geometry::Correspondences;
/// use segmentation::selection::{select_groups, Camera, GroupOrigin};
/// // No group: no motion, every match an outlier.
/// let p = [[0.0, 0.0]; 20];
/// let pts = Correspondences::new(&p, &p).unwrap();
/// let (origin, camera) = (GroupOrigin::Clustered, Camera::centred((640, 480)));
/// let s = select_groups(&pts, &[], origin, camera, 2.5).unwrap();
/// assert_eq!((s.motions, s.labels), (0, vec![-1; 20]));
/// ```
pub fn select_groups(
    points: &Correspondences,
    groups: &[Vec<usize>],
    origin: GroupOrigin,
    camera: Camera,
    thr_px: f64,
) -> Result<Selection, SelectionError> {
    check_indices(points, groups.iter().flatten())?;
    check_scene(camera, thr_px)?;
    let no_merges = vec![None; groups.len()];
    let labels = by_nfa(points, groups, &no_merges, origin, &camera, thr_px);
    Ok(Selection::of(labels))
}

/// [`select_groups`] where every match was clustered
/// ([`GroupOrigin::Clustered`]), each group first replaced by the two
/// sides of its last merge (`sides[g]`, from
/// [`clustering::dendrogram::last_sides`]), or else by the two sides of
/// its [`two_means::two_means`], or else by those of its
/// [`two_means::two_means_by_displacement`], where they are two motions (the
/// conditions of [`split`]).
///
/// Errors: those of [`select_groups`], a side's index out of range,
/// `sides` and `groups` of different lengths.
pub fn select_clustered(
    points: &Correspondences,
    groups: &[Vec<usize>],
    sides: &[Option<Sides>],
    camera: Camera,
    thr_px: f64,
) -> Result<Selection, SelectionError> {
    if sides.len() != groups.len() {
        return Err(SelectionError::SidesMismatch {
            sides: sides.len(),
            groups: groups.len(),
        });
    }
    let in_sides = sides.iter().flatten().flatten().flatten();
    check_indices(points, groups.iter().flatten().chain(in_sides))?;
    check_scene(camera, thr_px)?;
    let labels = by_nfa(
        points,
        groups,
        sides,
        GroupOrigin::Clustered,
        &camera,
        thr_px,
    );
    Ok(Selection::of(labels))
}

/// Labels after [`nfa::detect`] of the groups, each first replaced by the
/// two sides of its last merge (`sides[g]`, None where no dendrogram gives
/// one) or else of its [`two_means::two_means`] or else of its
/// [`two_means::two_means_by_displacement`] where they are two motions
/// ([`split`]), the refits made with [`refit_params`]: the detected groups'
/// matches keep their group; another group joins, as a whole, the detected
/// F that explains (within `thr_px`, the band that explains a match in the
/// detection) the most of its matches: those it explains take its label,
/// the others the detected F nearest to them within `thr_px`, or are
/// outliers; a match of no group takes the detected F nearest to it within
/// `thr_px`, or is an outlier. Last, a match labelled by the nearest F
/// alone (its group, if any, did not bring it to that F) that several
/// detected Fs explain takes the label of its neighbours among those
/// ([`vote::vote_ambiguous`]).
fn by_nfa(
    points: &Correspondences,
    groups: &[Vec<usize>],
    sides: &[Option<Sides>],
    origin: GroupOrigin,
    camera: &Camera,
    thr_px: f64,
) -> Vec<i32> {
    let irls = refit_params(thr_px);
    let fitting = nfa::Fitting {
        points,
        camera,
        thr_px,
        irls: &irls,
    };
    let (groups, fits) = split::split_groups(&fitting, groups, sides);
    let detections = nfa::detect_fitted(&fitting, &groups, fits, origin);
    label_detected(points, &groups, &detections, thr_px)
}

/// Every index in `indices` names one of `points`
/// ([`SelectionError::BadIndex`] for the first that does not).
fn check_indices<'a>(
    points: &Correspondences,
    mut indices: impl Iterator<Item = &'a usize>,
) -> Result<(), SelectionError> {
    match indices.find(|&&m| m >= points.len()) {
        Some(&index) => Err(SelectionError::BadIndex {
            index,
            points: points.len(),
        }),
        None => Ok(()),
    }
}

/// [`by_nfa`]'s labels given its detections.
fn label_detected(
    points: &Correspondences,
    groups: &[Vec<usize>],
    detections: &[nfa::Detection],
    thr_px: f64,
) -> Vec<i32> {
    let residuals: Vec<&Vec<f64>> = detections.iter().map(|d| &d.residuals).collect();
    let mut assigned = by_nearest_f(&residuals, points.len(), thr_px);
    let mut held = vec![false; points.len()];
    join_undetected_groups(groups, &residuals, thr_px, &mut assigned, &mut held);
    for (d, det) in detections.iter().enumerate() {
        for &m in &groups[det.group] {
            assigned[m] = d as i32;
            held[m] = true;
        }
    }
    vote::vote_ambiguous(points, &residuals, &held, thr_px, &mut assigned);
    renumber(&assigned)
}

/// Per match: the detection whose F (`residuals[d]`) is nearest within
/// `thr_px`, or −1.
fn by_nearest_f(residuals: &[&Vec<f64>], n: usize, thr_px: f64) -> Vec<i32> {
    let nearest = |m: usize| {
        residuals
            .iter()
            .enumerate()
            .filter(|(_, r)| r[m] <= thr_px)
            .min_by(|a, b| a.1[m].total_cmp(&b.1[m]))
            .map_or(-1, |(d, _)| d as i32)
    };
    (0..n).map(nearest).collect()
}

/// Each group joins, as a whole, the detection that explains the most of
/// its matches: those it explains take its label and are `held` (the
/// clustering placed them).
fn join_undetected_groups(
    groups: &[Vec<usize>],
    residuals: &[&Vec<f64>],
    thr_px: f64,
    assigned: &mut [i32],
    held: &mut [bool],
) {
    for g in groups {
        let explained = |r: &[f64]| g.iter().filter(|&&m| r[m] <= thr_px).count();
        let joined =
            (0..residuals.len()).max_by_key(|&d| (explained(residuals[d]), std::cmp::Reverse(d)));
        if let Some(d) = joined {
            g.iter()
                .filter(|&&m| residuals[d][m] <= thr_px)
                .for_each(|&m| {
                    assigned[m] = d as i32;
                    held[m] = true;
                });
        }
    }
}

/// The matches of each label ≥ 0, in label order, increasing.
fn groups_of(labels: &[i32]) -> Vec<Vec<usize>> {
    let count = labels.iter().map(|&l| l + 1).max().unwrap_or(0) as usize;
    let mut groups = vec![Vec::new(); count];
    for (i, &l) in labels.iter().enumerate() {
        if l >= 0 {
            groups[l as usize].push(i);
        }
    }
    groups.retain(|g| !g.is_empty());
    groups
}

/// Labels ≥ 0 renumbered 0, 1, … by first appearance.
fn renumber(labels: &[i32]) -> Vec<i32> {
    let mut map = std::collections::HashMap::new();
    labels
        .iter()
        .map(|&l| {
            if l < 0 {
                return -1;
            }
            let next = map.len() as i32;
            *map.entry(l).or_insert(next)
        })
        .collect()
}

/// The F of `members` (at least 8) refitted by IRLS-Tukey on those matches
/// alone, started from their 8-point; their Hartley-normalised 8-point
/// when the refit fails (it drops below 8 inliers on a small cluster);
/// None when that fails too.
pub(crate) fn refit(
    points: &Correspondences,
    members: &[usize],
    irls: &IrlsParams,
) -> Option<Matrix3<f64>> {
    if members.len() < geometry::MIN_POINTS {
        return None;
    }
    let subset = points.subset(members).ok()?;
    let sample: Vec<usize> = (0..subset.len()).collect();
    IrlsWorkspace::new()
        .run(&subset, &sample, None, irls)
        .map(|s| s.f)
        .or_else(|_| geometry::eight_point_normalized(&subset))
        .ok()
}

/// Sampson distances (px) of every match to `f`.
pub(crate) fn sampson_residuals(points: &Correspondences, f: &Matrix3<f64>) -> Vec<f64> {
    let mut r = vec![0.0; points.len()];
    sampson_distances_squared(f, points, &mut r);
    r.iter_mut().for_each(|v| *v = v.sqrt());
    r
}
