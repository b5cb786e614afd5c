//! What the clusters of a profile are made of on synthetic validation
//! scenes: for each predicted cluster its majority ground-truth label, so
//! that an over-count of the motions splits into fragments of a motion
//! (a second cluster whose majority is a motion another cluster already
//! holds) and clusters of gross outliers, and the thesis-protocol errors
//! (ground-truth inliers mislabelled) into inliers called outliers, inliers
//! in a fragment and inliers in another motion's cluster. Scenes and
//! sampling seeds are those of `sctl run` on the same preset and indices.
//! Per scene, once: the motion count the a-contrario selection finds when
//! given the true groups (the ceiling of any clustering before it), and
//! how many true Fs are not significant even alone.
//! `--config` takes the parameters of a file's `[pipeline]` table (its
//! `profile` and the keys it gives), `--profile` those of a profile.
//!
//! ```text
//! cargo run --release -p sctl --example cluster_anatomy -- \
//!     [--preset adelaide-like] [--from 800] [--to 819] [--profile thesis] \
//!     [--config FILE.toml] [--num-samples M] [--seeds 12345,23456,34567]
//! ```

use clap::Parser;
use datasets::synthetic::Preset;
use datasets::Scene;
use geometry::{sampson_distances_squared, Correspondences};
use nalgebra::Matrix3;
use sctl::config::PipelineConfig;
use sctl::pipeline::{matches, scene_seed};
use segmentation::selection::{nfa, select_groups, Camera, GroupOrigin};
use segmentation::{segment, subset_indices, Params, Profile};
use std::path::PathBuf;
use std::process::ExitCode;

/// What the clusters of a configuration are made of on synthetic scenes.
#[derive(Parser)]
struct Options {
    /// The synthetic preset (`sctl synth --help` lists them).
    #[arg(long, default_value = "adelaide-like", value_parser = preset)]
    preset: Preset,
    /// The first scene index.
    #[arg(long, default_value_t = 800)]
    from: u32,
    /// The last scene index.
    #[arg(long, default_value_t = 819)]
    to: u32,
    /// A profile's parameters (`default`, `thesis`).
    #[arg(long, value_parser = profile, conflicts_with = "config")]
    profile: Option<Profile>,
    /// The parameters of a config file's `[pipeline]` table.
    #[arg(long)]
    config: Option<PathBuf>,
    /// M, the hypotheses per scene, instead of the parameters'.
    #[arg(long)]
    num_samples: Option<usize>,
    /// The run seeds, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = [12345, 23456, 34567])]
    seeds: Vec<u64>,
}

fn preset(name: &str) -> Result<Preset, String> {
    Preset::from_name(name).ok_or(format!("unknown preset {name}"))
}

fn profile(name: &str) -> Result<Profile, String> {
    Profile::from_name(name).ok_or(format!("unknown profile {name}"))
}

impl Options {
    /// The parameters: the config's, else the profile's, else the
    /// default, with `--num-samples`.
    fn params(&self) -> Result<Params, String> {
        let mut params = match (&self.config, self.profile) {
            (Some(path), _) => PipelineConfig::load(path)
                .map_err(|e| e.to_string())?
                .params(),
            (None, Some(profile)) => profile.params(),
            (None, None) => Params::default(),
        };
        if let Some(m) = self.num_samples {
            params.sampling.num_samples = m;
        }
        Ok(params)
    }
}

/// Counts over every scene and seed.
#[derive(Default)]
struct Anatomy {
    runs: usize,
    over: usize,
    under: usize,
    motion_clusters: usize,
    fragments: usize,
    outlier_clusters: usize,
    gt_inliers: usize,
    gt_outliers: usize,
    outliers_in_clusters: usize,
    inliers_as_outliers: usize,
    outside_subset_as_outliers: usize,
    inliers_in_fragments: usize,
    inliers_in_other_motion: usize,
    /// Ground-truth inliers farther than `thr_px` (Sampson) from their
    /// motion's true F: no model can explain them.
    inliers_beyond_thr: usize,
    /// Ground-truth inliers within `thr_px` of another motion's true F.
    inliers_ambiguous: usize,
    /// Ground-truth inliers of the scenes (once per scene, not per seed):
    /// the denominator of the two counts above.
    scene_inliers: usize,
    /// Scenes, and those whose true motion count the selection finds when
    /// given the true groups (each motion's matches) instead of clusters.
    scenes: usize,
    true_groups_exact: usize,
    /// True motions, and those whose true F is not significant (NFA ≥ 1)
    /// alone among the scene's matches: no clustering makes them found.
    true_motions: usize,
    true_f_not_significant: usize,
}

