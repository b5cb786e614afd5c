//! Loader and generator timings: one AdelaideRMF scene (with and without
//! decoding its images), one HOPE-F features archive, one synthetic scene,
//! and writing the `quick` preset in the HOPE-F layout.

use criterion::{criterion_group, criterion_main, Criterion};
use datasets::adelaidermf::{load_scene_with, LoadOptions};
use datasets::hopef::{parse_features, FEATURES_FILE};
use datasets::synthetic::{generate_scene, write_hopef_layout, Preset, SyntheticParams};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

fn shared() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared")
}

fn loaders(c: &mut Criterion) {
    let mat = shared().join("datasets/adelaidermf/F/biscuit.mat");
    assert!(
        mat.is_file(),
        "{} missing: {}",
        mat.display(),
        datasets::DATASET_HINT
    );
    c.bench_function("adelaidermf/load biscuit with images", |b| {
        b.iter(|| load_scene_with(black_box(&mat), LoadOptions { images: true }).unwrap())
    });
    c.bench_function("adelaidermf/load biscuit without images", |b| {
        b.iter(|| load_scene_with(black_box(&mat), LoadOptions { images: false }).unwrap())
    });
    let npz_path = shared()
        .join("fixtures/hopef-layout/good/4/0001")
        .join(FEATURES_FILE);
    let npz = std::fs::read(&npz_path).expect("HOPE-F layout fixture");
    c.bench_function("hopef/parse features (379 points)", |b| {
        b.iter(|| parse_features(black_box(&npz), &npz_path).unwrap())
    });
}

fn synthetic(c: &mut Criterion) {
    let params = SyntheticParams::default();
    c.bench_function("synthetic/generate 4 objects", |b| {
        b.iter(|| generate_scene(&params, black_box(7), 4, "bench").unwrap())
    });
    let scenes = Preset::Quick.generate(1).unwrap();
    let dir = tempfile::tempdir().unwrap();
    c.bench_function("synthetic/write quick preset (4 scenes)", |b| {
        b.iter(|| write_hopef_layout(dir.path(), black_box(&scenes)).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1));
    targets = loaders, synthetic
}
criterion_main!(benches);
