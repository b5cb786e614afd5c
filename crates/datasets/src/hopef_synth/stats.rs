//! The distributions of a set of `hopef` scenes (issue 15's acceptance
//! statistics): N, outlier share, matches per object, |relative yaw|,
//! displacement, label noise and the localisation error of correct matches.
//! `cargo run --release -p datasets --example hopef_stats` prints them.

use super::truth::{HopefTruth, MatchSource};
use crate::synthetic::SyntheticScene;
use crate::DatasetError;
use geometry::sampson_distance;
use std::collections::BTreeMap;
use std::fmt;

/// Summary of one quantity: count, mean and the quantiles min, 10 %, 25 %,
/// median, 75 %, 90 %, max (linear interpolation between order statistics).
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution {
    /// Number of values.
    pub count: usize,
    /// Mean (NaN when empty).
    pub mean: f64,
    /// Quantiles at 0, 0.1, 0.25, 0.5, 0.75, 0.9, 1 (NaN when empty).
    pub quantiles: [f64; 7],
}

/// The probabilities of [`Distribution::quantiles`].
pub const QUANTILES: [f64; 7] = [0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0];

impl Distribution {
    /// The summary of `values` (NaNs are ignored).
    ///
    /// ```
    /// use datasets::hopef_synth::stats::Distribution;
    /// let d = Distribution::of(&[4.0, 1.0, 3.0, 2.0, 5.0]);
    /// assert_eq!(d.count, 5);
    /// assert_eq!(d.mean, 3.0);
    /// assert_eq!(d.quantiles[3], 3.0);
    /// assert_eq!(d.quantiles[2], 2.0);
    /// ```
    pub fn of(values: &[f64]) -> Self {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| !x.is_nan()).collect();
        v.sort_by(f64::total_cmp);
        let quantile = |q: f64| {
            if v.is_empty() {
                return f64::NAN;
            }
            let pos = q * (v.len() - 1) as f64;
            let (i, frac) = (pos.floor() as usize, pos.fract());
            let next = v[(i + 1).min(v.len() - 1)];
            v[i] + frac * (next - v[i])
        };
        Self {
            count: v.len(),
            mean: v.iter().sum::<f64>() / v.len() as f64,
            quantiles: QUANTILES.map(quantile),
        }
    }
}

/// Per-category means.
#[derive(Debug, Clone, PartialEq)]
pub struct CategoryStats {
    /// Scenes of the category.
    pub scenes: usize,
    /// Mean N.
    pub mean_matches: f64,
    /// Mean share of label 0.
    pub mean_outlier_share: f64,
    /// Mean share of true mismatches.
    pub mean_mismatch_share: f64,
}

/// The statistics of a set of `hopef` scenes.
#[derive(Debug, Clone, PartialEq)]
pub struct HopefStats {
    /// Scenes summarised.
    pub scenes: usize,
    /// Matches N per scene.
    pub matches: Distribution,
    /// Share of matches labelled 0 per scene.
    pub outlier_share: Distribution,
    /// Share of true mismatches per scene.
    pub mismatch_share: Distribution,
    /// Matches labelled with each object, per object.
    pub matches_per_object: Distribution,
    /// |yaw₂ − yaw₁| per object, degrees.
    pub relative_yaw_deg: Distribution,
    /// Median |p₂ − p₁| of each object's correct matches, px.
    pub displacement_px: Distribution,
    /// Sampson distance of every correct match to its own object's F, px.
    pub correct_sampson_px: Distribution,
    /// Draws per scene until the acceptance rule held.
    pub attempts: Distribution,
    /// Share of correct matches labelled 0.
    pub correct_labelled_outlier: f64,
    /// Share of correct matches labelled with another object.
    pub correct_labelled_other: f64,
    /// Share of mismatches given an object label.
    pub mismatches_labelled_object: f64,
    /// Means per category (number of objects).
    pub per_category: BTreeMap<u32, CategoryStats>,
}

fn truth_of(s: &SyntheticScene) -> Result<&HopefTruth, DatasetError> {
    s.hopef.as_ref().ok_or_else(|| DatasetError::Generation {
        scene: s.scene.name.clone(),
        problem: "not a `hopef` scene (no generator record)".into(),
    })
}

fn share(part: usize, whole: usize) -> f64 {
    part as f64 / whole.max(1) as f64
}

