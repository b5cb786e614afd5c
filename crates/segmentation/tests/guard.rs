//! Nothing lost, nothing silent: the memory guard of `max_memory_mb = 0`,
//! cancellation, and the input's coordinate checks and warnings.

mod support;

use segmentation::{
    check_available_memory, check_matches, mem_available, memory_need, segment,
    segment_cancellable, Cancel, InputWarning, Matches, Params, SegmentationError,
    MAX_COORDINATE_PX,
};
use std::time::Duration;
use support::{in_pool, matches, quick_scene};

/// The default with every match clustered (`cluster_subset = 0`): the
/// need then grows as N².
fn every_match_clustered() -> Params {
    Params::default().with(|q| q.sampling.cluster_subset = 0)
}

#[test]
fn the_automatic_bound_refuses_with_the_figures_and_what_to_change() {
    let params = every_match_clustered();
    let need = memory_need(5_000_000, &params);
    let available = Some(need.total() - 1);
    let err = check_available_memory(5_000_000, &params, available).unwrap_err();
    let SegmentationError::MemoryAvailable {
        n_matches,
        n_clustered,
        n_hypotheses,
        needed_mb,
        available_mb,
        ..
    } = &err
    else {
        panic!("expected MemoryAvailable, got {err}");
    };
    assert_eq!((*n_matches, *n_clustered), (5_000_000, 5_000_000));
    assert_eq!(*n_hypotheses, params.sampling.num_samples);
    assert_eq!(*needed_mb, need.total().div_ceil(1_000_000));
    assert_eq!(*available_mb, (need.total() - 1) / 1_000_000);
    let text = err.to_string();
    for hint in [
        "fewer matches",
        "cluster_subset",
        "num_samples",
        "max_memory_mb",
    ] {
        assert!(text.contains(hint), "{text}");
    }
    // Exactly enough passes; an unknown figure and an explicit bound too.
    assert!(check_available_memory(5_000_000, &params, Some(need.total())).is_ok());
    assert!(check_available_memory(5_000_000, &params, None).is_ok());
    let explicit = Params::default().with(|q| q.max_memory_mb = 5);
    assert!(check_available_memory(5_000_000, &explicit, Some(1)).is_ok());
}

#[test]
fn a_cluster_subset_or_fewer_samples_lower_the_need() {
    // Uniform sampling: guided sampling's co-inlier counts do not shrink with M.
    let params = every_match_clustered().with(|q| {
        q.sampling.num_samples = 3000;
        q.sampling.sampling = segmentation::Sampling::Uniform;
    });
    let full = memory_need(5_000_000, &params);
    let subset = memory_need(
        5_000_000,
        &params.clone().with(|q| q.sampling.cluster_subset = 1000),
    );
    let fewer = memory_need(
        5_000_000,
        &params.clone().with(|q| q.sampling.num_samples = 300),
    );
    assert!(subset.clustering * 1000 < full.clustering);
    assert!(fewer.total() * 5 < full.total());
    assert_eq!(
        full.clustering,
        clustering::required_memory(
            params.clustering.linkage,
            5_000_000,
            params.sampling.num_samples,
            0.2
        )
    );
}

#[test]
fn mem_available_reads_the_meminfo_line_in_kib() {
    let text = "MemTotal:       32000000 kB\nMemFree:  1 kB\nMemAvailable:   1000 kB\n";
    assert_eq!(mem_available(text), Some(1_024_000));
    assert_eq!(mem_available("MemAvailable: many kB\n"), None);
    assert_eq!(mem_available("MemAvailable: 5 MB\n"), None);
}

#[test]
fn a_small_explicit_bound_refuses_a_large_input_before_sampling() {
    let n = 200_000;
    let p1: Vec<[f64; 2]> = (0..n)
        .map(|i| [(i % 640) as f64, (i % 480) as f64])
        .collect();
    let params = every_match_clustered().with(|q| q.max_memory_mb = 50);
    let err = segment(&Matches::new(&p1, &p1, (640, 480)), &params).unwrap_err();
    assert!(
        matches!(err, SegmentationError::MemoryBound { limit_mb: 50, .. }),
        "{err}"
    );
}

