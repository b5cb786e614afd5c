//! Algorithm 1 on one synthetic scene (3 moving objects, about 300 matches
//! with 20 % gross outliers): the baseline at the reference's AdelaideRMF M
//! and the semi-calibrated pipeline (whose focal stage dominates) at a
//! smaller M. Per-stage times of real runs are in each run's timings.csv.

use criterion::{criterion_group, criterion_main, Criterion};
use datasets::synthetic::{generate_scene, SyntheticParams};
use sctl::config::{Method, PipelineConfig};
use sctl::pipeline::segment;

fn pipeline(c: &mut Criterion) {
    let scene = generate_scene(&SyntheticParams::default(), 11, 3, "bench").expect("scene");
    let mut group = c.benchmark_group(format!("segment_n{}", scene.len()));
    group.sample_size(10);
    for (method, m) in [(Method::Baseline, 5000), (Method::Semical, 1000)] {
        let config = PipelineConfig::from_params(segmentation::Params {
            method,
            num_samples: m,
            thr_px: 4.5,
            tau_diff: 0.15,
            tau_range: 0.25,
            ..Default::default()
        });
        group.bench_function(format!("{method:?}_m{m}").to_lowercase(), |b| {
            b.iter(|| segment(&scene, &config).expect("segmentation"))
        });
    }
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
