//! Preference build (Eq. 38) and T-Linkage (Eq. 39–40) on realistic inputs.
//!
//! Inputs are synthetic two-view scenes with several rigid motions and 15 %
//! gross outliers; hypotheses are perturbed copies of the true motions (80 %)
//! or random motions (20 %), as refined hypotheses are; residuals are squared
//! Sampson distances (geometry::sampson_distances_squared), τ = thr_px².
//!
//! Unless named otherwise, every measurement runs inside a one-thread rayon
//! pool (one core). Groups, each measured twice — wall-clock time (`wall_*`)
//! and CPU time of the process (`cpu_*`, see `support/cpu_time.rs`; on a
//! shared machine the figure to hold against a one-core budget):
//! * `*_adelaide_n300_m5000` (thr 4.5 px, 3 motions): build, cluster, both,
//!   and the plain reference clustering;
//! * `*_hopef_n1000_m3000` (thr 2.5 px, 4 motions): the same, plus both on two
//!   threads and J-Linkage;
//! * `cpu_scaling_n` (M = 3000) and `cpu_scaling_m` (N = 500): clustering only.

#[path = "support/cpu_time.rs"]
mod cpu_time;
#[path = "support/scene.rs"]
mod scene;

use clustering::{
    j_linkage, reference, t_linkage, BinaryPreferenceMatrix, Linkage, PreferenceBuilder,
    PreferenceMatrix, Preferences,
};
use cpu_time::ProcessCpuTime;
use criterion::measurement::{Measurement, WallTime};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use geometry::{sampson_distances_squared, Correspondences};
use nalgebra::Matrix3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Duration;

/// A scene and its hypotheses: everything the clustering phase receives.
struct Input {
    points: Correspondences,
    /// Ground truth: 0 = outlier, 1..=k = motion.
    labels: Vec<usize>,
    hypotheses: Vec<Matrix3<f64>>,
    tau: f64,
}

fn input(n: usize, m: usize, motions: usize, thr_px: f64, seed: u64) -> Input {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = scene::synthetic_scene(&mut rng, n, motions, 0.15, 0.5);
    let hypotheses = scene::hypotheses(&mut rng, &scene, m, 0.8, scene::REFINED);
    Input {
        points: scene.points,
        labels: scene.labels,
        hypotheses,
        tau: thr_px * thr_px,
    }
}

/// Step 7 as the pipeline runs it: one hypothesis's N residuals at a time.
fn build(input: &Input, linkage: Linkage) -> Preferences {
    let n = input.points.len();
    let mut builder = PreferenceBuilder::new(linkage, n, input.tau).unwrap();
    let mut residuals = vec![0.0; n];
    for f in &input.hypotheses {
        sampson_distances_squared(f, &input.points, &mut residuals);
        builder.push_residuals(&residuals).unwrap();
    }
    builder.finish()
}

fn continuous(input: &Input) -> PreferenceMatrix {
    match build(input, Linkage::TLinkage) {
        Preferences::Continuous(p) => p,
        Preferences::Binary(_) => unreachable!(),
    }
}

fn binary(input: &Input) -> BinaryPreferenceMatrix {
    match build(input, Linkage::JLinkage) {
        Preferences::Binary(b) => b,
        Preferences::Continuous(_) => unreachable!(),
    }
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Prints the input's shape and what T-Linkage makes of it.
fn describe(name: &str, input: &Input, p: &PreferenceMatrix) {
    let c = t_linkage(p, 8);
    let motions = input.labels.iter().max().copied().unwrap_or(0);
    let outliers = input.labels.iter().filter(|&&l| l == 0).count();
    eprintln!(
        "{name}: N = {}, M = {}, {motions} motions, {outliers} outliers, density {:.3}; \
         {} merges, {} clusters, {} with >= 8 points",
        p.n_points(),
        p.n_hypotheses(),
        p.density(),
        c.merges.len(),
        c.clusters_before_filter,
        c.clusters_after_filter
    );
}

fn realistic<M: Measurement>(c: &mut Criterion<M>, name: &str, input: &Input, with_jlinkage: bool) {
    let one = pool(1);
    let p = continuous(input);
    describe(name, input, &p);
    let mut group = c.benchmark_group(name);
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    group.bench_function("build+cluster", |b| {
        b.iter(|| one.install(|| t_linkage(&continuous(black_box(input)), 8)))
    });
    group.bench_function("build", |b| {
        b.iter(|| one.install(|| continuous(black_box(input))))
    });
    group.bench_function("cluster", |b| {
        b.iter(|| one.install(|| t_linkage(black_box(&p), 8)))
    });
    if with_jlinkage {
        let two = pool(2);
        group.bench_function("build+cluster/2 threads", |b| {
            b.iter(|| two.install(|| t_linkage(&continuous(black_box(input)), 8)))
        });
        let bits = binary(input);
        group.bench_function("jlinkage cluster", |b| {
            b.iter(|| one.install(|| j_linkage(black_box(&bits), 8)))
        });
    }
    group.sample_size(10).warm_up_time(Duration::from_millis(1));
    group.bench_function("reference cluster", |b| {
        b.iter(|| reference::t_linkage(black_box(&p), 8))
    });
    group.finish();
}

/// The name of a measurement, as a group name prefix.
trait Prefix {
    const PREFIX: &'static str;
}

impl Prefix for WallTime {
    const PREFIX: &'static str = "wall";
}

impl Prefix for ProcessCpuTime {
    const PREFIX: &'static str = "cpu";
}

fn adelaide<M: Measurement + Prefix>(c: &mut Criterion<M>) {
    let name = format!("{}_adelaide_n300_m5000", M::PREFIX);
    realistic(c, &name, &input(300, 5000, 3, 4.5, 1), false);
}

fn hopef<M: Measurement + Prefix>(c: &mut Criterion<M>) {
    let name = format!("{}_hopef_n1000_m3000", M::PREFIX);
    realistic(c, &name, &input(1000, 3000, 4, 2.5, 2), true);
}

fn scaling(c: &mut Criterion<ProcessCpuTime>) {
    let one = pool(1);
    let mut group = c.benchmark_group("cpu_scaling_n");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    for n in [250, 500, 1000, 2000] {
        let input = input(n, 3000, 3, 2.5, 3);
        let p = continuous(&input);
        describe(&format!("scaling_n/{n}"), &input, &p);
        group.bench_with_input(BenchmarkId::new("cluster", n), &p, |b, p| {
            b.iter(|| one.install(|| t_linkage(p, 8)))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("cpu_scaling_m");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    for m in [500, 1000, 2000, 3000, 5000] {
        let input = input(500, m, 3, 2.5, 4);
        let p = continuous(&input);
        describe(&format!("scaling_m/{m}"), &input, &p);
        group.bench_with_input(BenchmarkId::new("cluster", m), &p, |b, p| {
            b.iter(|| one.install(|| t_linkage(p, 8)))
        });
    }
    group.finish();
}

criterion_group!(wall, adelaide::<WallTime>, hopef::<WallTime>);
criterion_group! {
    name = cpu;
    config = Criterion::default().with_measurement(ProcessCpuTime);
    targets = adelaide::<ProcessCpuTime>, hopef::<ProcessCpuTime>, scaling
}
criterion_main!(wall, cpu);