#[test]
fn a_set_flag_stops_the_segmentation() {
    let scene = quick_scene(2, 900);
    let cancel = Cancel::new();
    cancel.cancel();
    let err = segment_cancellable(&matches(&scene), &Params::default(), &cancel).unwrap_err();
    assert!(matches!(err, SegmentationError::Interrupted), "{err}");
    // Not set: the result of the plain call.
    let params = Params::default().with(|q| q.sampling.num_samples = 300);
    let plain = segment(&matches(&scene), &params).unwrap();
    let free = segment_cancellable(&matches(&scene), &params, &Cancel::new()).unwrap();
    assert_eq!(plain.labels, free.labels);
}

#[test]
fn a_flag_set_from_another_thread_interrupts_the_sampling() {
    // A run of many hypotheses, cancelled while it samples.
    let scene = quick_scene(2, 901);
    let params = Params::default().with(|q| {
        q.sampling.num_samples = 1_000_000;
        q.max_memory_mb = 1_000_000;
    });
    let cancel = Cancel::new();
    let result = std::thread::scope(|s| {
        let run = s.spawn(|| {
            in_pool(2, || {
                segment_cancellable(&matches(&scene), &params, &cancel)
            })
        });
        std::thread::sleep(Duration::from_millis(100));
        cancel.cancel();
        run.join().unwrap()
    });
    assert!(matches!(result, Err(SegmentationError::Interrupted)));
}

/// The quick scene with one coordinate replaced.
fn with_value(row: usize, column: usize, value: f64) -> SegmentationError {
    let scene = quick_scene(1, 900);
    let (mut p1, mut p2) = (scene.points1.clone(), scene.points2.clone());
    match column {
        0 | 1 => p1[row][column] = value,
        _ => p2[row][column - 2] = value,
    }
    let m = Matches::new(&p1, &p2, scene.image_size);
    segment(&m, &Params::default()).unwrap_err()
}

#[test]
fn absurd_and_non_finite_coordinates_are_refused_naming_row_column_value() {
    let err = with_value(7, 3, 1e200);
    assert!(
        matches!(err, SegmentationError::InvalidCoordinate { row: 7, column: "y2", value, .. } if value == 1e200),
        "{err}"
    );
    let text = err.to_string();
    assert!(
        text.contains("row 7, column y2: coordinate 1e200"),
        "{text}"
    );
    let err = with_value(3, 0, f64::NAN);
    assert!(err.to_string().contains("row 3, column x1"), "{err}");
    let err = with_value(0, 2, -2.0 * MAX_COORDINATE_PX);
    assert!(err.to_string().contains("row 0, column x2"), "{err}");
}

#[test]
fn points_far_outside_the_image_are_reported_with_an_example_row() {
    let scene = quick_scene(1, 900);
    let mut p2 = scene.points2.clone();
    for row in [12, 40, 41] {
        p2[row] = [5e4, 100.0];
    }
    let m = Matches::new(&scene.points1, &p2, scene.image_size);
    let clean = Matches::new(&scene.points1, &scene.points2, scene.image_size);
    assert_eq!(check_matches(&clean).unwrap(), vec![]);
    let params = Params::default().with(|q| q.sampling.num_samples = 300);
    let seg = segment(&m, &params).unwrap();
    assert_eq!(seg.warnings.len(), 1, "{:?}", seg.warnings);
    let InputWarning::FarOutside {
        count,
        total,
        row,
        x2,
        ..
    } = &seg.warnings[0]
    else {
        panic!("{:?}", seg.warnings);
    };
    assert_eq!((*count, *total, *row, *x2), (3, p2.len(), 12, 5e4));
    assert!(seg.warnings[0].to_string().contains("3 of"));
}

#[test]
fn an_image_size_given_as_height_width_is_reported() {
    // Points that fill a 640 x 480 image, passed with (480, 640).
    let p1: Vec<[f64; 2]> = (0..40)
        .map(|i| [16.0 * i as f64, 12.0 * i as f64])
        .collect();
    let transposed = Matches::new(&p1, &p1, (480, 640));
    let warnings = check_matches(&transposed).unwrap();
    assert_eq!(
        warnings,
        vec![InputWarning::TransposedImageSize {
            width: 480,
            height: 640
        }]
    );
    let text = warnings[0].to_string();
    assert!(
        text.contains("(480, 640)") && text.contains("Pass (640, 480)"),
        "{text}"
    );
    assert_eq!(
        check_matches(&Matches::new(&p1, &p1, (640, 480))).unwrap(),
        vec![]
    );
}
