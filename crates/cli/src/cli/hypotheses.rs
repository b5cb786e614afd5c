//! `sctl hypotheses CONFIG.toml --out FILE`: the refined hypotheses (steps
//! 1–3) of every scene of a config's dataset with its `[pipeline]`
//! parameters, as a CSV of `scene,hypothesis,f_prior,F00,...,F22` (F scaled
//! to unit norm, principal points at the origin) — the input of an external
//! focal solver whose answers `focal_solver = "external"` reads back
//! (`scripts/poselib_focals.py` runs PoseLib on it).

use super::LoadedConfig;
use crate::focal_file::{focal_file_path, F_COLUMNS};
use crate::pipeline::generate_hypotheses;
use anyhow::{Context, Result};
use std::io::Write;

/// Options of `sctl hypotheses`.
#[derive(clap::Args)]
pub struct Args {
    /// The config and its scenes.
    #[command(flatten)]
    pub input: super::ConfigScenes,
    /// Output CSV; `{seed}` in it is replaced by the seed.
    #[arg(long, value_name = "FILE")]
    pub out: String,
    /// Sampling seed [default: the config's `seed`].
    #[arg(long)]
    pub seed: Option<u64>,
}

/// Writes every refined hypothesis of every scene.
pub fn run(args: Args) -> Result<()> {
    let LoadedConfig { mut config, scenes } = args.input.load()?;
    if let Some(seed) = args.seed {
        config.pipeline.params.sampling.seed = seed;
    }
    let pipeline = &config.pipeline;
    let path = focal_file_path(&args.out, pipeline.params.sampling.seed);
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("{}", dir.display()))?;
    }
    let file = std::fs::File::create(&path).with_context(|| format!("{}", path.display()))?;
    let mut out = std::io::BufWriter::new(file);
    writeln!(out, "scene,hypothesis,f_prior,{}", F_COLUMNS.join(","))?;
    for scene in &scenes {
        let generated = generate_hypotheses(scene, pipeline)?;
        let f_prior = scene.focal_prior();
        for (j, model) in generated.models.iter().enumerate() {
            let Some(f) = model else { continue };
            let f = f / f.norm();
            let entries: Vec<String> = (0..9).map(|k| format!("{:e}", f[(k / 3, k % 3)])).collect();
            writeln!(out, "{},{j},{f_prior},{}", scene.name, entries.join(","))?;
        }
    }
    out.flush()?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
