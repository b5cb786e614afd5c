//! The memory bound, the profiles and the merge, on synthetic scenes of
//! the `quick` preset.

mod support;

use segmentation::{segment, Params, Profile, SegmentationError};
use support::{in_pool, matches, quick_scene};

#[test]
fn a_memory_bound_refuses_before_sampling_and_names_the_key() {
    let scene = quick_scene(1, 900);
    let params = Params::default().with(|q| {
        q.max_memory_mb = 1;
        q.sampling.num_samples = 20_000;
    });
    let err = segment(&matches(&scene), &params).unwrap_err();
    let SegmentationError::MemoryBound {
        n_points,
        n_hypotheses,
        required_mb,
        limit_mb,
    } = &err
    else {
        panic!("expected a memory bound error, got {err}");
    };
    assert_eq!(
        (*n_points, *n_hypotheses, *limit_mb),
        (scene.points1.len(), 20_000, 1)
    );
    assert!(*required_mb > 1);
    assert!(err.to_string().contains("max_memory_mb = 1"), "{err}");
    // A bound above the need changes nothing.
    let roomy = Params::default().with(|q| {
        q.max_memory_mb = 10_000;
        q.sampling.num_samples = 300;
    });
    let unbounded = roomy.clone().with(|q| q.max_memory_mb = 0);
    let a = segment(&matches(&scene), &roomy).unwrap();
    let b = segment(&matches(&scene), &unbounded).unwrap();
    assert_eq!(a.labels, b.labels);
}

#[test]
fn every_profile_segments_a_synthetic_scene_at_any_thread_count() {
    let scene = quick_scene(2, 900);
    for profile in Profile::ALL {
        let params = profile.params().with(|q| q.sampling.num_samples = 300);
        let seg = in_pool(1, || segment(&matches(&scene), &params).unwrap());
        assert_eq!(seg.labels.len(), scene.points1.len(), "{profile:?}");
        assert!(seg.labels.iter().any(|&l| l >= 0), "{profile:?}");
        let two = in_pool(2, || segment(&matches(&scene), &params).unwrap());
        assert_eq!(seg.labels, two.labels, "{profile:?}: threads");
    }
}

#[test]
fn merging_only_joins_clusters() {
    use segmentation::FinalAssignment;
    for (category, index) in [(1, 900), (2, 900), (2, 901)] {
        let scene = quick_scene(category, index);
        let none = Params::default().with(|q| {
            q.sampling.num_samples = 300;
            q.selection.final_assignment = FinalAssignment::None;
        });
        let merge = none
            .clone()
            .with(|q| q.selection.final_assignment = FinalAssignment::Merge);
        let a = segment(&matches(&scene), &none).unwrap().labels;
        let b = segment(&matches(&scene), &merge).unwrap().labels;
        // The outliers are the same, and each merged cluster is a union of
        // clusters: matches together before stay together.
        for i in 0..a.len() {
            assert_eq!(a[i] < 0, b[i] < 0, "match {i}");
            for k in 0..a.len() {
                if a[i] >= 0 && a[i] == a[k] {
                    assert_eq!(b[i], b[k], "matches {i} and {k}");
                }
            }
        }
    }
}
