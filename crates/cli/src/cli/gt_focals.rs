//! `sctl gt-focals CONFIG.toml`: the focal lengths implied by each
//! ground-truth motion of every scene of a config's dataset, as a CSV on
//! stdout — the check of whether the focal stage can work on the data at
//! all: F is the Hartley-normalised 8-point fit to all of a motion's points
//! (centred coordinates), solved by the config's robust solver (its weight
//! sets and `max_iters`, failures reported) and by Bougnoux's formula.

use super::LoadedConfig;
use crate::evaluate::motion_indices;
use crate::pipeline::fit_cluster;
use anyhow::{Context, Result};
use focal::OnFailure;
use geometry::Correspondences;
use std::io::Write;

/// Options of `sctl gt-focals`.
#[derive(clap::Args)]
pub struct Args {
    /// The config and its scenes.
    #[command(flatten)]
    pub input: super::ConfigScenes,
}

/// The CSV header.
pub const HEADER: &str = "scene,motion,points,f_prior,f_true,kocur_f1,kocur_f2,kocur_iterations,kocur_status,bougnoux_f1,bougnoux_f2";

fn cell(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:.3}"))
}

/// Prints one row per (scene, ground-truth motion).
pub fn run(args: Args) -> Result<()> {
    let LoadedConfig { config, scenes } = args.input.load()?;
    let pipeline = &config.pipeline;
    let weight_sets = pipeline.params.focal.weight_sets.sets();
    let mut out = std::io::stdout().lock();
    writeln!(out, "{HEADER}")?;
    for scene in &scenes {
        let Some(labels) = &scene.labels else {
            continue;
        };
        let points = Correspondences::new(&scene.points1, &scene.points2)
            .with_context(|| format!("scene `{}`", scene.name))?
            .shifted(scene.principal_point, scene.principal_point);
        let motions = motion_indices(labels);
        let f_prior = scene.focal_prior();
        for (motion, idx) in &motions {
            let f = fit_cluster(&points, idx);
            let kocur = f.map(|f| {
                focal::robust_focals_multi_start(
                    &f,
                    f_prior,
                    &weight_sets,
                    pipeline.params.focal.max_iters,
                    OnFailure::Report,
                )
            });
            let (k1, k2, iterations, status) = match &kocur {
                Some(Ok(e)) => (
                    Some(e.f1),
                    Some(e.f2),
                    e.iterations.to_string(),
                    "ok".to_string(),
                ),
                Some(Err(e)) => (None, None, e.iterations().to_string(), "failed".to_string()),
                None => (None, None, String::new(), "no fit".to_string()),
            };
            let bougnoux = f.and_then(|f| focal::bougnoux(&f, [0.0, 0.0], [0.0, 0.0]).ok());
            writeln!(
                out,
                "{},{motion},{},{},{},{},{},{iterations},{status},{},{}",
                scene.name,
                idx.len(),
                cell(Some(f_prior)),
                cell(scene.true_focal),
                cell(k1),
                cell(k2),
                cell(bougnoux.map(|b| b.0)),
                cell(bougnoux.map(|b| b.1)),
            )?;
        }
    }
    Ok(())
}
