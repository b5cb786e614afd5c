//! Prints the distributions of a split of the `hopef` preset (N, outlier
//! share, matches per object, |relative yaw|, displacement, label noise,
//! localisation error) as Markdown tables.
//!
//! ```text
//! cargo run --release -p datasets --example hopef_stats -- [--seed 1] [--split test|val|train] [--preset hopef|adelaide-like] [--params FILE.toml]
//! ```
//!
//! `--seed` is the generator seed (`[dataset] generator_seed`, default 1);
//! `--preset` a preset of the HOPE-F-faithful generator (default `hopef`);
//! `--params` a TOML file of `HopefParams` fields overriding `hopef`'s.

use datasets::hopef::Split;
use datasets::hopef_synth::stats::HopefStats;
use datasets::hopef_synth::{generate_scene, HopefParams};
use datasets::synthetic::{Preset, PresetParams};
use std::process::ExitCode;

struct Options {
    seed: u64,
    split: Split,
    params: HopefParams,
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Options, String> {
    let mut options = Options {
        seed: 1,
        split: Split::Test,
        params: HopefParams::default(),
    };
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--seed" => options.seed = value.parse().map_err(|e| format!("--seed {value}: {e}"))?,
            "--split" => options.split = value.parse()?,
            "--preset" => {
                let preset = Preset::from_name(&value).ok_or(format!("unknown preset {value}"))?;
                let PresetParams::Hopef(params) = preset.params() else {
                    return Err(format!(
                        "{value} does not use the HOPE-F-faithful generator"
                    ));
                };
                options.params = params;
            }
            "--params" => {
                let text = std::fs::read_to_string(&value).map_err(|e| format!("{value}: {e}"))?;
                options.params = toml::from_str(&text).map_err(|e| format!("{value}: {e}"))?;
            }
            other => {
                return Err(format!(
                    "unknown option {other} (--seed, --split, --preset, --params)"
                ))
            }
        }
    }
    Ok(options)
}

fn main() -> ExitCode {
    let options = match parse(std::env::args().skip(1)) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("hopef_stats: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut scenes = Vec::new();
    for category in datasets::hopef::CATEGORIES {
        for index in options.split.indices() {
            match generate_scene(&options.params, options.seed, category, index) {
                Ok(s) => scenes.push(s),
                Err(e) => {
                    eprintln!("hopef_stats: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
    }
    match HopefStats::compute(&scenes) {
        Ok(stats) => {
            println!("{stats}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("hopef_stats: {e}");
            ExitCode::FAILURE
        }
    }
}
