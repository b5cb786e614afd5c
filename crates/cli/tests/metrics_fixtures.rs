//! The clustering metrics against their oracle,
//! `shared/fixtures/stats/clustering.json` (scikit-learn ARI / NMI and the
//! evaluation protocol's ME / PUR / FNR), plus hand-made cases and FROB
//! against an exhaustive assignment. (The Wilcoxon test against scipy is a
//! unit test of `src/wilcoxon`.)

mod support;
use support::load_fixture;

use metrics::{
    adjusted_rand_index, false_negative_rate, frob_score, misclassification_error,
    normalized_mutual_info, purity, ClusteringMetrics, MetricsError,
};
use nalgebra::Matrix3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;

const TOLERANCE: f64 = 1e-9;

#[derive(Deserialize)]
struct Case {
    gt: Vec<i32>,
    pred: Vec<i32>,
    ari: f64,
    nmi: f64,
    me: f64,
    purity: f64,
    fnr: f64,
}

fn load_cases() -> Vec<Case> {
    load_fixture("clustering.json")
}

fn assert_close(what: &str, case: usize, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= TOLERANCE,
        "case {case}: {what} = {got}, oracle {want} (|diff| = {:e})",
        (got - want).abs()
    );
}

#[test]
fn every_fixture_case_agrees_with_the_oracle() {
    let cases = load_cases();
    for (i, c) in cases.iter().enumerate() {
        let m = ClusteringMetrics::compute(&c.pred, &c.gt).expect("fixture labels are valid");
        assert_close("ME", i, m.me, c.me);
        assert_close("ACC", i, m.acc, 1.0 - c.me);
        assert_close("PUR", i, m.pur, c.purity);
        assert_close("FNR", i, m.fnr, c.fnr);
        assert_close("ARI", i, m.ari, c.ari);
        assert_close("NMI", i, m.nmi, c.nmi);
        // The free functions agree with the bundle.
        assert_eq!(misclassification_error(&c.pred, &c.gt).unwrap(), m.me);
        assert_eq!(false_negative_rate(&c.pred, &c.gt).unwrap(), m.fnr);
        assert_eq!(purity(&c.pred, &c.gt).unwrap(), m.pur);
        assert_eq!(adjusted_rand_index(&c.pred, &c.gt).unwrap(), m.ari);
        assert_eq!(normalized_mutual_info(&c.pred, &c.gt).unwrap(), m.nmi);
    }
}

#[test]
fn perfect_labelling_scores_perfectly() {
    let gt = [1, 1, 1, 2, 2, 3, 3, 3, 0, 0];
    let pred = [1, 1, 1, 2, 2, 3, 3, 3, -1, -1];
    let m = ClusteringMetrics::compute(&pred, &gt).unwrap();
    assert_eq!(m.me, 0.0);
    assert_eq!(m.acc, 1.0);
    assert_eq!(m.fnr, 0.0);
    assert_eq!(m.pur, 1.0);
    assert_eq!(m.ari, 1.0);
    assert!((m.nmi - 1.0).abs() < 1e-12, "nmi {}", m.nmi);
}

#[test]
fn permuting_predicted_ids_changes_nothing() {
    let gt = [1, 1, 2, 2, 2, 3, 0, 0, 1, 3, 3, 2];
    let pred = [0, 0, 1, 1, 4, 2, -1, 2, 1, 2, 2, -1];
    // Bijective renaming of the cluster ids (-1 stays -1).
    let renamed: Vec<i32> = pred
        .iter()
        .map(|&p| match p {
            -1 => -1,
            0 => 17,
            1 => 3,
            2 => 0,
            4 => 9,
            other => other + 100,
        })
        .collect();
    let a = ClusteringMetrics::compute(&pred, &gt).unwrap();
    let b = ClusteringMetrics::compute(&renamed, &gt).unwrap();
    for (x, y, name) in [
        (a.me, b.me, "me"),
        (a.fnr, b.fnr, "fnr"),
        (a.pur, b.pur, "pur"),
        (a.ari, b.ari, "ari"),
        (a.nmi, b.nmi, "nmi"),
    ] {
        assert!((x - y).abs() < 1e-15, "{name}: {x} vs {y}");
    }
    // And the values are those worked out by hand: 10 inliers (gt != 0), the
    // best matching 0->1, 1->2, 2->3 agrees on 2 + 2 + 3 = 7 of them.
    assert!((a.me - 3.0 / 10.0).abs() < 1e-15);
}

#[test]
fn a_permuted_perfect_labelling_is_perfect() {
    let gt = [1, 1, 2, 2, 3, 3];
    let pred = [8, 8, 0, 0, 5, 5];
    let m = ClusteringMetrics::compute(&pred, &gt).unwrap();
    assert_eq!((m.me, m.fnr, m.pur, m.ari), (0.0, 0.0, 1.0, 1.0));
}

