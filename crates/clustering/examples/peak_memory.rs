//! Peak memory of the clustering phase at a given size: builds the
//! preferences of a realistic synthetic scene (several moving objects, 15 %
//! outliers, hypotheses drawn around the motions, as in the benchmarks) one
//! point at a time, exactly as the pipeline does, and clusters them on the
//! matrix it hands over (`try_cluster_owned`).
//!
//! ```text
//! cargo build --release -p clustering --example peak_memory
//! /usr/bin/time -v target/release/examples/peak_memory 5000 3000
//! ```
//! and read "Maximum resident set size". Arguments: N (default 5000),
//! M (default 3000), seed (default 1). Prints the density of the matrix,
//! the clusters found and
//! the times.

#[path = "../benches/support/scene.rs"]
#[allow(dead_code)]
mod scene;

use clustering::{ClusteringParams, Preferences};
use geometry::SampsonModels;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The system allocator, counting the bytes allocated now and at most.
struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded to `System` unchanged; only counters are added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = CURRENT.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(now, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let now = CURRENT.fetch_add(new_size, Ordering::Relaxed) + new_size;
        PEAK.fetch_max(now, Ordering::Relaxed);
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The peak of the bytes allocated so far, in MB.
fn peak_heap_mb() -> usize {
    PEAK.load(Ordering::Relaxed) / 1_000_000
}

fn arg(position: usize, default: u64) -> u64 {
    std::env::args()
        .nth(position)
        .map_or(default, |a| a.parse().expect("arguments: N M seed"))
}

fn main() {
    let (n, m, seed) = (arg(1, 5000) as usize, arg(2, 3000) as usize, arg(3, 1));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = scene::synthetic_scene(&mut rng, n, 4, 0.15, 0.5);
    let hypotheses = scene::hypotheses(&mut rng, &scene, m, 0.8, scene::REFINED);
    let tau = 2.0f64 * 2.0;
    let params = ClusteringParams::default();

    let t = Instant::now();
    let models = SampsonModels::new(&hypotheses);
    let points = &scene.points;
    let preferences = Preferences::from_residual_rows(params.linkage, n, m, tau, |i, out| {
        models.distances_squared(points.point1(i), points.point2(i), out)
    })
    .expect("valid residuals");
    let built = t.elapsed().as_secs_f64();
    let density = preferences.density();
    let after_build = (peak_rss_mb(), peak_heap_mb());

    let t = Instant::now();
    let clustering = params
        .try_cluster_owned(preferences)
        .expect("no memory bound");
    eprintln!(
        "N = {n}, M = {m}, density {density:.3}; {} clusters, {} kept; \
         preferences {built:.2} s, linkage {:.2} s; \
         peak RSS {} MB (heap {} MB) after the preferences, {} MB (heap {} MB) in all",
        clustering.clusters_before_filter,
        clustering.clusters_after_filter,
        t.elapsed().as_secs_f64(),
        after_build.0,
        after_build.1,
        peak_rss_mb(),
        peak_heap_mb()
    );
}

/// The peak resident set size so far (`VmHWM` of /proc/self/status), in MB;
/// 0 where it cannot be read.
fn peak_rss_mb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
            line.split_whitespace().nth(1)?.parse::<u64>().ok()
        })
        .map_or(0, |kb| kb / 1000)
}
