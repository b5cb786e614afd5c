//! The default pipeline ([`crate::segment`] with [`crate::Params::default`],
//! whose `final_assignment = "nfa"` ends in this module's selection) on the
//! hand-made scenes of `tests.rs`, end to end: the number of motions it
//! finds.

use super::tests::{background, kept_together, small_mover, Motion, Scene, SIZE};
use crate::{segment, Matches, Params};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The default's labels of `s` (its points shifted from the
/// principal-point-centred frame to pixels).
fn default_labels(s: &Scene) -> (Vec<i32>, usize) {
    let centre = [
        (f64::from(SIZE.0) - 1.0) / 2.0,
        (f64::from(SIZE.1) - 1.0) / 2.0,
    ];
    let px = |p: &Vec<[f64; 2]>| -> Vec<[f64; 2]> {
        p.iter()
            .map(|q| [q[0] + centre[0], q[1] + centre[1]])
            .collect()
    };
    let (p1, p2) = (px(&s.p1), px(&s.p2));
    let seg = segment(&Matches::new(&p1, &p2, SIZE), &Params::default()).unwrap();
    (seg.labels, seg.clusters.len())
}

#[test]
#[ignore = "not achieved: 4 motions for 3 (results/notes/selection.md, The default end to end)"]
fn the_default_finds_three_planted_motions_at_n_50000() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut s = Scene::default();
    s.add_motion(&mut rng, &background(), 30_000, (-300.0, 300.0));
    let left = Motion::new([0.0, -0.1, 0.02], [0.4, 0.0, -0.3]);
    s.add_motion(&mut rng, &left, 10_000, (-300.0, 0.0));
    let right = Motion::new([0.05, 0.08, 0.0], [-0.2, 0.3, 0.1]);
    s.add_motion(&mut rng, &right, 5000, (0.0, 300.0));
    s.add_outliers(&mut rng, 5000);
    let (labels, motions) = default_labels(&s);
    assert_eq!(motions, 3);
    for t in 0..3 {
        let together = kept_together(&s.truth, &labels, t);
        assert!(together > 0.9, "motion {t}: {together}");
    }
}

#[test]
fn the_default_finds_no_motion_in_pure_outliers_when_it_clusters_them_all() {
    for n in [200, 1000] {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let mut s = Scene::default();
        s.add_outliers(&mut rng, n);
        let (labels, motions) = default_labels(&s);
        assert_eq!(motions, 0, "N {n}");
        assert!(labels.iter().all(|&l| l == -1), "N {n}");
    }
}

#[test]
#[ignore = "not achieved: 1 motion at N 5000 (results/notes/selection.md, The default end to end)"]
fn the_default_finds_no_motion_in_pure_outliers_beyond_its_subset() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mut s = Scene::default();
    s.add_outliers(&mut rng, 5000);
    let (_, motions) = default_labels(&s);
    assert_eq!(motions, 0);
}

#[test]
#[ignore = "not achieved: 2 motions, but 66 % of the mover's matches together (results/notes/selection.md, The default end to end)"]
fn the_default_keeps_a_mover_of_two_percent_at_three_px_at_n_20000() {
    let s = small_mover(20_000, 3);
    let (labels, motions) = default_labels(&s);
    assert_eq!(motions, 2);
    let together = kept_together(&s.truth, &labels, 1);
    assert!(together > 0.8, "{together}");
}

#[test]
fn the_default_keeps_one_motion_of_identical_f_in_two_regions_as_one() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut s = Scene::default();
    let m = Motion::new([0.01, 0.05, 0.0], [0.3, 0.05, -0.2]);
    s.add_motion(&mut rng, &m, 150, (-300.0, -20.0));
    s.add_motion(&mut rng, &m, 150, (20.0, 300.0));
    s.add_outliers(&mut rng, 60);
    // add_motion labels the second call 1: the same F, one motion.
    let (labels, motions) = default_labels(&s);
    assert_eq!(motions, 1);
    let one: Vec<i32> = s
        .truth
        .iter()
        .map(|&t| if t < 0 { -1 } else { 0 })
        .collect();
    assert!(kept_together(&one, &labels, 0) > 0.9);
}
