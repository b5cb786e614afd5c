//! `focal_solver = "external"`: focal lengths read from a file written for
//! the hypotheses of `sctl hypotheses`.

mod support;
use support::quick_scene;

use datasets::Scene;
use nalgebra::Matrix3;
use sctl::config::{FocalSolver, Method, OnFailure, PipelineConfig};
use sctl::pipeline::{
    estimate_hypothesis_focals, generate_hypotheses, segment, segment_with, PipelineError,
};
use std::fmt::Write;
use std::path::Path;

fn kocur() -> PipelineConfig {
    PipelineConfig::from_params(segmentation::Params {
        method: Method::Semical,
        num_samples: 300,
        focal_failure: OnFailure::Prior,
        ..Default::default()
    })
}

/// What the file says of a hypothesis's F.
type ModelMap = fn(&Matrix3<f64>) -> Matrix3<f64>;

/// `-3 F`: the same model at another scale and sign.
fn rescaled(f: &Matrix3<f64>) -> Matrix3<f64> {
    -3.0 * f
}

/// The focal file of `config`'s hypotheses on `scene`, with `focals(j)` as
/// the answer of hypothesis j and, with `models`, `models(F)` as its F.
fn focal_file(
    scene: &Scene,
    config: &PipelineConfig,
    models: Option<ModelMap>,
    focals: impl Fn(usize) -> (f64, f64),
) -> String {
    let with_models = models.is_some();
    let generated = generate_hypotheses(scene, config).unwrap();
    let mut text = String::from("scene,hypothesis,f1,f2");
    if with_models {
        text.push_str(",F00,F01,F02,F10,F11,F12,F20,F21,F22");
    }
    text.push('\n');
    for (j, model) in generated.models.iter().enumerate() {
        let Some(f) = model else { continue };
        let (f1, f2) = focals(j);
        write!(text, "{},{j},{f1:?},{f2:?}", scene.name).unwrap();
        if let Some(map) = models {
            let g = map(f);
            for k in 0..9 {
                write!(text, ",{:e}", g[(k / 3, k % 3)]).unwrap();
            }
        }
        text.push('\n');
    }
    text
}

fn external(path: &Path) -> PipelineConfig {
    let mut config = kocur();
    config.params.focal_solver = FocalSolver::External;
    config.focal_file = path.to_str().unwrap().replace("12345", "{seed}");
    config
}

#[test]
fn the_solvers_own_answers_read_back_give_the_same_segmentation() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("focals_12345.csv");
    for (category, index) in [(1, 900), (2, 901)] {
        let scene = quick_scene(category, index);
        let config = kocur();
        let generated = generate_hypotheses(&scene, &config).unwrap();
        let ours = estimate_hypothesis_focals(&scene, &config, &generated).unwrap();
        let text = focal_file(&scene, &config, Some(rescaled), |j| ours.focals[j].unwrap());
        std::fs::write(&path, text).unwrap();

        let expected = segment(&scene, &config).unwrap();
        let got = segment(&scene, &external(&path)).unwrap();
        assert_eq!(got.labels, expected.labels, "{}", scene.name);
        assert_eq!(got.f_peak(), expected.f_peak(), "{}", scene.name);
        assert_eq!(got.counts.kept, expected.counts.kept, "{}", scene.name);
        // A prior answer read back counts as one.
        let read = estimate_hypothesis_focals(&scene, &external(&path), &generated).unwrap();
        assert_eq!(read.focals, ours.focals);
        for (j, (&theirs, &mine)) in read.from_prior.iter().zip(&ours.from_prior).enumerate() {
            if mine {
                assert!(theirs, "hypothesis {j}");
            }
        }
    }
}

#[test]
fn answers_are_truncated_and_non_finite_ones_leave_no_focals() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("focals_12345.csv");
    let scene = quick_scene(1, 900);
    let text = focal_file(&scene, &kocur(), None, |j| match j % 3 {
        0 => (700.9, 701.2),
        1 => (f64::NAN, 700.0),
        _ => (f64::INFINITY, 1.0),
    });
    std::fs::write(&path, text).unwrap();
    let mut config = external(&path);
    config.params.truncate_focals = true;
    let generated = generate_hypotheses(&scene, &config).unwrap();
    let read = estimate_hypothesis_focals(&scene, &config, &generated).unwrap();
    for (j, model) in generated.models.iter().enumerate() {
        let expected = match (model, j % 3) {
            (Some(_), 0) => Some((700.0, 701.0)),
            _ => None,
        };
        assert_eq!(read.focals[j], expected, "hypothesis {j}");
    }
    // The segmentation runs on the remaining third.
    let seg = segment_with(&scene, &config, &generated, Some(&read)).unwrap();
    assert!((seg.f_peak().unwrap() - 700.5).abs() < 1e-9);
}

#[test]
fn a_file_made_for_other_hypotheses_is_an_error_naming_scene_file_and_hypothesis() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("focals_12345.csv");
    let scene = quick_scene(1, 900);
    // Models that differ (transposed).
    let text = focal_file(&scene, &kocur(), Some(|f| f.transpose()), |_| {
        (700.0, 700.0)
    });
    std::fs::write(&path, text).unwrap();
    let e = segment(&scene, &external(&path)).unwrap_err();
    assert!(matches!(e, PipelineError::FocalFile { .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains(&scene.name) && msg.contains("focals_12345.csv") && msg.contains("another F"),
        "{msg}"
    );

    // A hypothesis missing from the file.
    let text = focal_file(&scene, &kocur(), None, |_| (700.0, 700.0));
    let first_row_dropped: Vec<&str> = text
        .lines()
        .enumerate()
        .filter(|(i, _)| *i != 1)
        .map(|(_, l)| l)
        .collect();
    std::fs::write(&path, first_row_dropped.join("\n")).unwrap();
    let msg = segment(&scene, &external(&path)).unwrap_err().to_string();
    assert!(
        msg.contains("no row for hypothesis") && msg.contains("sctl hypotheses"),
        "{msg}"
    );

    // No file at all; no file named.
    let msg = segment(&scene, &external(&dir.path().join("missing_12345.csv")))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("missing_12345.csv"), "{msg}");
    let unnamed = PipelineConfig {
        focal_file: String::new(),
        ..external(&path)
    };
    let msg = segment(&scene, &unnamed).unwrap_err().to_string();
    assert!(msg.contains("focal_file"), "{msg}");
}
