//! Tests of the derived files and the figure data.

use super::figures::{run_plot_stem, FOCAL_ERROR_PLOT, ME_SCATTER_PLOT};
use super::stats::MeanStd;
use super::*;
use crate::config::{ExperimentConfig, Method, PlotFormat};
use crate::output::{CsvTable, PLOTS_DIR};
use crate::plots::Series;
use crate::plots::{me_scene_pairs, me_vs_samples_series};
use crate::sweep::SweepPlan;
use std::path::Path;

fn plan() -> SweepPlan {
    let config = ExperimentConfig::parse(
        "name = \"r\"\n[dataset]\nkind = \"synthetic\"\n[sweep]\nmethod = [\"baseline\", \"semical\"]\n",
        Path::new("r.toml"),
    )
    .unwrap();
    SweepPlan::expand(&config).unwrap()
}

/// A row of `header` with 0 in the count columns and every other cell empty.
fn zero_counts(header: &[String]) -> Vec<String> {
    header
        .iter()
        .map(|h| {
            let count = h == "n"
                || h.starts_with("hypotheses_")
                || (h.starts_with("focal_") && h != "focal_verdict")
                || h == "motions"
                || h == "outliers";
            if count { "0" } else { "" }.to_string()
        })
        .collect()
}

fn table(rows: &[(&str, &str, &str, &str)]) -> CsvTable {
    let header = crate::output::per_scene_header(&["method".to_string()]);
    let rows = rows
        .iter()
        .map(|(method, scene, me, frob)| {
            let mut row = zero_counts(&header);
            row[0] = method.to_string();
            row[1] = scene.to_string();
            for (name, v) in [
                ("me", *me),
                ("me_all", *me),
                ("fnr", *me),
                ("frob", *frob),
                ("hypotheses_generated", "10"),
                ("hypotheses_kept", "4"),
            ] {
                let i = header.iter().position(|h| h == name).unwrap();
                row[i] = v.to_string();
            }
            row
        })
        .collect();
    CsvTable { header, rows }
}

#[test]
fn mean_and_population_std() {
    let s = MeanStd::of(&[1.0, 2.0, 3.0, 4.0]).unwrap();
    assert_eq!(s.mean, 2.5);
    assert!((s.std - 1.25f64.sqrt()).abs() < 1e-15);
    assert!(MeanStd::of(&[]).is_none());
}

#[test]
fn summary_is_in_percent_and_tests_pair_by_scene() {
    let p = plan();
    let t = table(&[
        ("baseline", "a", "0.300000", "0.01"),
        ("baseline", "b", "0.200000", ""),
        ("baseline", "c", "0.100000", "0.03"),
        ("semical", "c", "0.050000", "0.02"),
        ("semical", "a", "0.100000", ""),
        ("semical", "b", "0.100000", ""),
    ]);
    let values = RunValues::collect(&p, &t, Path::new("p.csv")).unwrap();
    let s = summary_table(&p, &values);
    let me_mean = s.header.iter().position(|h| h == "me_mean").unwrap();
    assert_eq!(s.rows[0][me_mean], "20.0000");
    let frob_n = s.header.iter().position(|h| h == "frob_scenes").unwrap();
    assert_eq!(s.rows[0][frob_n], "2");
    assert_eq!(s.rows[1][frob_n], "1");
    let against = crate::config::CompareConfig::default().against;
    let tests = wilcoxon_rows(&p, &values, &against);
    assert_eq!(tests.len(), 3);
    assert_eq!(tests[0].combination, 1);
    assert_eq!(tests[0].reference, 0);
    let r = tests[0].result.as_ref().unwrap();
    // Differences baseline - semical, paired by scene: 0.2, 0.1, 0.05: all positive.
    assert_eq!((r.n, r.statistic), (3, 6.0));
    assert!((r.p_value - 0.125).abs() < 1e-12);
    let w = wilcoxon_table(&p, &tests);
    assert_eq!(
        w.rows[0],
        [
            "semical",
            "method=baseline",
            "me",
            "3",
            "6.0",
            "1.250000e-1",
            "exact"
        ]
    );
}