impl Anatomy {
    /// One scene run: its ground truth (0 outlier, 1.. motions), the
    /// predicted labels and which matches the clustering saw
    /// (`cluster_subset`).
    fn add(&mut self, truth: &[i32], labels: &[i32], motions: usize, clustered: &[bool]) {
        let clusters = labels.iter().map(|&l| l + 1).max().unwrap_or(0) as usize;
        // counts[c][t]: matches of cluster c with ground-truth label t.
        let mut counts = vec![vec![0usize; motions + 1]; clusters];
        for (&l, &t) in labels.iter().zip(truth) {
            if l >= 0 {
                counts[l as usize][t as usize] += 1;
            }
        }
        let majority: Vec<usize> = counts
            .iter()
            .map(|c| {
                (0..=motions)
                    .max_by_key(|&t| (c[t], std::cmp::Reverse(t)))
                    .unwrap()
            })
            .collect();
        // The cluster holding most of motion t is its own; others with
        // majority t are fragments.
        let mut owner = vec![None; motions + 1];
        for t in 1..=motions {
            owner[t] = (0..clusters)
                .filter(|&c| majority[c] == t)
                .max_by_key(|&c| (counts[c][t], std::cmp::Reverse(c)));
        }
        for (c, &t) in majority.iter().enumerate() {
            match t {
                0 => self.outlier_clusters += 1,
                t if owner[t] == Some(c) => self.motion_clusters += 1,
                _ => self.fragments += 1,
            }
        }
        self.runs += 1;
        self.over += usize::from(clusters > motions);
        self.under += usize::from(clusters < motions);
        for ((&l, &t), &seen) in labels.iter().zip(truth).zip(clustered) {
            if t == 0 {
                self.gt_outliers += 1;
                self.outliers_in_clusters += usize::from(l >= 0);
                continue;
            }
            self.gt_inliers += 1;
            let t = t as usize;
            match usize::try_from(l) {
                Err(_) => {
                    self.inliers_as_outliers += 1;
                    self.outside_subset_as_outliers += usize::from(!seen);
                }
                Ok(c) if majority[c] == t && owner[t] != Some(c) => self.inliers_in_fragments += 1,
                Ok(c) if majority[c] != t => self.inliers_in_other_motion += 1,
                Ok(_) => {}
            }
        }
    }

    /// The ground-truth inliers of `scene` beyond `thr_px` of their
    /// motion's true F, and those within `thr_px` of another motion's
    /// (properties of the scene, counted once whatever the seeds).
    fn add_true_models(&mut self, scene: &Scene, thr_px: f64) {
        let (Some(truth), Ok(points)) = (
            &scene.labels,
            Correspondences::new(&scene.points1, &scene.points2),
        ) else {
            return;
        };
        let thr2 = thr_px * thr_px;
        let mut r = vec![0.0; points.len()];
        let mut explained_by = vec![Vec::new(); points.len()];
        for (t, f) in scene.gt_fundamentals.iter().enumerate() {
            sampson_distances_squared(f, &points, &mut r);
            for (i, _) in r.iter().enumerate().filter(|(_, &d)| d <= thr2) {
                explained_by[i].push(t as i32 + 1);
            }
        }
        for (&l, by) in truth.iter().zip(&explained_by).filter(|(&l, _)| l > 0) {
            self.scene_inliers += 1;
            self.inliers_beyond_thr += usize::from(!by.contains(&l));
            self.inliers_ambiguous += usize::from(by.iter().any(|&t| t != l));
        }
    }

