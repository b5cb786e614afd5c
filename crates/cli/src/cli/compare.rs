//! `sctl compare RESULTS_A RESULTS_B`: paired comparison of two runs on
//! their common scenes.

use crate::compare::{compare, load_side, parse_filter, render, Filter};
use anyhow::Result;
use std::path::PathBuf;

/// Options of `sctl compare`.
#[derive(clap::Args)]
pub struct Args {
    /// Run A: a run directory or its per_scene.csv.
    pub a: PathBuf,
    /// Run B: a run directory or its per_scene.csv.
    pub b: PathBuf,
    /// Metric: me, acc, fnr, pur, ari, nmi or frob.
    #[arg(long, default_value = "me")]
    pub metric: String,
    /// Select A's combination by a parameter value (repeatable), e.g. --a method=semical.
    #[arg(long = "a", value_name = "KEY=VALUE", value_parser = parse_filter)]
    pub select_a: Vec<Filter>,
    /// Select B's combination by a parameter value (repeatable), e.g. --b method=baseline.
    #[arg(long = "b", value_name = "KEY=VALUE", value_parser = parse_filter)]
    pub select_b: Vec<Filter>,
}

/// Prints the comparison.
pub fn run(args: Args) -> Result<()> {
    let a = load_side(&args.a, &args.metric, &args.select_a)?;
    let b = load_side(&args.b, &args.metric, &args.select_b)?;
    let comparison = compare(&a, &b, &args.metric)?;
    super::print_out(&render(&a, &b, &comparison))
}
