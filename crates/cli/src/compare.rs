//! `sctl compare`: a paired comparison of two runs on their common scenes
//! (means, wins and losses, Wilcoxon signed-rank p-values).

use crate::output::{CsvTable, SceneResult, PER_SCENE_FILE};
use crate::report::{lower_is_better, paired, summary_scale, SUMMARY_METRICS};
use crate::wilcoxon::{wilcoxon, Alternative, Mode, WilcoxonError, WilcoxonResult};
use anyhow::{bail, Context, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The per-scene values of one combination of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSide {
    /// The `per_scene.csv` read.
    pub file: PathBuf,
    /// The combination, as `key=value` pairs.
    pub label: String,
    /// `(scene, value)` of the compared metric, in file order.
    pub values: Vec<(String, f64)>,
}

/// A selection of a combination by one parameter: `KEY=VALUE`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Filter {
    /// The parameter column.
    pub key: String,
    /// Its value, as written in `per_scene.csv`.
    pub value: String,
}

/// A `--a` / `--b` argument that is not `KEY=VALUE`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not KEY=VALUE (e.g. method=semical)")]
pub struct FilterError(String);

/// Parses `KEY=VALUE`.
pub fn parse_filter(s: &str) -> std::result::Result<Filter, FilterError> {
    s.split_once('=')
        .map(|(k, v)| Filter {
            key: k.trim().to_string(),
            value: v.trim().to_string(),
        })
        .filter(|f| !f.key.is_empty())
        .ok_or_else(|| FilterError(s.to_string()))
}

