//! `sctl synth`: writes a synthetic HOPE-F-like dataset (a named preset,
//! optionally with parameters overridden from a TOML file) in the HOPE-F
//! on-disk layout, plus `synthetic.toml` recording how it was made.

use anyhow::{bail, Context};
use datasets::synthetic::{write_hopef_layout_with, Preset, PresetParams};
use std::path::{Path, PathBuf};

/// Name of the file, at the top of the output directory, that records the
/// preset, seed and generator parameters.
pub const METADATA_FILE: &str = "synthetic.toml";

/// Options of `sctl synth`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Preset: hopef-like (4 x 100 scenes), quick (4 small scenes),
    /// kitti-like (background + movers, 20 scenes), hopef (HOPE-F's own
    /// process, 4 x 1000 scenes with train/val/test folders), kitti-real
    /// (1242 x 375 driving scenes of 1000-5000 matches, 2 x 1000 scenes with
    /// train/val/test folders), adelaide-like (HOPE-F's process at
    /// AdelaideRMF's image size, outlier shares and inliers per motion,
    /// 4 x 1000 scenes with train/val/test folders), driving-random
    /// (kitti-real's scenes with N 200-20 000, 0-3 movers 0.5-20 px from the
    /// background's epipolar geometry, drawn per scene; 1000 scenes with
    /// train/val/test folders) or objects-3d (1-5 general 3-D objects
    /// turning about any axis, N 100-3000; 1000 scenes with train/val/test
    /// folders).
    #[arg(long, default_value = "hopef-like")]
    pub preset: String,
    /// Output directory (created; must be empty unless --force).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Seed of the generator; scene (k, NNNN) uses a seed mixed from it.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// TOML file of generator parameters overriding the preset's (any subset
    /// of the fields of `SyntheticParams`, or of `HopefParams` for hopef).
    #[arg(long, value_name = "FILE")]
    pub params: Option<PathBuf>,
    /// Write into a non-empty directory, replacing files of the same names.
    #[arg(long)]
    pub force: bool,
}

/// Overlays the tables of `overrides` on `base`, recursively.
fn merge(base: &mut toml::Value, overrides: toml::Value) {
    match (base, overrides) {
        (toml::Value::Table(base), toml::Value::Table(overrides)) => {
            for (key, value) in overrides {
                match base.get_mut(&key) {
                    Some(slot) => merge(slot, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

/// The preset's parameters with the fields of the TOML file `path` replaced.
pub fn params_with_overrides(preset: Preset, path: Option<&Path>) -> anyhow::Result<PresetParams> {
    let base = preset.params();
    let Some(path) = path else { return Ok(base) };
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    let overrides: toml::Value =
        toml::from_str(&text).with_context(|| format!("{}: not valid TOML", path.display()))?;
    let mut merged = toml::Value::try_from(&base).context("encoding preset parameters")?;
    merge(&mut merged, overrides);
    let params = preset
        .params_from_toml(merged)
        .with_context(|| format!("{}: not valid generator parameters", path.display()))?;
    params
        .validate()
        .with_context(|| format!("{}", path.display()))?;
    Ok(params)
}

fn is_empty_dir(dir: &Path) -> anyhow::Result<bool> {
    Ok(std::fs::read_dir(dir)
        .with_context(|| format!("{}: cannot list", dir.display()))?
        .next()
        .is_none())
}

/// Runs `sctl synth`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let preset = Preset::from_name(&args.preset).with_context(|| {
        let names: Vec<&str> = Preset::ALL.iter().map(|p| p.name()).collect();
        format!(
            "unknown preset `{}` (available: {})",
            args.preset,
            names.join(", ")
        )
    })?;
    let params = params_with_overrides(preset, args.params.as_deref())?;
    let out = &args.out;
    if out.exists() {
        if !out.is_dir() {
            bail!("{} exists and is not a directory", out.display());
        }
        if !args.force && !is_empty_dir(out)? {
            bail!(
                "{} is not empty (use --force to write into it)",
                out.display()
            );
        }
    }
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create", out.display()))?;

    let total = preset.len();
    eprintln!(
        "synth: generating {total} scenes (preset {}, seed {}) into {}",
        preset.name(),
        args.seed,
        out.display()
    );
    let scenes = preset.generate_with(&params, args.seed, |_, _| {})?;
    let step = (total / 10).max(1);
    write_hopef_layout_with(out, &scenes, |done, total| {
        if done % step == 0 || done == total {
            eprintln!("synth: {done}/{total} scenes written");
        }
    })?;

    // TOML integers are i64: a larger seed is recorded as a string.
    let seed = i64::try_from(args.seed).map_or_else(
        |_| toml::Value::String(args.seed.to_string()),
        toml::Value::Integer,
    );
    let metadata = toml::Value::Table(toml::map::Map::from_iter([
        (
            "preset".to_string(),
            toml::Value::String(preset.name().to_string()),
        ),
        ("seed".to_string(), seed),
        (
            "params".to_string(),
            toml::Value::try_from(&params).context("encoding parameters")?,
        ),
    ]));
    let path = out.join(METADATA_FILE);
    std::fs::write(
        &path,
        toml::to_string_pretty(&metadata).context("encoding metadata")?,
    )
    .with_context(|| format!("{}: cannot write", path.display()))?;
    eprintln!(
        "synth: done; read it with `sctl inspect --dataset hopef --dir {}`",
        out.display()
    );
    Ok(())
}
