//! The switches that trade cost against accuracy: adaptive M, the duplicate
//! filter, the memory bound and the profiles, on synthetic scenes of the
//! `quick` preset.

mod support;

use geometry::sampson_distances_squared;
use segmentation::{
    generate_hypotheses, segment, segment_with, DuplicateFilter, HypothesisStatus, Method, Params,
    Profile, SegmentationError, SupportTracker,
};
use support::{in_pool, matches, quick_scene};

fn adaptive(batch: usize, tolerance: f64) -> Params {
    Params {
        num_samples: 600,
        adaptive_batch: batch,
        adaptive_tolerance: tolerance,
        ..Params::default()
    }
}

#[test]
fn adaptive_hypotheses_are_the_first_ones_of_the_fixed_run() {
    let scene = quick_scene(2, 900);
    let fixed = generate_hypotheses(&matches(&scene), &adaptive(0, 0.01)).unwrap();
    assert_eq!(fixed.models.len(), 600);
    // A tolerance of 1 stops after the second batch, 0 never stops early.
    for (tolerance, expected) in [(1.0, 200), (0.0, 600)] {
        let params = adaptive(100, tolerance);
        let generated = generate_hypotheses(&matches(&scene), &params).unwrap();
        assert_eq!(generated.models.len(), expected, "tolerance {tolerance}");
        assert_eq!(generated.models[..], fixed.models[..expected]);
        assert_eq!(generated.fitted[..], fixed.fitted[..expected]);
    }
}

#[test]
fn the_stop_rule_is_the_support_trackers() {
    // Replays the batches through a tracker: the run stops after the first
    // batch (from the second on) in which fewer than tolerance N points
    // gained, and not before.
    let scene = quick_scene(2, 901);
    let params = adaptive(50, 0.05);
    let generated = generate_hypotheses(&matches(&scene), &params).unwrap();
    let m = generated.models.len();
    assert!(
        m < 600,
        "the quick scene should settle before the cap, got {m}"
    );
    let n = generated.points.len();
    let mut tracker = SupportTracker::new(n, params.thr_px);
    let batches: Vec<_> = generated.models.chunks(50).collect();
    for (b, batch) in batches.iter().enumerate() {
        let gained = tracker.add_batch(&generated.points, batch);
        let stops = b >= 1 && (gained as f64) < 0.05 * n as f64;
        assert_eq!(stops, b + 1 == batches.len(), "batch {b}: {gained} gained");
    }
}

#[test]
fn adaptive_labels_do_not_depend_on_the_thread_count() {
    let scene = quick_scene(2, 900);
    let params = adaptive(50, 0.02);
    let one = in_pool(1, || segment(&matches(&scene), &params).unwrap());
    let two = in_pool(2, || segment(&matches(&scene), &params).unwrap());
    assert_eq!(one.labels, two.labels);
    assert_eq!(one.counts.generated, two.counts.generated);
}

#[test]
fn a_memory_bound_refuses_before_sampling_and_names_the_key() {
    let scene = quick_scene(1, 900);
    let params = Params {
        max_memory_mb: 1,
        num_samples: 20_000,
        ..Params::default()
    };
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
    let roomy = Params {
        max_memory_mb: 10_000,
        num_samples: 300,
        ..Params::default()
    };
    let unbounded = Params {
        max_memory_mb: 0,
        ..roomy.clone()
    };
    let a = segment(&matches(&scene), &roomy).unwrap();
    let b = segment(&matches(&scene), &unbounded).unwrap();
    assert_eq!(a.labels, b.labels);
}

#[test]
fn every_profile_segments_a_synthetic_scene() {
    let scene = quick_scene(2, 900);
    for profile in Profile::ALL {
        let params = Params {
            num_samples: 300,
            ..profile.params()
        };
        let seg = segment(&matches(&scene), &params).unwrap();
        assert_eq!(seg.labels.len(), scene.points1.len(), "{profile:?}");
        assert!(seg.labels.iter().any(|&l| l >= 0), "{profile:?}");
    }
}

#[test]
fn the_duplicate_filter_keeps_one_hypothesis_per_inlier_set() {
    let scene = quick_scene(2, 900);
    let params = Params {
        num_samples: 300,
        method: Method::Baseline,
        duplicate_filter: DuplicateFilter::SameInliers,
        ..Params::default()
    };
    let generated = generate_hypotheses(&matches(&scene), &params).unwrap();
    let seg = segment_with(&matches(&scene), &params, &generated, None).unwrap();
    // The naive reference: each refined model's inlier set, in order.
    let tau = params.thr_px * params.thr_px;
    let mut residuals = vec![0.0; generated.points.len()];
    let mut first_of = std::collections::HashMap::new();
    let mut duplicates = 0;
    for (j, model) in generated.models.iter().enumerate() {
        let Some(f) = model else { continue };
        sampson_distances_squared(f, &generated.points, &mut residuals);
        let set: Vec<bool> = residuals.iter().map(|&r| r <= tau).collect();
        let first = *first_of.entry(set).or_insert(j);
        let expected = if first == j {
            HypothesisStatus::Kept
        } else {
            duplicates += 1;
            HypothesisStatus::Duplicate
        };
        assert_eq!(seg.hypotheses[j].status, expected, "hypothesis {j}");
    }
    assert!(
        duplicates > 0,
        "refined hypotheses of one structure repeat inlier sets"
    );
    assert_eq!(seg.counts.kept, first_of.len());
    // Without the filter every refined hypothesis is kept.
    let all = Params {
        duplicate_filter: DuplicateFilter::None,
        ..params
    };
    let seg = segment_with(&matches(&scene), &all, &generated, None).unwrap();
    assert_eq!(seg.counts.kept, generated.refined().len());
}

#[test]
fn merging_only_joins_clusters() {
    use segmentation::FinalAssignment;
    for (category, index) in [(1, 900), (2, 900), (2, 901)] {
        let scene = quick_scene(category, index);
        let none = Params {
            num_samples: 300,
            ..Params::default()
        };
        let merge = Params {
            final_assignment: FinalAssignment::Merge,
            ..none.clone()
        };
        let merge_refit = Params {
            final_assignment: FinalAssignment::MergeRefit,
            ..none.clone()
        };
        let a = segment(&matches(&scene), &none).unwrap().labels;
        let b = segment(&matches(&scene), &merge).unwrap().labels;
        let c = segment(&matches(&scene), &merge_refit).unwrap().labels;
        let anchored = Params {
            final_assignment: FinalAssignment::MergeAnchored,
            ..none.clone()
        };
        let d = segment(&matches(&scene), &anchored).unwrap().labels;
        // The outliers are the same, and each merged cluster is a union of
        // clusters: matches together before stay together.
        for (a, b) in [(&a, &b), (&b, &c), (&b, &d)] {
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
}
