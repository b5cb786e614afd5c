//! Criterion benchmarks of the geometry hot paths:
//! * the Sampson batch over N = 2000 matches (preference matrix, Eq. 38),
//!   reported as point-evaluations per second, and the consensus set of
//!   one F at N = 300 (step 2's choice among a minimal sample's solutions);
//! * IRLS-Tukey refinement from an 8-point sample at N = 300 (step 3), the
//!   text's variant and the reference code's (plain refit, polish);
//! * the three 8-point variants on a minimal sample (step 2);
//! * the minimal solver (5-point E) on noisy minimal samples, one sample
//!   per call.
//!
//! Run with `cargo bench -p geometry --bench geometry`.

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use geometry::{
    eight_point_normalized, eight_point_plain, eight_point_weighted, five_point, refine_irls_tukey,
    sampson_consensus, sampson_distances_squared, sampson_residuals_signed, Correspondences,
    IrlsParams, IrlsWorkspace,
};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A scene like an AdelaideRMF sequence: two rigid motions (130 and 90
/// matches, 0.5 px noise) and 80 gross outliers, N = 300. Returns the
/// correspondences and the indices of the first motion.
fn two_motion_scene(seed: u64) -> (Correspondences, usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let a = common::random_scene(&mut rng, 130, 0, 0.5);
    let b = common::random_scene(&mut rng, 90, 80, 0.5);
    let (mut p1, mut p2) = common::point_lists(&a.points);
    let (q1, q2) = common::point_lists(&b.points);
    p1.extend(q1);
    p2.extend(q2);
    (Correspondences::new(&p1, &p2).unwrap(), 130)
}

fn sampson_batch(c: &mut Criterion) {
    let mut group = c.benchmark_group("sampson_batch");
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let n = 2000;
    let scene = common::random_scene(&mut rng, n / 2, n / 2, 1.0);
    let f = scene.f_true;
    let mut out = vec![0.0; n];
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function(BenchmarkId::new("squared", n), |b| {
        b.iter(|| sampson_distances_squared(black_box(&f), black_box(&scene.points), &mut out))
    });
    group.bench_function(BenchmarkId::new("signed", n), |b| {
        b.iter(|| sampson_residuals_signed(black_box(&f), black_box(&scene.points), &mut out))
    });
    group.finish();

    // The consensus set of a minimal sample's solution (step 2), N = 300,
    // in full and against a bound it cannot reach.
    let mut group = c.benchmark_group("sampson_consensus");
    let (points, _) = two_motion_scene(2);
    let f = eight_point_normalized(&points.subset(&(0..8).collect::<Vec<_>>()).unwrap()).unwrap();
    let mut inliers = Vec::new();
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("full_300", |b| {
        b.iter(|| sampson_consensus(black_box(&f), black_box(&points), 6.25, 0, &mut inliers))
    });
    group.bench_function("give_up_300", |b| {
        b.iter(|| sampson_consensus(black_box(&f), black_box(&points), 6.25, 250, &mut inliers))
    });
    group.finish();
}

fn irls(c: &mut Criterion) {
    let mut group = c.benchmark_group("irls_tukey");
    let (points, first_motion) = two_motion_scene(2);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    // A pool of clean minimal samples of the first motion, cycled through.
    let samples: Vec<Vec<usize>> = (0..64)
        .map(|_| common::sample_indices(&mut rng, first_motion, 8))
        .collect();
    let initials: Vec<_> = samples
        .iter()
        .map(|s| eight_point_normalized(&points.subset(s).unwrap()).unwrap())
        .collect();
    let params = IrlsParams::default();
    let mut workspace = IrlsWorkspace::new();
    let mut k = 0;
    group.bench_function("workspace_n300", |b| {
        b.iter(|| {
            k = (k + 1) % samples.len();
            workspace.run(black_box(&points), &samples[k], Some(&initials[k]), &params)
        })
    });
    let mut k = 0;
    group.bench_function("workspace_with_8pt_n300", |b| {
        b.iter(|| {
            k = (k + 1) % samples.len();
            workspace.run(black_box(&points), &samples[k], None, &params)
        })
    });
    let reference = IrlsParams::reference_code();
    let mut k = 0;
    group.bench_function("workspace_reference_n300", |b| {
        b.iter(|| {
            k = (k + 1) % samples.len();
            workspace.run(
                black_box(&points),
                &samples[k],
                Some(&initials[k]),
                &reference,
            )
        })
    });
    let mut k = 0;
    group.bench_function("fresh_n300", |b| {
        b.iter(|| {
            k = (k + 1) % samples.len();
            refine_irls_tukey(black_box(&points), &samples[k], Some(&initials[k]), &params)
        })
    });
    group.finish();
}

fn eight_point(c: &mut Criterion) {
    let mut group = c.benchmark_group("eight_point");
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let scene = common::random_scene(&mut rng, 8, 0, 0.5);
    let weights = [1.0, 0.9, 0.5, 0.7, 1.0, 0.3, 0.8, 0.6];
    group.bench_function("plain_8", |b| {
        b.iter(|| eight_point_plain(black_box(&scene.points)))
    });
    group.bench_function("normalized_8", |b| {
        b.iter(|| eight_point_normalized(black_box(&scene.points)))
    });
    group.bench_function("weighted_8", |b| {
        b.iter(|| eight_point_weighted(black_box(&scene.points), black_box(&weights)))
    });
    // The over-determined path (e.g. refitting a cluster for the FROB metric).
    let scene = common::random_scene(&mut rng, 100, 0, 0.5);
    group.bench_function("plain_100", |b| {
        b.iter(|| eight_point_plain(black_box(&scene.points)))
    });
    group.bench_function("normalized_100", |b| {
        b.iter(|| eight_point_normalized(black_box(&scene.points)))
    });
    group.finish();
}

/// The calibrated bearings of a 5-point sample, image 1 and image 2.
type BearingPair = (Vec<Vector3<f64>>, Vec<Vector3<f64>>);

fn minimal_solvers(c: &mut Criterion) {
    let mut group = c.benchmark_group("minimal");
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    // A pool of noisy minimal samples, cycled through.
    let samples: Vec<_> = (0..32)
        .map(|_| common::random_scene(&mut rng, 7, 0, 0.5))
        .collect();
    let bearings: Vec<BearingPair> = samples
        .iter()
        .map(|s| {
            (0..5)
                .map(|i| {
                    let ([a, b], [c, d]) = (s.points.point1(i), s.points.point2(i));
                    (
                        Vector3::new(a / s.focal1, b / s.focal1, 1.0),
                        Vector3::new(c / s.focal2, d / s.focal2, 1.0),
                    )
                })
                .unzip()
        })
        .collect();
    let mut k = 0;
    group.bench_function("five_point", |b| {
        b.iter(|| {
            k = (k + 1) % bearings.len();
            five_point(black_box(&bearings[k].0), black_box(&bearings[k].1))
        })
    });
    group.finish();
}

criterion_group!(benches, sampson_batch, irls, eight_point, minimal_solvers);
criterion_main!(benches);
