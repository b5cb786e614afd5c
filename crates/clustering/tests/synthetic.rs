//! End to end on synthetic two-view scenes (residuals from
//! geometry::sampson_distances_squared): exact recovery of the motions on
//! noiseless data, and agreement of the column-at-a-time build with the
//! closure build.

#[path = "../benches/support/scene.rs"]
mod scene;

use clustering::{
    reference, BinaryPreferenceMatrix, ClusteringParams, Linkage, PreferenceMatrix, Preferences,
};
use geometry::sampson_distances_squared;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The labels equal the ground truth up to a renaming of the clusters, on
/// the points where `keep` is true.
fn same_partition(labels: &[i32], truth: &[usize], keep: &[bool]) -> bool {
    let mut forward = std::collections::HashMap::new();
    let mut backward = std::collections::HashMap::new();
    labels
        .iter()
        .zip(truth)
        .zip(keep)
        .filter(|(_, &k)| k)
        .all(|((&l, &t), _)| {
            *forward.entry(l).or_insert(t) == t && *backward.entry(t).or_insert(l) == l
        })
}

fn residual_columns(scene: &scene::Scene, hypotheses: &[nalgebra::Matrix3<f64>]) -> Vec<Vec<f64>> {
    hypotheses
        .iter()
        .map(|f| {
            let mut column = vec![0.0; scene.points.len()];
            sampson_distances_squared(f, &scene.points, &mut column);
            column
        })
        .collect()
}

#[test]
fn noiseless_motions_are_recovered_exactly() {
    for (seed, motions) in [(1u64, 2usize), (2, 3), (3, 4)] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let scene = scene::synthetic_scene(&mut rng, 60 * motions, motions, 0.0, 0.0);
        let exact = scene::Perturbation {
            angle_deg: 0.0,
            shift: 0.0,
        };
        let hypotheses = scene::hypotheses(&mut rng, &scene, 400, 0.7, exact);
        let columns = residual_columns(&scene, &hypotheses);
        // thr = 0.5 px: noiseless inliers have residual ~0. A point that also
        // satisfies another motion's epipolar constraint within 5τ prefers
        // both motions' hypotheses and may join either: it is ambiguous.
        let tau = 0.25;
        let truth: Vec<_> = scene.motions.iter().map(|m| m.fundamental()).collect();
        let true_residuals = residual_columns(&scene, &truth);
        let unambiguous: Vec<bool> = (0..scene.points.len())
            .map(|i| {
                (0..motions)
                    .filter(|&m| true_residuals[m][i] <= 5.0 * tau)
                    .count()
                    == 1
            })
            .collect();
        let ambiguous = unambiguous.iter().filter(|&&u| !u).count();
        assert!(
            ambiguous * 4 < scene.points.len(),
            "{ambiguous} ambiguous points"
        );
        for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
            let params = ClusteringParams {
                linkage,
                ..Default::default()
            };
            let mut builder = params.preference_builder(scene.points.len(), tau).unwrap();
            for column in &columns {
                builder.push_residuals(column).unwrap();
            }
            let clustering = params.cluster(&builder.finish());
            assert_eq!(
                clustering.clusters_after_filter, motions,
                "{linkage:?} seed {seed}"
            );
            assert!(
                same_partition(&clustering.labels, &scene.labels, &unambiguous),
                "{linkage:?} seed {seed}: {:?}",
                clustering.labels
            );
        }
    }
}

#[test]
fn realistic_scene_matches_the_reference() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let scene = scene::synthetic_scene(&mut rng, 150, 3, 0.15, 0.5);
    let hypotheses = scene::hypotheses(&mut rng, &scene, 600, 0.8, scene::REFINED);
    let columns = residual_columns(&scene, &hypotheses);
    let tau = 2.5 * 2.5;
    let residual = |i: usize, j: usize| columns[j][i];
    let p = PreferenceMatrix::from_residuals(150, 600, tau, residual).unwrap();
    assert!(p.density() > 0.1, "density {}", p.density());
    let fast = clustering::t_linkage(&p, 8);
    assert_eq!(fast, reference::t_linkage(&p, 8));
    assert!(fast.merges.len() > 100);
    let b = BinaryPreferenceMatrix::from_residuals(150, 600, tau, residual).unwrap();
    assert_eq!(clustering::j_linkage(&b, 8), reference::j_linkage(&b, 8));
    // The column-at-a-time build gives the same matrix.
    let mut builder = clustering::PreferenceBuilder::new(Linkage::TLinkage, 150, tau).unwrap();
    for column in &columns {
        builder.push_residuals(column).unwrap();
    }
    assert_eq!(builder.finish(), Preferences::Continuous(p));
}
