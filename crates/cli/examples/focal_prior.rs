//! How much the focal prior matters: the ME of a configuration when the
//! focal prior (the focal the five-point default solves its essential
//! matrices at, docs/method.md "The default") is a multiple of a reference
//! focal. The reference is the scene's true focal where the data set has
//! one (HOPE-F, the synthetic presets) and `max(W, H)` otherwise
//! (AdelaideRMF). Scenes and sampling seeds are those of `sctl run` on the
//! same config; the config's `[pipeline]` table gives the parameters.
//!
//! ```text
//! cargo run --release -p sctl --example focal_prior -- CONFIG.toml \
//!     [--scales 0.25,0.5,1,2,4] [--seeds 12345,23456,34567]
//! ```
//!
//! Prints one row per scale: the mean ME over scenes and seeds, both ways
//! (the thesis's protocol, GT outliers excluded, and over all points), and
//! the scenes × seeds it averaged.

use clap::Parser;
use datasets::Scene;
use sctl::config::ExperimentConfig;
use sctl::dataset::load_scenes;
use sctl::pipeline::{matches, scene_seed};
use segmentation::{segment, Params};
use std::path::PathBuf;
use std::process::ExitCode;

/// The ME of a config's pipeline at focal priors that are multiples of
/// the reference focal.
#[derive(Parser)]
struct Options {
    /// The experiment config: its data set and its `[pipeline]` table.
    config: PathBuf,
    /// The multiples of the reference focal, comma-separated, each > 0.
    #[arg(long, value_delimiter = ',', value_parser = positive,
          default_values_t = [0.25, 0.5, 1.0, 2.0, 4.0])]
    scales: Vec<f64>,
    /// The run seeds, comma-separated (each scene's seed derives from them
    /// as in `sctl run`).
    #[arg(long, value_delimiter = ',', default_values_t = [12345, 23456, 34567])]
    seeds: Vec<u64>,
}

/// A finite number > 0.
fn positive(v: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(x) => Err(format!("{x} is not a finite number > 0")),
        Err(e) => Err(e.to_string()),
    }
}

/// The focal the prior is a multiple of: the true focal, else `max(W, H)`.
fn reference_focal(scene: &Scene) -> f64 {
    scene.true_focal.unwrap_or_else(|| scene.focal_prior())
}

/// (ME, ME over all points) in % of one scene segmented at `scale` times
/// its reference focal.
fn scene_me(scene: &Scene, params: &Params, scale: f64) -> Result<(f64, f64), String> {
    let input = matches(scene).with_focal_prior(scale * reference_focal(scene));
    let truth = scene
        .labels
        .as_deref()
        .ok_or(format!("{}: no ground-truth labels", scene.name))?;
    let seg = segment(&input, params).map_err(|e| format!("{}: {e}", scene.name))?;
    let me = metrics::misclassification_error(&seg.labels, truth)
        .map_err(|e| format!("{}: {e}", scene.name))?;
    let me_all = metrics::misclassification_error_all(&seg.labels, truth)
        .map_err(|e| format!("{}: {e}", scene.name))?;
    Ok((100.0 * me, 100.0 * me_all))
}

fn run(o: &Options) -> Result<(), String> {
    let config = ExperimentConfig::load(&o.config).map_err(|e| e.to_string())?;
    let scenes = load_scenes(&config.dataset, None, false).map_err(|e| e.to_string())?;
    let base = config.pipeline.params();
    println!("scale,me,me_all,runs");
    for &scale in &o.scales {
        let (mut me, mut me_all, mut runs) = (0.0, 0.0, 0usize);
        for scene in &scenes {
            for &seed in &o.seeds {
                let scene_seed = scene_seed(seed, &scene.name);
                let params = base.clone().with(|q| q.sampling.seed = scene_seed);
                let (a, b) = scene_me(scene, &params, scale)?;
                me += a;
                me_all += b;
                runs += 1;
            }
        }
        let n = runs.max(1) as f64;
        println!("{scale},{:.2},{:.2},{runs}", me / n, me_all / n);
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(&Options::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("focal_prior: {e}");
            ExitCode::FAILURE
        }
    }
}
