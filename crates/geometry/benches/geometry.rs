//! Criterion benchmarks of the geometry hot paths:
//! * the Sampson batch over N = 2000 matches (preference matrix, Eq. 38),
//!   reported as point-evaluations per second;
//! * IRLS-Tukey refinement from an 8-point sample at N = 300 (step 3), the
//!   text's variant and the reference code's (plain refit, polish);
//! * the three 8-point variants on a minimal sample (step 2).
//!
//! Run with `cargo bench -p geometry --bench geometry`.

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use geometry::{
    eight_point_normalized, eight_point_plain, eight_point_weighted, refine_irls_tukey,
    sampson_distances_squared, sampson_residuals_signed, Correspondences, IrlsParams,
    IrlsWorkspace,
};
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

criterion_group!(benches, sampson_batch, irls, eight_point);
criterion_main!(benches);