impl HopefStats {
    /// Computes the statistics of `scenes`; every scene must come from the
    /// `hopef` generator (else the error names it).
    pub fn compute(scenes: &[SyntheticScene]) -> Result<Self, DatasetError> {
        let (mut n, mut outliers, mut mismatches, mut per_object) =
            (vec![], vec![], vec![], vec![]);
        let (mut yaw, mut displacement, mut sampson, mut attempts) =
            (vec![], vec![], vec![], vec![]);
        let [mut correct, mut correct_zero, mut correct_other, mut wrong, mut wrong_object] =
            [0usize; 5];
        let mut categories: BTreeMap<u32, Vec<[f64; 3]>> = BTreeMap::new();
        for s in scenes {
            let truth = truth_of(s)?;
            let scene = &s.scene;
            let labels = scene.labels.as_deref().unwrap_or(&[]);
            let k = truth.objects.len();
            let mut moved: Vec<Vec<f64>> = vec![vec![]; k];
            let mut scene_mismatches = 0;
            for (i, source) in truth.sources.iter().enumerate() {
                let label = labels.get(i).copied().unwrap_or(0);
                let (p1, p2) = (scene.points1[i], scene.points2[i]);
                match *source {
                    MatchSource::Correct { object } => {
                        correct += 1;
                        correct_zero += usize::from(label == 0);
                        correct_other += usize::from(label > 0 && label as usize != object + 1);
                        moved[object]
                            .push(((p2[0] - p1[0]).powi(2) + (p2[1] - p1[1]).powi(2)).sqrt());
                        sampson.push(sampson_distance(&scene.gt_fundamentals[object], p1, p2));
                    }
                    MatchSource::Mismatch { .. } => {
                        wrong += 1;
                        scene_mismatches += 1;
                        wrong_object += usize::from(label > 0);
                    }
                }
            }
            for (j, object) in truth.objects.iter().enumerate() {
                per_object.push(labels.iter().filter(|&&l| l as usize == j + 1).count() as f64);
                yaw.push(object.relative_yaw_deg().abs());
                displacement.push(Distribution::of(&moved[j]).quantiles[3]);
            }
            let row = [
                scene.len() as f64,
                share(scene.num_outliers(), scene.len()),
                share(scene_mismatches, scene.len()),
            ];
            n.push(row[0]);
            outliers.push(row[1]);
            mismatches.push(row[2]);
            attempts.push(f64::from(truth.attempts));
            categories.entry(s.category).or_default().push(row);
        }
        let per_category = categories
            .into_iter()
            .map(|(c, rows)| {
                let mean = |a: usize| rows.iter().map(|r| r[a]).sum::<f64>() / rows.len() as f64;
                let stats = CategoryStats {
                    scenes: rows.len(),
                    mean_matches: mean(0),
                    mean_outlier_share: mean(1),
                    mean_mismatch_share: mean(2),
                };
                (c, stats)
            })
            .collect();
        Ok(Self {
            scenes: scenes.len(),
            matches: Distribution::of(&n),
            outlier_share: Distribution::of(&outliers),
            mismatch_share: Distribution::of(&mismatches),
            matches_per_object: Distribution::of(&per_object),
            relative_yaw_deg: Distribution::of(&yaw),
            displacement_px: Distribution::of(&displacement),
            correct_sampson_px: Distribution::of(&sampson),
            attempts: Distribution::of(&attempts),
            correct_labelled_outlier: share(correct_zero, correct),
            correct_labelled_other: share(correct_other, correct),
            mismatches_labelled_object: share(wrong_object, wrong),
            per_category,
        })
    }
}

impl fmt::Display for HopefStats {
    /// Markdown tables: the distributions, the label noise and the
    /// per-category means.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{} scenes\n", self.scenes)?;
        writeln!(
            f,
            "| quantity | n | mean | min | 10% | 25% | median | 75% | 90% | max |"
        )?;
        writeln!(f, "|---|---|---|---|---|---|---|---|---|---|")?;
        let rows = [
            ("N (matches per scene)", &self.matches),
            ("outlier share (label 0)", &self.outlier_share),
            ("mismatch share (true)", &self.mismatch_share),
            ("matches per object (labelled)", &self.matches_per_object),
            ("abs relative yaw (deg)", &self.relative_yaw_deg),
            (
                "displacement (px, median per object)",
                &self.displacement_px,
            ),
            (
                "Sampson distance of correct matches (px)",
                &self.correct_sampson_px,
            ),
            ("draws per scene", &self.attempts),
        ];
        for (name, d) in rows {
            write!(f, "| {name} | {} | {:.3} |", d.count, d.mean)?;
            for q in d.quantiles {
                write!(f, " {q:.3} |")?;
            }
            writeln!(f)?;
        }
        writeln!(f, "\nlabel noise:")?;
        writeln!(
            f,
            "- correct matches labelled 0: {:.2} %",
            100.0 * self.correct_labelled_outlier
        )?;
        writeln!(
            f,
            "- correct matches labelled with another object: {:.2} %",
            100.0 * self.correct_labelled_other
        )?;
        writeln!(
            f,
            "- mismatches given an object label: {:.2} %",
            100.0 * self.mismatches_labelled_object
        )?;
        writeln!(
            f,
            "\n| category | scenes | mean N | mean outlier share | mean mismatch share |"
        )?;
        writeln!(f, "|---|---|---|---|---|")?;
        for (c, s) in &self.per_category {
            writeln!(
                f,
                "| {c} | {} | {:.1} | {:.3} | {:.3} |",
                s.scenes, s.mean_matches, s.mean_outlier_share, s.mean_mismatch_share
            )?;
        }
        Ok(())
    }
}
