//! The reference code's IRLS variants (`fit`, `unit_weight_fallback`,
//! `sigma_offset_px`, `polish`): exact recovery, the plain refit's bias on
//! off-centre objects, typed errors, and the polish's wiring.

mod common;

use common::{random_scene, sample_indices, Scene};
use geometry::{
    eight_point_normalized, eight_point_plain, frob_distance, polish_fundamental,
    refine_irls_tukey, sampson_distance_squared, Correspondences, GeometryError, IrlsFit,
    IrlsParams, IrlsWorkspace,
};
use nalgebra::Matrix3;
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Every combination of the four switches.
fn all_variants() -> Vec<IrlsParams> {
    let mut list = Vec::new();
    for fit in [IrlsFit::Normalized, IrlsFit::Plain] {
        for unit_weight_fallback in [true, false] {
            for sigma_offset_px in [0.0, 1e-12] {
                for polish in [false, true] {
                    list.push(IrlsParams {
                        fit,
                        unit_weight_fallback,
                        sigma_offset_px,
                        polish,
                        ..IrlsParams::default()
                    });
                }
            }
        }
    }
    list
}

#[test]
fn every_variant_recovers_the_true_f_from_noiseless_inliers() {
    let mut strict_failures = 0;
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(3000 + seed);
        let scene = random_scene(&mut rng, 60, 30, 0.0);
        let sample = sample_indices(&mut rng, 60, 8);
        let start = eight_point_plain(&scene.points.subset(&sample).unwrap()).unwrap();
        for params in all_variants() {
            let run = |initial| refine_irls_tukey(&scene.points, &sample, initial, &params);
            for model in [run(None), run(Some(&start))] {
                match model {
                    Ok(model) => {
                        let d = frob_distance(&model.f, &scene.f_true);
                        assert!(d < 1e-8, "seed {seed}, {params:?}: FROB {d:e}");
                        assert!(model.inliers[60..].iter().all(|&b| !b), "seed {seed}");
                    }
                    // Tukey weights of rounding-noise residuals (~1e-13 to
                    // 1e-11 px, so even with the reference's 1e-12 px offset)
                    // may leave fewer than 8 positive: an error only without
                    // the fallback.
                    Err(GeometryError::TooFewWeightedPoints { .. })
                        if !params.unit_weight_fallback =>
                    {
                        strict_failures += 1
                    }
                    Err(e) => panic!("seed {seed}, {params:?}: {e}"),
                }
            }
        }
    }
    // Of 10 seeds × 8 variants without the fallback × 2 starts, measured:
    // 23 of 80 without the offset, 10 of 80 with it.
    assert!(strict_failures <= 40, "{strict_failures} of 160");
}

/// One rigid object seen in a 150 × 150 px patch off the image centre (1 px
/// noise): at most 150 of its matches, `None` when fewer than 30 fall in
/// the patch.
fn off_centre_object(seed: u64) -> Option<(Scene, Vec<usize>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = random_scene(&mut rng, 5000, 0, 1.0);
    let object: Vec<usize> = (0..scene.points.len())
        .filter(|&i| {
            let [x, y] = scene.points.point1(i);
            (100.0..250.0).contains(&x) && (50.0..200.0).contains(&y)
        })
        .take(150)
        .collect();
    (object.len() >= 30).then_some((scene, object))
}

/// RMS Sampson distance (px) of `points` to `f`, and the share within 2.5 px.
fn fit_quality(f: &Matrix3<f64>, points: &Correspondences) -> (f64, f64) {
    let n = points.len() as f64;
    let d2: Vec<f64> = (0..points.len())
        .map(|i| sampson_distance_squared(f, points.point1(i), points.point2(i)))
        .collect();
    let rms = (d2.iter().sum::<f64>() / n).sqrt();
    let within = d2.iter().filter(|&&v| v <= 2.5 * 2.5).count() as f64 / n;
    (rms, within)
}

