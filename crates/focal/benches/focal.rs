//! Benchmarks of the focal solvers and the KDE consensus.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use focal::{
    bougnoux, focal_consensus, robust_focals, robust_focals_multi_start, ConsensusParams,
    FocalWeights, OnFailure, RobustFocalParams, ADELAIDE_MAX_ITERS, ADELAIDE_WEIGHT_SETS,
};
use nalgebra::Matrix3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// F of a noisy 8-point estimate (row 1 of the PoseLib fixture, kind
/// noise_0.5; PoseLib needs 4 iterations on it).
fn noisy_f() -> Matrix3<f64> {
    Matrix3::new(
        8.56185036959288e-07,
        -2.097448953241165e-05,
        0.016941065621662234,
        2.1245468220718325e-05,
        4.013419871588667e-06,
        0.02314471109277397,
        -0.013675075456424468,
        -0.02357224811818454,
        0.9992170250580255,
    )
}

fn bench(c: &mut Criterion) {
    let f = noisy_f();
    let params = RobustFocalParams {
        f_prior: 1024.0,
        weights: FocalWeights::new(5e-4, 1.0, 5e-4, 1.0),
        max_iters: 100,
    };
    let est = robust_focals(&f, &params).expect("the benchmark F has a solution");
    println!(
        "robust_focals on the benchmark F: f1 {:.3}, f2 {:.3}, {} iterations",
        est.f1, est.f2, est.iterations
    );
    c.bench_function("robust_focals/one_weight_set", |b| {
        b.iter(|| robust_focals(black_box(&f), black_box(&params)))
    });
    c.bench_function("robust_focals_multi_start/adelaide_4_sets", |b| {
        b.iter(|| {
            robust_focals_multi_start(
                black_box(&f),
                1024.0,
                &ADELAIDE_WEIGHT_SETS,
                ADELAIDE_MAX_ITERS,
                OnFailure::Report,
            )
        })
    });
    c.bench_function("bougnoux", |b| {
        b.iter(|| bougnoux(black_box(&f), [0.0, 0.0], [0.0, 0.0]))
    });

    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let a = Normal::new(800.0, 40.0).unwrap();
    let bn = Normal::new(1300.0, 60.0).unwrap();
    let values: Vec<f64> = (0..5000)
        .map(|i| {
            if i % 10 < 7 {
                a.sample(&mut rng)
            } else {
                bn.sample(&mut rng)
            }
        })
        .collect();
    let cp = ConsensusParams::default();
    c.bench_function("focal_consensus/5000_values", |b| {
        b.iter(|| focal_consensus(black_box(&values), black_box(&cp)))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bench
}
criterion_main!(benches);
