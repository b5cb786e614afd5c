//! Why the default misses true motions on synthetic scenes: for each true
//! motion, whether it is significant alone (the selection given its true
//! group only) and whether a motion found holds it (more than half of its
//! matches, in a motion whose majority it is); each significant motion
//! missed is put in one class by what the clustering (the default without
//! its selection, `final_assignment = "none"`) did with it:
//!
//! - own cluster: a cluster whose majority it is holds more than half of
//!   it, and the selection did not keep it;
//! - merged: the cluster holding most of it is another motion's; counted
//!   apart when more than half of its matches lie within `thr_px` of that
//!   motion's F (the normalised 8-point of its true matches), where no
//!   labelling by that F can tell the two apart;
//! - no cluster: more than half of its matches are in no cluster;
//! - other: the rest (split over clusters, or in a cluster of outliers).
//!
//! Scenes and sampling seeds are those of `sctl run` on the same preset
//! and indices.
//!
//! ```text
//! cargo run --release -p sctl --example missed_motions -- \
//!     [--preset hopef] [--from 800] [--to 899] [--seeds 12345]
//! ```

use clap::Parser;
use datasets::synthetic::Preset;
use datasets::Scene;
use geometry::{eight_point_normalized, sampson_distance, Correspondences};
use sctl::pipeline::{matches, scene_seed};
use segmentation::selection::{select_groups, Camera, GroupOrigin, ImageRect};
use segmentation::{centred_points, segment, FinalAssignment, Params};
use std::collections::HashMap;
use std::process::ExitCode;

/// Why the default misses true motions on synthetic scenes.
#[derive(Parser)]
struct Options {
    /// The synthetic preset (`sctl synth --help` lists them).
    #[arg(long, default_value = "hopef", value_parser = preset)]
    preset: Preset,
    /// The first scene index.
    #[arg(long, default_value_t = 800)]
    from: u32,
    /// The last scene index.
    #[arg(long, default_value_t = 899)]
    to: u32,
    /// The run seeds, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = [12345])]
    seeds: Vec<u64>,
}

fn preset(name: &str) -> Result<Preset, String> {
    Preset::from_name(name).ok_or(format!("unknown preset {name}"))
}

/// Counts over every scene run.
#[derive(Default)]
struct Counts {
    motions: usize,
    significant: usize,
    found: usize,
    own_cluster: usize,
    merged: usize,
    merged_within: usize,
    no_cluster: usize,
    other: usize,
}

/// The label (≥ 0) holding the most of `idx` under `labels`, with how many
/// it holds; None when every one is −1.
fn holder(labels: &[i32], idx: &[usize]) -> Option<(i32, usize)> {
    let mut count: HashMap<i32, usize> = HashMap::new();
    for &i in idx.iter().filter(|&&i| labels[i] >= 0) {
        *count.entry(labels[i]).or_default() += 1;
    }
    count
        .into_iter()
        .max_by_key(|&(l, n)| (n, std::cmp::Reverse(l)))
}

/// One scene run: which true motions are significant alone, the
/// default's labels and its clustering's.
struct Run<'a> {
    significant: &'a [bool],
    found: &'a [i32],
    clustered: &'a [i32],
}

/// How many of the matches `idx` of `scene` lie within `thr_px` (Sampson,
/// pixels) of the normalised 8-point F of true motion `other`'s matches.
fn within_other_f(scene: &Scene, idx: &[usize], other: i32, thr_px: f64) -> usize {
    let truth = scene.labels.as_deref().unwrap_or_default();
    let of: Vec<usize> = (0..truth.len()).filter(|&i| truth[i] == other).collect();
    let pick = |p: &[[f64; 2]], at: &[usize]| at.iter().map(|&i| p[i]).collect::<Vec<_>>();
    let fitted = Correspondences::new(&pick(&scene.points1, &of), &pick(&scene.points2, &of))
        .and_then(|c| eight_point_normalized(&c));
    let Ok(f) = fitted else {
        return 0;
    };
    idx.iter()
        .filter(|&&i| sampson_distance(&f, scene.points1[i], scene.points2[i]) <= thr_px)
        .count()
}

