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

use datasets::Scene;
use sctl::config::ExperimentConfig;
use sctl::dataset::load_scenes;
use sctl::pipeline::{matches, scene_seed};
use segmentation::{segment, Params};
use std::path::PathBuf;
use std::process::ExitCode;

struct Options {
    config: PathBuf,
    scales: Vec<f64>,
    seeds: Vec<u64>,
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Options, String> {
    let config = args
        .next()
        .ok_or("usage: focal_prior CONFIG.toml [--scales S,..] [--seeds S,..]")?;
    let mut o = Options {
        config: PathBuf::from(config),
        scales: vec![0.25, 0.5, 1.0, 2.0, 4.0],
        seeds: vec![12345, 23456, 34567],
    };
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--scales" => {
                o.scales = value
                    .split(',')
                    .map(|v| v.parse::<f64>().map_err(|e| format!("--scales {v}: {e}")))
                    .collect::<Result<_, _>>()?
            }
            "--seeds" => {
                o.seeds = value
                    .split(',')
                    .map(|v| v.parse::<u64>().map_err(|e| format!("--seeds {v}: {e}")))
                    .collect::<Result<_, _>>()?
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    if o.scales.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(format!(
            "--scales must be finite and > 0, got {:?}",
            o.scales
        ));
    }
    Ok(o)
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
    match parse(std::env::args().skip(1)).and_then(|o| run(&o)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("focal_prior: {e}");
            ExitCode::FAILURE
        }
    }
}
