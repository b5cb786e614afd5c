//! The ground-truth checks end to end: `sctl gt-focals` (one row per
//! ground-truth motion, equal to the library's answers on the F fitted to
//! that motion; bad input) and `sctl filter-quality` (counts that add up).

mod support;
use support::{quickstart, sctl};

use geometry::Correspondences;
use predicates::prelude::*;
use sctl::config::ExperimentConfig;
use sctl::pipeline::fit_cluster;

/// What `sctl <subcommand> configs/quickstart.toml` prints (it must succeed).
fn stdout_on_quickstart(subcommand: &str) -> String {
    let assert = sctl().arg(subcommand).arg(quickstart()).assert().success();
    String::from_utf8(assert.get_output().stdout.clone()).unwrap()
}

#[test]
fn one_row_per_motion_with_the_libraries_answers() {
    let text = stdout_on_quickstart("gt-focals");
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), bench_header());
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();

    let config = ExperimentConfig::load(&quickstart()).unwrap();
    let scenes = sctl::dataset::load_scenes(&config.dataset, None, false).unwrap();
    let mut expected = Vec::new();
    for scene in &scenes {
        let points = Correspondences::new(&scene.points1, &scene.points2)
            .unwrap()
            .shifted(scene.principal_point, scene.principal_point);
        let labels = scene.labels.as_ref().unwrap();
        for motion in 1..=scene.num_motions() as i32 {
            let idx: Vec<usize> = (0..labels.len()).filter(|&i| labels[i] == motion).collect();
            let f = fit_cluster(&points, &idx).unwrap();
            let est = focal::robust_focals_multi_start(
                &f,
                scene.focal_prior(),
                &config.pipeline.params.weight_sets.sets(),
                config.pipeline.params.max_iters,
                focal::OnFailure::Report,
            );
            expected.push((
                scene.name.clone(),
                motion,
                idx.len(),
                scene.true_focal,
                est.ok(),
            ));
        }
    }
    assert_eq!(rows.len(), expected.len());
    assert!(rows.len() >= 4);
    for (row, (name, motion, points, f_true, est)) in rows.iter().zip(&expected) {
        assert_eq!(row[0], *name);
        assert_eq!(row[1], motion.to_string());
        assert_eq!(row[2], points.to_string());
        assert_eq!(row[4], format!("{:.3}", f_true.unwrap()));
        match est {
            Some(e) => {
                assert_eq!(row[5], format!("{:.3}", e.f1));
                assert_eq!(row[6], format!("{:.3}", e.f2));
                assert_eq!(row[7], e.iterations.to_string());
                assert_eq!(row[8], "ok");
            }
            None => assert_eq!(row[8], "failed"),
        }
    }
}

fn bench_header() -> &'static str {
    "scene,motion,points,f_prior,f_true,kocur_f1,kocur_f2,kocur_iterations,kocur_status,bougnoux_f1,bougnoux_f2"
}

#[test]
fn a_missing_config_is_an_error_naming_it() {
    sctl()
        .args(["gt-focals", "no/such/config.toml"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("no/such/config.toml"));
}

#[test]
fn filter_quality_counts_add_up_per_scene() {
    let text = stdout_on_quickstart("filter-quality");
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "scene,refined,good_refined,kept,good_kept,discarded,good_discarded"
    );
    let rows: Vec<Vec<usize>> = lines
        .map(|l| l.split(',').skip(1).map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!(r[2] + r[4], r[0], "{r:?}");
        assert_eq!(r[3] + r[5], r[1], "{r:?}");
        assert!(r[1] > 0, "every quick scene has good models: {r:?}");
    }
}