/// Reads the combination of run `path` (a run directory or its
/// `per_scene.csv`) selected by `filters`; the filters must leave exactly
/// one combination.
pub fn load_side(path: &Path, metric: &str, filters: &[Filter]) -> Result<RunSide> {
    let file = if path.is_dir() {
        path.join(PER_SCENE_FILE)
    } else {
        path.to_path_buf()
    };
    let table = CsvTable::read(&file)?;
    let scene_col = table.require_column("scene", &file)?;
    if table.header[scene_col..] != SceneResult::fields() {
        bail!(
            "{}: not a per_scene.csv written by sctl run",
            file.display()
        );
    }
    let params = &table.header[..scene_col];
    let metric_col = table.require_column(metric, &file)?;
    let mut cols = Vec::new();
    for Filter { key, value } in filters {
        let col = params.iter().position(|p| p == key).with_context(|| {
            format!(
                "{}: no parameter column `{key}` (columns: {})",
                file.display(),
                params.join(", ")
            )
        })?;
        cols.push((col, value));
    }
    let rows: Vec<&Vec<String>> = table
        .rows
        .iter()
        .filter(|r| cols.iter().all(|(c, v)| &&r[*c] == v))
        .collect();
    let mut combos: Vec<&[String]> = rows.iter().map(|r| &r[..scene_col]).collect();
    combos.sort();
    combos.dedup();
    let label_of = |values: &[String]| {
        params
            .iter()
            .zip(values)
            .map(|(k, v)| format!("{k}={v}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    match combos.len() {
        0 => bail!("{}: no row matches the selection", file.display()),
        1 => {}
        _ => bail!(
            "{}: {} combinations match; select one with --a/--b KEY=VALUE: {}",
            file.display(),
            combos.len(),
            combos
                .iter()
                .map(|c| label_of(c))
                .collect::<Vec<_>>()
                .join(" | ")
        ),
    }
    let label = label_of(combos[0]);
    let mut values = Vec::new();
    for (r, row) in rows.iter().enumerate() {
        let cell = &row[metric_col];
        if cell.is_empty() {
            continue;
        }
        let v: f64 = cell.parse().with_context(|| {
            format!(
                "{}: row {}: `{metric}` = `{cell}` is not a number",
                file.display(),
                r + 2
            )
        })?;
        values.push((row[scene_col].clone(), v));
    }
    Ok(RunSide {
        file,
        label,
        values,
    })
}

/// The paired comparison of A and B on one metric.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The metric.
    pub metric: String,
    /// Common scenes.
    pub pairs: usize,
    /// Mean of A and of B on the common scenes (summary units: percent for
    /// the label metrics).
    pub means: (f64, f64),
    /// Scenes where A is better, where B is better, and ties.
    pub wins: (usize, usize, usize),
    /// Wilcoxon p-values (method `auto`): two-sided, H1 "A is better",
    /// H1 "B is better".
    pub tests: [std::result::Result<WilcoxonResult, WilcoxonError>; 3],
}

/// Compares A and B on their common scenes (in A's order).
pub fn compare(a: &RunSide, b: &RunSide, metric: &str) -> Result<Comparison> {
    if !SUMMARY_METRICS.contains(&metric) {
        bail!(
            "unknown metric `{metric}` (one of {})",
            SUMMARY_METRICS.join(", ")
        );
    }
    let (x, y) = paired(&a.values, &b.values);
    if x.is_empty() {
        bail!(
            "{} and {} have no scene in common",
            a.file.display(),
            b.file.display()
        );
    }
    let lower = lower_is_better(metric);
    let scale = summary_scale(metric);
    let mut wins = (0, 0, 0);
    for (va, vb) in x.iter().zip(&y) {
        if va == vb {
            wins.2 += 1;
        } else if (va < vb) == lower {
            wins.0 += 1;
        } else {
            wins.1 += 1;
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64 * scale;
    // "A is better" for an error metric: B's values are larger.
    let (a_better, b_better) = if lower {
        (Alternative::Less, Alternative::Greater)
    } else {
        (Alternative::Greater, Alternative::Less)
    };
    Ok(Comparison {
        metric: metric.to_string(),
        pairs: x.len(),
        means: (mean(&x), mean(&y)),
        wins,
        tests: [
            wilcoxon(&x, &y, Alternative::TwoSided, Mode::Auto),
            wilcoxon(&x, &y, a_better, Mode::Auto),
            wilcoxon(&x, &y, b_better, Mode::Auto),
        ],
    })
}

/// The text `sctl compare` prints.
pub fn render(a: &RunSide, b: &RunSide, c: &Comparison) -> String {
    let unit = if c.metric == "frob" { "" } else { " %" };
    let p = |r: &std::result::Result<WilcoxonResult, WilcoxonError>| match r {
        Ok(r) => format!("{:.4e} ({}, n = {})", r.p_value, r.mode_used, r.n),
        Err(e) => format!("undefined ({e})"),
    };
    let mut out = String::new();
    let _ = writeln!(out, "A: {} ({})", a.label, a.file.display());
    let _ = writeln!(out, "B: {} ({})", b.label, b.file.display());
    let _ = writeln!(
        out,
        "{} common scenes, metric {}",
        c.pairs,
        c.metric.to_uppercase()
    );
    let _ = writeln!(
        out,
        "mean A {:.4}{unit}, mean B {:.4}{unit}",
        c.means.0, c.means.1
    );
    let _ = writeln!(
        out,
        "A better on {}, B better on {}, ties {}",
        c.wins.0, c.wins.1, c.wins.2
    );
    let _ = writeln!(out, "Wilcoxon p two-sided: {}", p(&c.tests[0]));
    let _ = writeln!(out, "Wilcoxon p, H1 A better: {}", p(&c.tests[1]));
    let _ = writeln!(out, "Wilcoxon p, H1 B better: {}", p(&c.tests[2]));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn side(values: &[(&str, f64)]) -> RunSide {
        RunSide {
            file: "x.csv".into(),
            label: "method=x".into(),
            values: values.iter().map(|(s, v)| (s.to_string(), *v)).collect(),
        }
    }

    #[test]
    fn pairs_common_scenes_and_counts_wins_by_direction() {
        let a = side(&[("s1", 0.1), ("s2", 0.2), ("s3", 0.3), ("only_a", 0.9)]);
        let b = side(&[("s3", 0.4), ("s2", 0.2), ("s1", 0.3)]);
        let c = compare(&a, &b, "me").unwrap();
        assert_eq!(c.pairs, 3);
        assert_eq!(c.wins, (2, 0, 1));
        assert!((c.means.0 - 20.0).abs() < 1e-12 && (c.means.1 - 30.0).abs() < 1e-12);
        // ME: A is lower on the two non-tied scenes.
        let a_better = c.tests[1].as_ref().unwrap();
        assert!((a_better.p_value - 0.25).abs() < 1e-12, "{a_better:?}");
        let c = compare(&a, &b, "ari").unwrap();
        assert_eq!(c.wins, (0, 2, 1));
        assert!(compare(&a, &b, "speed").is_err());
        assert!(compare(&a, &side(&[("zz", 1.0)]), "me").is_err());
    }

    #[test]
    fn filters_parse() {
        assert_eq!(
            parse_filter("method=semical").unwrap(),
            Filter {
                key: "method".into(),
                value: "semical".into()
            }
        );
        assert!(parse_filter("method").is_err());
        assert!(parse_filter("=x").is_err());
    }
}