#[test]
fn unknown_combination_is_an_error() {
    let p = plan();
    let t = table(&[("bogus", "a", "0.1", "")]);
    let err = RunValues::collect(&p, &t, Path::new("p.csv"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("p.csv: row 2: parameters (bogus)"), "{err}");
}

/// A per_scene table for a sweep of method × num_samples × tau_range:
/// rows `(method, M, tau_range, scene, me, f_peak_error)`.
fn swept() -> (SweepPlan, CsvTable) {
    swept_with("tau_range = [0.1, 0.3]", "0.3", 0.0)
}

/// As [`swept`] with `third` (a TOML sweep line) as the third swept
/// parameter; ME is `bump` higher where it takes the value `bumped`.
fn swept_with(third: &str, bumped: &str, bump: f64) -> (SweepPlan, CsvTable) {
    let config = ExperimentConfig::parse(
        &format!(
            "name = \"r\"\n[dataset]\nkind = \"synthetic\"\n[sweep]\n\
             method = [\"baseline\", \"semical\"]\nnum_samples = [500, 100]\n{third}\n"
        ),
        Path::new("r.toml"),
    )
    .unwrap();
    let plan = SweepPlan::expand(&config).unwrap();
    let header = crate::output::per_scene_header(&plan.columns);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let mut rows = Vec::new();
    for combo in &plan.combinations {
        let semical = combo.pipeline.params.focal.method == Method::Semical;
        for (s, scene) in ["a", "b"].iter().enumerate() {
            // ME: baseline 0.2 / 0.4 on scenes a / b, semical half of it,
            // and 0.1 lower at M = 500.
            let mut me = 0.2 * (s + 1) as f64;
            if semical {
                me /= 2.0;
            }
            if combo.pipeline.params.sampling.num_samples == 500 {
                me -= 0.1;
            }
            if combo.values[2] == bumped {
                me += bump;
            }
            let mut row = combo.values.clone();
            row.extend(crate::output::SceneResult::default().cells());
            row[3] = scene.to_string();
            row[col("me")] = format!("{me:.6}");
            row[col("hypotheses_generated")] = "10".into();
            row[col("hypotheses_kept")] = "4".into();
            if semical && s == 0 {
                row[col("f_peak_error")] = "0.250000".into();
            }
            rows.push(row);
        }
    }
    (plan, CsvTable { header, rows })
}

/// The Fig. 10 series of a table and their labels.
fn series_of(plan_and_table: (SweepPlan, CsvTable)) -> (Vec<Series>, Vec<String>) {
    let (swept_plan, table) = plan_and_table;
    let values = RunValues::collect(&swept_plan, &table, Path::new("p.csv")).unwrap();
    let series = me_vs_samples_series(&swept_plan, &values).unwrap();
    let labels = series.iter().map(|s| s.label.clone()).collect();
    (series, labels)
}

#[test]
fn me_against_m_has_one_series_per_other_combination() {
    let (series, labels) = series_of(swept());
    assert_eq!(
        labels,
        [
            "method=baseline, tau_range=0.1 (mean ± std over scenes)",
            "method=baseline, tau_range=0.3 (mean ± std over scenes)",
            "method=semical, tau_range=0.1 (mean ± std over scenes)",
            "method=semical, tau_range=0.3 (mean ± std over scenes)"
        ]
    );
    // Semical, tau_range 0.3: M = 500 first (sweep order), ME 0, 10 %
    // (mean 5, std 5), then M = 100: 10, 20 % (mean 15, std 5).
    let points = &series[3].points;
    assert_eq!(points.len(), 2);
    assert_eq!(points[0].0, 500);
    assert!((points[0].1 - 5.0).abs() < 1e-9 && (points[0].2 - 5.0).abs() < 1e-9);
    assert_eq!(points[1].0, 100);
    assert!((points[1].1 - 15.0).abs() < 1e-9 && (points[1].2 - 5.0).abs() < 1e-9);
    // Without num_samples in the sweep there is no such figure.
    assert_eq!(me_vs_samples_series(&plan(), &values_of_plan()), None);
}

#[test]
fn me_against_m_pools_the_seeds_of_a_line() {
    let (series, labels) = series_of(swept_with("seed = [1, 2]", "2", 0.1));
    assert_eq!(
        labels,
        [
            "baseline (mean of 2 seeds ± std across seeds)",
            "semical (mean of 2 seeds ± std across seeds)"
        ]
    );
    // Semical at M = 500: seed 1 has ME 0, 10 % (mean 5), seed 2 10,
    // 20 % (mean 15): pooled mean 10, spread 5.
    let points = &series[1].points;
    assert_eq!(points.len(), 2);
    assert_eq!(points[0].0, 500);
    assert!((points[0].1 - 10.0).abs() < 1e-9, "{points:?}");
    assert!((points[0].2 - 5.0).abs() < 1e-9, "{points:?}");
}

fn values_of_plan() -> RunValues {
    RunValues::collect(&plan(), &table(&[]), Path::new("p.csv")).unwrap()
}

#[test]
fn scatter_pairs_semical_with_its_baseline_and_errors_by_combination() {
    let (plan, table) = swept();
    let values = RunValues::collect(&plan, &table, Path::new("p.csv")).unwrap();
    // Combination 0 is baseline: no pairs.
    assert!(me_scene_pairs(&plan, &values, 0).is_none());
    let semical = plan
        .find(&["semical".into(), "100".into(), "0.3".into()])
        .unwrap();
    let pairs = me_scene_pairs(&plan, &values, semical).unwrap();
    let got: Vec<(&str, f64, f64)> = pairs
        .iter()
        .map(|p| (p.scene.as_str(), p.baseline_me, p.method_me))
        .collect();
    assert_eq!(got.len(), 2);
    for ((scene, b, m), (want_scene, want_b, want_m)) in
        got.iter().zip([("a", 20.0, 10.0), ("b", 40.0, 20.0)])
    {
        assert_eq!(*scene, want_scene);
        assert!((b - want_b).abs() < 1e-9 && (m - want_m).abs() < 1e-9);
    }
    let errors = &values.focal_errors;
    let with_errors: Vec<usize> = (0..errors.len())
        .filter(|&c| !errors[c].is_empty())
        .collect();
    assert_eq!(with_errors, [4, 5, 6, 7]);
    assert_eq!(errors[semical], [0.25]);
    assert_eq!(
        run_plot_stem(FOCAL_ERROR_PLOT, &plan, semical),
        "focal_error__num_samples-100__tau_range-0.3"
    );
}

#[test]
fn run_plots_are_written_and_replace_earlier_ones() {
    let (plan, table) = swept();
    let values = RunValues::collect(&plan, &table, Path::new("p.csv")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let stale = dir.path().join(PLOTS_DIR).join("me_scatter__old.svg");
    std::fs::create_dir_all(stale.parent().unwrap()).unwrap();
    std::fs::write(&stale, "<svg/>").unwrap();
    clear_run_plots(dir.path()).unwrap();
    assert!(!stale.exists());
    let written = write_run_plots(dir.path(), &plan, &values, &[PlotFormat::Svg]).unwrap();
    let mut names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut expected = vec!["me_vs_num_samples.svg".to_string()];
    for m in [100, 500] {
        for tau in ["0.1", "0.3"] {
            for stem in [FOCAL_ERROR_PLOT, ME_SCATTER_PLOT] {
                expected.push(format!("{stem}__num_samples-{m}__tau_range-{tau}.svg"));
            }
        }
    }
    expected.sort();
    assert_eq!(names, expected);
    let histogram = std::fs::read_to_string(
        dir.path()
            .join(PLOTS_DIR)
            .join("focal_error__num_samples-500__tau_range-0.1.svg"),
    )
    .unwrap();
    assert!(histogram.contains("within τ_range = 0.1: 0 of 1 scenes"));
}