#[test]
fn the_plain_fit_of_an_off_centre_object_misses_many_of_its_own_points() {
    // The mechanism of issue 15: the least-squares fit of a whole motion in
    // pixel coordinates is biased when the object is far from the origin.
    // Measured here: within 2.5 px 98.9 % (normalised) against 61.8 %
    // (plain), the normalised fit closer (RMS) in 39 of 40 objects.
    let (mut scenes, mut normalized_better) = (0, 0);
    let (mut within_normalized, mut within_plain) = (0.0, 0.0);
    for seed in 0..40 {
        let Some((scene, object)) = off_centre_object(9000 + seed) else {
            continue;
        };
        let points = scene.points.subset(&object).unwrap();
        let weights = vec![1.0; points.len()];
        let normalized = geometry::eight_point_weighted(&points, &weights).unwrap();
        let plain = geometry::eight_point_weighted_plain(&points, &weights).unwrap();
        let (rms_n, in_n) = fit_quality(&normalized, &points);
        let (rms_p, in_p) = fit_quality(&plain, &points);
        scenes += 1;
        normalized_better += usize::from(rms_n < rms_p);
        within_normalized += in_n;
        within_plain += in_p;
    }
    assert!(scenes >= 30, "{scenes} scenes");
    let (within_normalized, within_plain) = (
        within_normalized / scenes as f64,
        within_plain / scenes as f64,
    );
    assert!(
        normalized_better * 10 >= scenes * 9,
        "{normalized_better} of {scenes}"
    );
    assert!(within_normalized > 0.95, "normalised: {within_normalized}");
    assert!(
        within_plain < within_normalized - 0.2,
        "plain: {within_plain}"
    );
}

#[test]
fn the_plain_refit_finds_fewer_of_an_off_centre_objects_matches() {
    // Measured: 97 % of the object's matches recovered (normalised refit)
    // against 69 % (plain), from the same plain 8-point start.
    let (mut scenes, mut recall_normalized, mut recall_plain) = (0, 0.0, 0.0);
    for seed in 0..40 {
        let Some((scene, object)) = off_centre_object(9000 + seed) else {
            continue;
        };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let sample: Vec<usize> = sample_indices(&mut rng, object.len(), 8)
            .iter()
            .map(|&k| object[k])
            .collect();
        let start = eight_point_plain(&scene.points.subset(&sample).unwrap()).unwrap();
        scenes += 1;
        for (fit, recall) in [
            (IrlsFit::Normalized, &mut recall_normalized),
            (IrlsFit::Plain, &mut recall_plain),
        ] {
            let params = IrlsParams {
                fit,
                ..IrlsParams::default()
            };
            if let Ok(model) = refine_irls_tukey(&scene.points, &sample, Some(&start), &params) {
                let found = object.iter().filter(|&&i| model.inliers[i]).count();
                *recall += found as f64 / object.len() as f64;
            }
        }
    }
    let (normalized, plain) = (
        recall_normalized / scenes as f64,
        recall_plain / scenes as f64,
    );
    assert!(
        normalized > plain + 0.15,
        "normalised {normalized}, plain {plain}"
    );
}

#[test]
fn on_whole_image_scenes_the_normalised_fit_is_still_closer() {
    // A smaller effect when the matches cover the image (measured: RMS
    // 0.998 px against 1.066 px, normalised closer in 37 of 40 scenes).
    let (mut better, mut sum_n, mut sum_p) = (0, 0.0, 0.0);
    for seed in 0..40 {
        let mut rng = ChaCha8Rng::seed_from_u64(9000 + seed);
        let scene = random_scene(&mut rng, 150, 0, 1.0);
        let (rms_n, _) = fit_quality(
            &eight_point_normalized(&scene.points).unwrap(),
            &scene.points,
        );
        let (rms_p, _) = fit_quality(&eight_point_plain(&scene.points).unwrap(), &scene.points);
        better += usize::from(rms_n < rms_p);
        sum_n += rms_n;
        sum_p += rms_p;
    }
    assert!(
        better >= 30 && sum_n < sum_p,
        "{better} of 40, {sum_n} vs {sum_p}"
    );
}

/// A noiseless scene whose sample holds 7 exact matches and 3 gross
/// outliers, with the true F as the start: with σ = 1e-6 px the Tukey
/// weights are positive for exactly the 7 exact matches.
fn seven_positive_weights() -> (Correspondences, Vec<usize>, Matrix3<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let scene = random_scene(&mut rng, 40, 0, 0.0);
    let (p1, mut p2) = common::point_lists(&scene.points);
    for p in &mut p2[7..10] {
        *p = [p[0] + 60.0, p[1] - 45.0];
    }
    let points = Correspondences::new(&p1, &p2).unwrap();
    (points, (0..10).collect(), scene.f_true)
}