/// The majority true label of the matches labelled `label`.
fn majority(labels: &[i32], truth: &[i32], label: i32) -> i32 {
    let mut count: HashMap<i32, usize> = HashMap::new();
    for (_, &t) in labels.iter().zip(truth).filter(|(&l, _)| l == label) {
        *count.entry(t).or_default() += 1;
    }
    count
        .into_iter()
        .max_by_key(|&(t, n)| (n, std::cmp::Reverse(t)))
        .map_or(0, |(t, _)| t)
}

impl Counts {
    /// One scene run: the default's labels and its clustering's.
    fn add(&mut self, scene: &Scene, runs: &Run, thr_px: f64) {
        let Run {
            significant,
            found,
            clustered,
        } = *runs;
        let truth = scene.labels.as_deref().unwrap_or_default();
        for (t, &sig) in (1..).zip(significant) {
            let idx: Vec<usize> = (0..truth.len()).filter(|&i| truth[i] == t).collect();
            self.motions += 1;
            self.significant += usize::from(sig);
            let held = |labels: &[i32]| {
                holder(labels, &idx)
                    .filter(|&(l, n)| 2 * n > idx.len() && majority(labels, truth, l) == t)
            };
            if held(found).is_some() {
                self.found += 1;
                continue;
            }
            if !sig {
                continue;
            }
            let unclustered = idx.iter().filter(|&&i| clustered[i] < 0).count();
            // The true motion most of the cluster holding most of it is.
            let holder_truth = holder(clustered, &idx).map(|(l, _)| majority(clustered, truth, l));
            match holder_truth {
                _ if held(clustered).is_some() => self.own_cluster += 1,
                Some(other) if ![0, t].contains(&other) => {
                    self.merged += 1;
                    if 2 * within_other_f(scene, &idx, other, thr_px) > idx.len() {
                        self.merged_within += 1;
                    }
                }
                _ if 2 * unclustered > idx.len() => self.no_cluster += 1,
                _ => self.other += 1,
            }
        }
    }

    fn print(&self) {
        println!(
            "true motions {}: significant alone {}, found {}",
            self.motions, self.significant, self.found
        );
        println!(
            "significant and missed {}: own cluster not kept {}, merged into another motion's cluster {} ({} with more than half of its matches within thr_px of that motion's F), in no cluster {}, other {}",
            self.own_cluster + self.merged + self.no_cluster + self.other,
            self.own_cluster,
            self.merged,
            self.merged_within,
            self.no_cluster,
            self.other
        );
    }
}

/// Per true motion of `scene`: whether the selection given its true group
/// alone detects it.
fn significant_alone(scene: &Scene, params: &Params) -> Result<Vec<bool>, String> {
    let m = matches(scene);
    let points = centred_points(&m, params).map_err(|e| e.to_string())?;
    let camera = Camera {
        image: ImageRect::new(m.image_size, m.principal_point),
        focal_px: m.focal_prior,
    };
    let truth = scene.labels.as_deref().unwrap_or_default();
    (1..=scene.num_motions() as i32)
        .map(|t| {
            let group: Vec<usize> = (0..truth.len()).filter(|&i| truth[i] == t).collect();
            let thr = params.refinement.thr_px;
            select_groups(&points, &[group], GroupOrigin::Clustered, camera, thr)
                .map(|s| s.motions == 1)
                .map_err(|e| format!("{}: {e}", scene.name))
        })
        .collect()
}

fn run(o: &Options) -> Result<Counts, String> {
    let scenes = sctl::dataset::preset_scenes(o.preset, o.from, o.to).map_err(|e| e.to_string())?;
    let mut counts = Counts::default();
    for scene in &scenes {
        let significant = significant_alone(scene, &Params::default())?;
        for &seed in &o.seeds {
            let p = Params::default().with(|q| q.sampling.seed = scene_seed(seed, &scene.name));
            let clustering = p
                .clone()
                .with(|q| q.selection.final_assignment = FinalAssignment::None);
            let m = matches(scene);
            let label = |p: &Params| {
                segment(&m, p)
                    .map(|s| s.labels)
                    .map_err(|e| format!("{}: {e}", scene.name))
            };
            let run = Run {
                significant: &significant,
                found: &label(&p)?,
                clustered: &label(&clustering)?,
            };
            counts.add(scene, &run, p.refinement.thr_px);
        }
    }
    Ok(counts)
}

fn main() -> ExitCode {
    match run(&Options::parse()) {
        Ok(counts) => {
            counts.print();
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("missed_motions: {e}");
            ExitCode::FAILURE
        }
    }
}