    /// The selection given the true groups, and the significance of each
    /// true F alone (its scene's tests: motions × (N − 7)), once per scene.
    fn add_true_groups(&mut self, scene: &Scene, thr_px: f64) {
        let m = matches(scene);
        let pp = m.principal_point;
        let (Some(truth), Ok(points)) = (
            &scene.labels,
            Correspondences::new(&scene.points1, &scene.points2),
        ) else {
            return;
        };
        let points = points.shifted(pp, pp);
        let image = nfa::ImageRect::new(m.image_size, pp);
        let camera = Camera {
            image,
            focal_px: m.focal_prior,
        };
        let k = scene.num_motions();
        let groups: Vec<Vec<usize>> = (1..=k as i32)
            .map(|t| (0..truth.len()).filter(|&i| truth[i] == t).collect())
            .collect();
        let Ok(selected) = select_groups(&points, &groups, GroupOrigin::Clustered, camera, thr_px)
        else {
            return;
        };
        self.scenes += 1;
        self.true_groups_exact += usize::from(selected.motions == k);
        // The true F in principal-point-centred coordinates: Tᵀ F T, T the
        // shift back to pixels.
        let t = Matrix3::new(1.0, 0.0, pp[0], 0.0, 1.0, pp[1], 0.0, 0.0, 1.0);
        let ln_tests = (k as f64 * (points.len() as f64 - 7.0)).ln();
        for f in &scene.gt_fundamentals {
            let f = t.transpose() * f * t;
            let mut r = vec![0.0; points.len()];
            sampson_distances_squared(&f, &points, &mut r);
            let mut r: Vec<f64> = r.iter().map(|v| v.sqrt()).collect();
            r.sort_by(f64::total_cmp);
            let s = nfa::significance(&r, ln_tests, &nfa::Background::new(&f, &image), thr_px);
            self.true_motions += 1;
            self.true_f_not_significant += usize::from(!s.is_significant());
        }
    }

    fn print(&self) {
        let pct = |x: usize| 100.0 * x as f64 / self.gt_inliers.max(1) as f64;
        let of_scenes = |x: usize| 100.0 * x as f64 / self.scene_inliers.max(1) as f64;
        println!(
            "scene runs {}: over-counted {}, under-counted {}",
            self.runs, self.over, self.under
        );
        println!(
            "clusters: {} motions, {} fragments, {} of gross outliers",
            self.motion_clusters, self.fragments, self.outlier_clusters
        );
        println!(
            "ground-truth inliers {}: {:.2} % called outliers ({:.2} % outside the clustered subset), {:.2} % in fragments, {:.2} % in another motion's cluster",
            self.gt_inliers,
            pct(self.inliers_as_outliers),
            pct(self.outside_subset_as_outliers),
            pct(self.inliers_in_fragments),
            pct(self.inliers_in_other_motion)
        );
        println!(
            "ground-truth inliers beyond thr_px of their motion's true F: {:.2} %; within thr_px of another motion's: {:.2} %",
            of_scenes(self.inliers_beyond_thr),
            of_scenes(self.inliers_ambiguous)
        );
        println!(
            "given the true groups, the selection finds the true count on {} of {} scenes; {} of {} true Fs are not significant alone",
            self.true_groups_exact, self.scenes, self.true_f_not_significant, self.true_motions
        );
        println!(
            "ground-truth outliers {}: {:.2} % in a cluster",
            self.gt_outliers,
            100.0 * self.outliers_in_clusters as f64 / self.gt_outliers.max(1) as f64
        );
    }
}

fn scene_labels(scene: &Scene) -> Vec<i32> {
    scene.labels.clone().unwrap_or_default()
}

fn main() -> ExitCode {
    let o = Options::parse();
    let params = match o.params() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("cluster_anatomy: {e}");
            return ExitCode::FAILURE;
        }
    };
    let scenes = match sctl::dataset::preset_scenes(o.preset, o.from, o.to) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("cluster_anatomy: {e:#}");
            return ExitCode::FAILURE;
        }
    };
    let mut anatomy = Anatomy::default();
    for scene in &scenes {
        anatomy.add_true_models(scene, params.refinement.thr_px);
        anatomy.add_true_groups(scene, params.refinement.thr_px);
        for &seed in &o.seeds {
            let p = params
                .clone()
                .with(|q| q.sampling.seed = scene_seed(seed, &scene.name));
            let mut clustered = vec![false; scene.len()];
            for i in subset_indices(p.sampling.seed, scene.len(), p.sampling.cluster_subset) {
                clustered[i] = true;
            }
            match segment(&matches(scene), &p) {
                Ok(seg) => anatomy.add(
                    &scene_labels(scene),
                    &seg.labels,
                    scene.num_motions(),
                    &clustered,
                ),
                Err(e) => eprintln!("cluster_anatomy: {}: {e}", scene.name),
            }
        }
    }
    anatomy.print();
    ExitCode::SUCCESS
}