#[test]
fn all_outliers_predicted() {
    let gt = [1, 1, 2, 2, 0];
    let pred = [-1; 5];
    let m = ClusteringMetrics::compute(&pred, &gt).unwrap();
    assert_eq!(m.me, 1.0);
    assert_eq!(m.acc, 0.0);
    assert_eq!(m.fnr, 1.0);
    assert_eq!(m.pur, 0.0);
    // One predicted class against three true ones: no information.
    assert_eq!(m.nmi, 0.0);
    assert_eq!(m.ari, 0.0);
}

#[test]
fn no_ground_truth_inliers() {
    let gt = [0, 0, 0];
    let pred = [4, -1, 4];
    let m = ClusteringMetrics::compute(&pred, &gt).unwrap();
    assert_eq!(m.me, 0.0);
    assert_eq!(m.fnr, 0.0);
    assert_eq!(m.pur, 1.0);
}

#[test]
fn single_class_on_both_sides_and_empty_input() {
    let m = ClusteringMetrics::compute(&[2, 2, 2], &[1, 1, 1]).unwrap();
    assert_eq!((m.me, m.ari, m.nmi), (0.0, 1.0, 1.0));
    let e = ClusteringMetrics::compute(&[], &[]).unwrap();
    assert_eq!(
        (e.me, e.fnr, e.pur, e.ari, e.nmi),
        (0.0, 0.0, 0.0, 1.0, 1.0)
    );
}

#[test]
fn bad_label_vectors_are_typed_errors() {
    assert_eq!(
        ClusteringMetrics::compute(&[1, 2, 3], &[1, 2]),
        Err(MetricsError::LengthMismatch {
            predicted: 3,
            ground_truth: 2
        })
    );
    assert_eq!(
        misclassification_error(&[1, -2, 3], &[1, 2, 3]),
        Err(MetricsError::InvalidPredictedLabel {
            index: 1,
            label: -2
        })
    );
    let err = purity(&[1, 2, 3], &[1, 2, -1]).unwrap_err();
    assert_eq!(
        err,
        MetricsError::InvalidGroundTruthLabel {
            index: 2,
            label: -1
        }
    );
    assert!(err.to_string().contains("index 2"), "{err}");
}

fn random_fundamental(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
    Matrix3::from_fn(|_, _| rng.gen_range(-1.0..1.0))
}

/// The smallest mean cost over every injective map of the smaller side
/// into the larger one.
fn frob_brute_force(pred: &[Matrix3<f64>], gt: &[Matrix3<f64>]) -> f64 {
    fn best(i: usize, small: &[Matrix3<f64>], large: &[Matrix3<f64>], used: &mut Vec<bool>) -> f64 {
        if i == small.len() {
            return 0.0;
        }
        let mut top = f64::INFINITY;
        for j in 0..large.len() {
            if !used[j] {
                used[j] = true;
                let cost =
                    geometry::frob_distance(&small[i], &large[j]) + best(i + 1, small, large, used);
                top = top.min(cost);
                used[j] = false;
            }
        }
        top
    }
    let (small, large) = if pred.len() <= gt.len() {
        (pred, gt)
    } else {
        (gt, pred)
    };
    best(0, small, large, &mut vec![false; large.len()]) / small.len() as f64
}

#[test]
fn frob_equals_exhaustive_assignment_on_rectangular_sets() {
    let mut rng = ChaCha8Rng::seed_from_u64(45);
    for (p, g) in [(1, 1), (2, 3), (3, 2), (4, 4), (1, 5), (5, 2), (3, 3)] {
        for _ in 0..20 {
            let pred: Vec<_> = (0..p).map(|_| random_fundamental(&mut rng)).collect();
            let gt: Vec<_> = (0..g).map(|_| random_fundamental(&mut rng)).collect();
            let got = frob_score(&pred, &gt).unwrap();
            let want = frob_brute_force(&pred, &gt);
            assert!((got - want).abs() < 1e-12, "{p}x{g}: {got} vs {want}");
        }
    }
}

#[test]
fn frob_recovers_scaled_and_shuffled_matrices_exactly() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let gt: Vec<_> = (0..4).map(|_| random_fundamental(&mut rng)).collect();
    let pred = vec![-3.0 * gt[2], 0.5 * gt[0], 10.0 * gt[3], -gt[1]];
    assert!(frob_score(&pred, &gt).unwrap() < 1e-14);
    // An extra spurious predicted matrix is left unassigned.
    let mut more = pred.clone();
    more.push(random_fundamental(&mut rng));
    assert!(frob_score(&more, &gt).unwrap() < 1e-14);
}

#[test]
fn frob_is_undefined_for_empty_or_degenerate_sides() {
    let f = Matrix3::new(0.0, -1.0, 0.5, 1.0, 0.0, -0.2, -0.5, 0.2, 0.0);
    assert_eq!(frob_score(&[], &[f]), None);
    assert_eq!(frob_score(&[f], &[]), None);
    assert_eq!(frob_score(&[Matrix3::zeros()], &[f]), None);
    let mut nan = f;
    nan[(1, 1)] = f64::NAN;
    assert_eq!(frob_score(&[f], &[nan]), None);
}
