//! `sctl hypotheses` and `focal_solver = "external"` end to end: the
//! hypotheses written are the pipeline's, and a focal file made from them
//! drives `sctl run`.

mod support;
use support::{quickstart, same_up_to_scale as same_model, sctl};

use nalgebra::Matrix3;
use sctl::config::ExperimentConfig;
use sctl::pipeline::generate_hypotheses;
use std::path::Path;

/// `sctl run --allow-failures --out OUT EXP` (it must succeed); returns
/// `per_scene.csv`.
fn run(exp: &Path, out: &Path) -> String {
    sctl()
        .args(["run", "--quiet", "--allow-failures", "--out"])
        .arg(out)
        .arg(exp)
        .assert()
        .success();
    std::fs::read_to_string(out.join("per_scene.csv")).unwrap()
}

#[test]
fn writes_the_pipelines_hypotheses_and_reads_focals_back() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("hyps_{seed}.csv");
    sctl()
        .args(["hypotheses", "--seed", "3", "--out"])
        .arg(&template)
        .arg(quickstart())
        .assert()
        .success();
    let hyps = dir.path().join("hyps_3.csv");
    let text = std::fs::read_to_string(&hyps).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "scene,hypothesis,f_prior,F00,F01,F02,F10,F11,F12,F20,F21,F22"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();

    let mut config = ExperimentConfig::load(&quickstart()).unwrap();
    config.pipeline.params.sampling.seed = 3;
    let scenes = sctl::dataset::load_scenes(&config.dataset, None, false).unwrap();
    let mut expected = 0;
    for scene in &scenes {
        let generated = generate_hypotheses(scene, &config.pipeline).unwrap();
        for j in generated.refined() {
            let row = &rows[expected];
            assert_eq!(
                (row[0], row[1].parse::<usize>().unwrap()),
                (scene.name.as_str(), j)
            );
            assert_eq!(row[2].parse::<f64>().unwrap(), scene.focal_prior());
            let f: Vec<f64> = row[3..].iter().map(|v| v.parse().unwrap()).collect();
            let f = Matrix3::from_row_slice(&f);
            assert!((f.norm() - 1.0).abs() < 1e-12);
            assert!(same_model(&f, generated.models[j].as_ref().unwrap(), 1e-12));
            expected += 1;
        }
    }
    assert_eq!(rows.len(), expected);

    // Answers for every hypothesis (the prior, 1000 px), with F: `sctl run`
    // reads them for semical.
    let mut focals = String::from("scene,hypothesis,f1,f2,F00,F01,F02,F10,F11,F12,F20,F21,F22\n");
    for row in &rows {
        let f = row[3..].join(",");
        focals.push_str(&format!("{},{},1000,1000,{f}\n", row[0], row[1]));
    }
    std::fs::write(dir.path().join("focals_3.csv"), focals).unwrap();
    let exp = dir.path().join("exp.toml");
    let quick = std::fs::read_to_string(quickstart()).unwrap();
    let focal_file = dir.path().join("focals_{seed}.csv");
    let text = quick
        .replace("seed = 12345", "seed = 3\nfocal_solver = \"external\"")
        .replace(
            "[sweep]",
            &format!("focal_file = {:?}\n\n[sweep]", focal_file.to_str().unwrap()),
        );
    std::fs::write(&exp, text).unwrap();
    let per_scene = run(&exp, &dir.path().join("run"));
    let header: Vec<&str> = per_scene.lines().next().unwrap().split(',').collect();
    let peak = header.iter().position(|h| *h == "f_peak").unwrap();
    let method = header.iter().position(|h| *h == "method").unwrap();
    let semical: Vec<Vec<&str>> = per_scene
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[method] == "semical")
        .collect();
    assert_eq!(semical.len(), scenes.len());
    for row in semical {
        assert_eq!(row[peak].parse::<f64>().unwrap(), 1000.0, "{row:?}");
    }

    // The same file for another seed's hypotheses is refused: every
    // semical scene records the error, naming the file.
    let other = std::fs::read_to_string(&exp)
        .unwrap()
        .replace("seed = 3", "seed = 4");
    std::fs::write(&exp, other).unwrap();
    std::fs::copy(
        dir.path().join("focals_3.csv"),
        dir.path().join("focals_4.csv"),
    )
    .unwrap();
    let per_scene = run(&exp, &dir.path().join("run4"));
    let refused = per_scene
        .lines()
        .filter(|l| {
            l.starts_with("semical,")
                && l.contains("failed: focal file: ")
                && l.contains("focals_4.csv")
        })
        .count();
    assert_eq!(refused, scenes.len(), "{per_scene}");

    // No file for the seed: the run stops before any scene, naming it.
    let missing = std::fs::read_to_string(&exp)
        .unwrap()
        .replace("seed = 4", "seed = 5");
    std::fs::write(&exp, missing).unwrap();
    sctl()
        .args(["run", "--quiet", "--out"])
        .arg(dir.path().join("run5"))
        .arg(&exp)
        .assert()
        .failure()
        .stderr(predicates::str::contains("focal_file: "))
        .stderr(predicates::str::contains("focals_5.csv"));
    assert!(!dir.path().join("run5").join("per_scene.csv").exists());
}