#[test]
fn without_the_fallback_too_few_positive_weights_is_a_typed_error() {
    let (points, sample, f_true) = seven_positive_weights();
    for fit in [IrlsFit::Normalized, IrlsFit::Plain] {
        let params = IrlsParams {
            fit,
            sigma_offset_px: 1e-6,
            ..IrlsParams::default()
        };
        // With the fallback, the refit uses unit weights on the 10 matches
        // and the refinement goes on to the inlier step (where the 3
        // outliers' pull on F costs it the hypothesis).
        let r = refine_irls_tukey(&points, &sample, Some(&f_true), &params);
        assert!(
            matches!(r, Err(GeometryError::TooFewInliers { iteration: 1, .. })),
            "{r:?}"
        );
        let strict = IrlsParams {
            unit_weight_fallback: false,
            ..params
        };
        assert_eq!(
            refine_irls_tukey(&points, &sample, Some(&f_true), &strict),
            Err(GeometryError::TooFewWeightedPoints { got: 7, needed: 8 }),
            "{fit:?}"
        );
    }
}

#[test]
fn polish_true_equals_starting_from_the_polished_matrix() {
    let mut workspace = IrlsWorkspace::new();
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(4000 + seed);
        let scene = random_scene(&mut rng, 120, 60, 1.0);
        let sample = sample_indices(&mut rng, 120, 8);
        let start = eight_point_plain(&scene.points.subset(&sample).unwrap()).unwrap();
        // The refinement polishes on the sample's distinct indices, sorted.
        let mut sorted = sample.clone();
        sorted.sort_unstable();
        let polished = polish_fundamental(&scene.points, &sorted, &start).unwrap();
        assert!(polished.cost <= polished.initial_cost);
        let params = IrlsParams::reference_code();
        let unpolished = IrlsParams {
            polish: false,
            ..params
        };
        let a = workspace.refine(&scene.points, &sample, Some(&start), &params);
        let b = workspace.refine(&scene.points, &sample, Some(&polished.f), &unpolished);
        assert_eq!(a, b, "seed {seed}");
    }
}

#[test]
fn sigma_offset_is_validated() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let scene = random_scene(&mut rng, 20, 0, 0.5);
    for bad in [-1e-12, f64::NAN, f64::INFINITY] {
        let params = IrlsParams {
            sigma_offset_px: bad,
            ..IrlsParams::default()
        };
        assert!(matches!(
            refine_irls_tukey(&scene.points, &(0..8).collect::<Vec<_>>(), None, &params),
            Err(GeometryError::InvalidParameter {
                name: "sigma_offset_px",
                ..
            })
        ));
    }
}

#[test]
fn a_sample_of_one_repeated_match_is_a_typed_error_for_every_variant() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let scene = random_scene(&mut rng, 30, 0, 0.5);
    for params in all_variants() {
        for initial in [None, Some(&scene.f_true)] {
            let result = refine_irls_tukey(&scene.points, &[3; 8], initial, &params);
            assert!(
                matches!(
                    result,
                    Err(GeometryError::Degenerate(_) | GeometryError::TooFewWeightedPoints { .. })
                ),
                "{params:?}, start {}: {result:?}",
                initial.is_some()
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Arbitrary (often degenerate) matches and samples: every variant gives
    /// a model or an error value, never a panic, and a model is rank 2 with
    /// unit norm.
    #[test]
    fn arbitrary_input_never_panics(
        pts in prop::collection::vec(
            (prop::sample::select(vec![-200.0, 0.0, 3.5, 150.0]), -300.0..300.0f64,
             -300.0..300.0f64, prop::sample::select(vec![-100.0, 0.0, 7.0])),
            8..24),
        sample in prop::collection::vec(0usize..24, 8..10),
        variant in 0usize..16,
    ) {
        let p1: Vec<[f64; 2]> = pts.iter().map(|p| [p.0, p.1]).collect();
        let p2: Vec<[f64; 2]> = pts.iter().map(|p| [p.2, p.3]).collect();
        let points = Correspondences::new(&p1, &p2).unwrap();
        let sample: Vec<usize> = sample.iter().map(|&i| i % pts.len()).collect();
        let params = all_variants()[variant];
        if let Ok(model) = refine_irls_tukey(&points, &sample, None, &params) {
            prop_assert!((model.f.norm() - 1.0).abs() < 1e-12);
            prop_assert!(model.f.determinant().abs() < 1e-10);
        }
    }
}
