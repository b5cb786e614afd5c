//! Shared set-up of the segmentation crate's integration tests.

use datasets::synthetic::Preset;
use datasets::Scene;
use segmentation::Matches;

/// Scene `<category>/<index>` of the `quick` synthetic preset (seed 1).
pub fn quick_scene(category: u32, index: u32) -> Scene {
    Preset::Quick
        .params()
        .generate_scene(1, category, index)
        .unwrap()
        .scene
}

/// The scene's matches with its principal point.
pub fn matches(scene: &Scene) -> Matches<'_> {
    Matches::new(&scene.points1, &scene.points2, scene.image_size)
        .with_principal_point(scene.principal_point)
}

/// Runs `f` in a rayon pool of `threads` threads.
pub fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}
