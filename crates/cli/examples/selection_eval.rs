//! Model selection after the clustering, measured post hoc on synthetic
//! validation scenes: the raw T-Linkage clusters (`final_assignment =
//! "none"`) of a profile, then each [`segmentation::Strategy`], against the
//! profile itself (its size filter and merge). Scenes and sampling seeds
//! are those of `sctl run` on the same preset and indices. Per method: ME
//! (thesis protocol) and ME over all points, the share of scene runs with
//! the true number of motions, the mean number found and true, and the
//! seconds per scene run (the segmentation plus the selection; run with
//! `RAYON_NUM_THREADS=1` for one-thread figures).
//!
//! ```text
//! cargo run --release -p sctl --example selection_eval -- \
//!     [--preset hopef] [--from 800] [--to 809] [--profile default] \
//!     [--seeds 12345,23456,34567] [--out FILE.csv]
//! ```
//!
//! `--out` writes one row per method, scene and seed, and refuses to
//! overwrite a file.

use datasets::synthetic::Preset;
use datasets::Scene;
use metrics::{misclassification_error, misclassification_error_all};
use sctl::pipeline::{matches, scene_seed};
use segmentation::{centred_points, segment, select, FinalAssignment, Params, Profile, Strategy};
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

struct Options {
    preset: Preset,
    from: u32,
    to: u32,
    params: Params,
    seeds: Vec<u64>,
    out: Option<std::path::PathBuf>,
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Options, String> {
    let mut o = Options {
        preset: Preset::Hopef,
        from: 800,
        to: 809,
        params: Params::default(),
        seeds: vec![12345, 23456, 34567],
        out: None,
    };
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        let number = |v: &str| v.parse::<u64>().map_err(|e| format!("{flag} {v}: {e}"));
        match flag.as_str() {
            "--preset" => {
                o.preset = Preset::from_name(&value).ok_or(format!("unknown preset {value}"))?
            }
            "--from" => o.from = number(&value)? as u32,
            "--to" => o.to = number(&value)? as u32,
            "--profile" => {
                o.params = Profile::from_name(&value)
                    .ok_or(format!("unknown profile {value}"))?
                    .params()
            }
            "--seeds" => o.seeds = value.split(',').map(number).collect::<Result<_, _>>()?,
            "--out" => o.out = Some(value.into()),
            other => return Err(format!("unknown option {other}")),
        }
    }
    if !(800..=899).contains(&o.from) || !(800..=899).contains(&o.to) {
        return Err(format!(
            "--from {} --to {}: only the validation indices 800-899",
            o.from, o.to
        ));
    }
    Ok(o)
}

/// One method's result on one scene run.
struct Row {
    method: String,
    scene: String,
    seed: u64,
    me: f64,
    me_all: f64,
    found: usize,
    truth: usize,
    seconds: f64,
}

/// The rows of one scene and seed: the profile, the raw clusters and every
/// strategy on them.
fn run_scene(scene: &Scene, params: &Params, seed: u64) -> Result<Vec<Row>, String> {
    let scene_seed = scene_seed(seed, &scene.name);
    let p = params.clone().with(|q| q.sampling.seed = scene_seed);
    let raw_params = p
        .clone()
        .with(|q| q.selection.final_assignment = FinalAssignment::None);
    let m = matches(scene);
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", scene.name);
    let truth = scene
        .labels
        .clone()
        .ok_or(format!("{}: no labels", scene.name))?;
    let row = |method: &str, labels: &[i32], seconds: f64| -> Result<Row, String> {
        Ok(Row {
            method: method.to_string(),
            scene: scene.name.clone(),
            seed,
            me: misclassification_error(labels, &truth).map_err(|e| err(&e))?,
            me_all: misclassification_error_all(labels, &truth).map_err(|e| err(&e))?,
            found: labels.iter().map(|&l| l + 1).max().unwrap_or(0) as usize,
            truth: scene.num_motions(),
            seconds,
        })
    };
    let t = Instant::now();
    let profile = segment(&m, &p).map_err(|e| err(&e))?;
    let mut rows = vec![row("profile", &profile.labels, t.elapsed().as_secs_f64())?];
    let t = Instant::now();
    let raw = segment(&m, &raw_params).map_err(|e| err(&e))?;
    let raw_seconds = t.elapsed().as_secs_f64();
    rows.push(row("raw", &raw.labels, raw_seconds)?);
    let points = centred_points(&m, &raw_params).map_err(|e| err(&e))?;
    for strategy in Strategy::ALL {
        let t = Instant::now();
        let sel = select(
            &points,
            &raw.labels,
            scene.image_size,
            p.refinement.thr_px,
            strategy,
        )
        .map_err(|e| err(&e))?;
        let seconds = raw_seconds + t.elapsed().as_secs_f64();
        rows.push(row(strategy.name(), &sel.labels, seconds)?);
    }
    Ok(rows)
}

fn summary(rows: &[Row]) {
    println!("| method | ME % | ME all % | exact count | found / true | s/scene |");
    println!("|---|---|---|---|---|---|");
    let mut methods: Vec<&str> = Vec::new();
    for r in rows {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    for method in methods {
        let of: Vec<&Row> = rows.iter().filter(|r| r.method == method).collect();
        let n = of.len() as f64;
        let mean = |f: &dyn Fn(&Row) -> f64| of.iter().map(|r| f(r)).sum::<f64>() / n;
        println!(
            "| {method} | {:.2} | {:.2} | {:.0} % | {:.2} / {:.2} | {:.3} |",
            100.0 * mean(&|r| r.me),
            100.0 * mean(&|r| r.me_all),
            100.0 * mean(&|r| f64::from(u8::from(r.found == r.truth))),
            mean(&|r| r.found as f64),
            mean(&|r| r.truth as f64),
            mean(&|r| r.seconds),
        );
    }
}

fn write_csv(path: &std::path::Path, rows: &[Row]) -> Result<(), String> {
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
        .map_err(|e| {
            format!(
                "{}: {e} (existing results are not overwritten)",
                path.display()
            )
        })?;
    let mut text = String::from("method,scene,seed,me,me_all,found,true,seconds\n");
    for r in rows {
        text += &format!(
            "{},{},{},{},{},{},{},{}\n",
            r.method, r.scene, r.seed, r.me, r.me_all, r.found, r.truth, r.seconds
        );
    }
    file.write_all(text.as_bytes())
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn main() -> ExitCode {
    let o = match parse(std::env::args().skip(1)) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("selection_eval: {e}");
            return ExitCode::FAILURE;
        }
    };
    let scenes = match sctl::dataset::preset_scenes(o.preset, o.from, o.to) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("selection_eval: {e:#}");
            return ExitCode::FAILURE;
        }
    };
    let mut rows = Vec::new();
    for scene in &scenes {
        for &seed in &o.seeds {
            match run_scene(scene, &o.params, seed) {
                Ok(r) => rows.extend(r),
                Err(e) => {
                    eprintln!("selection_eval: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        eprintln!("selection_eval: {} done", scene.name);
    }
    summary(&rows);
    if let Some(path) = &o.out {
        if let Err(e) = write_csv(path, &rows) {
            eprintln!("selection_eval: {e}");
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}
