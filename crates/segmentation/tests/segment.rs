//! Algorithm 1 end to end on synthetic scenes of the `quick` preset.

mod support;

use datasets::Scene;
use metrics::ClusteringMetrics;
use segmentation::{
    EightPoint, FocalSolver, GeneratedHypotheses, HypothesisStatus, Linkage, LocalTest, Method,
    OnFailure, Params, Segmentation, SegmentationError,
};
use support::{in_pool, matches, quick_scene};

/// The thesis's pipeline (8-point hypotheses) with `method` and M 300.
fn config(method: Method) -> Params {
    Params {
        method,
        num_samples: 300,
        ..Params::thesis()
    }
}

fn segment(scene: &Scene, params: &Params) -> Result<Segmentation, SegmentationError> {
    segmentation::segment(&matches(scene), params)
}

/// The scene's hypotheses generated on one thread and on two.
fn hypotheses_on_one_and_two_threads(
    scene: &Scene,
    params: &Params,
) -> (GeneratedHypotheses, GeneratedHypotheses) {
    let generate = || segmentation::generate_hypotheses(&matches(scene), params).unwrap();
    (in_pool(1, generate), in_pool(2, generate))
}

fn me(scene: &Scene, seg: &Segmentation) -> f64 {
    ClusteringMetrics::compute(&seg.labels, scene.labels.as_ref().unwrap())
        .unwrap()
        .me
}

#[test]
fn three_synthetic_scenes_are_segmented_with_me_below_5_percent() {
    // Semical is left out on 2/0901: over seeds 1–12 its ME there is 0–40 %
    // (median 28 %) while the baseline's is 0 % on 11 of 12 — the focal
    // filter's known fragility, not a property this test can assert.
    for (category, index) in [(1, 900), (2, 900), (2, 901)] {
        let scene = quick_scene(category, index);
        let methods: &[Method] = if (category, index) == (2, 901) {
            &[Method::Baseline]
        } else {
            &[Method::Baseline, Method::Semical]
        };
        for &method in methods {
            let seg = segment(&scene, &config(method)).unwrap();
            let error = me(&scene, &seg);
            assert!(error < 0.05, "{} {method:?}: ME {error}", scene.name);
            assert_eq!(
                seg.clusters.len(),
                scene.num_motions(),
                "{} {method:?}",
                scene.name
            );
            assert_eq!(seg.counts.generated, 300);
            assert_eq!(seg.hypotheses.len(), 300);
            let kept = seg
                .hypotheses
                .iter()
                .filter(|h| h.status == HypothesisStatus::Kept)
                .count();
            assert_eq!(kept, seg.counts.kept);
            assert!(seg.counts.kept <= seg.counts.refined && seg.counts.refined <= 300);
            match method {
                Method::Baseline => {
                    assert_eq!(seg.counts.kept, seg.counts.refined);
                    assert!(seg.consensus.is_none());
                    assert!(seg.hypotheses.iter().all(|h| h.focals.is_none()));
                }
                Method::Semical => {
                    let c = seg.consensus.as_ref().unwrap();
                    assert_eq!(c.density.len(), 512);
                    // The consensus focal is near the true focal of the camera.
                    let truth = scene.true_focal.unwrap();
                    assert!(
                        (c.f_peak - truth).abs() / truth < 0.3,
                        "{} f_peak {} truth {truth}",
                        scene.name,
                        c.f_peak
                    );
                    // Every kept hypothesis passed the local test and lies in the band.
                    for h in seg
                        .hypotheses
                        .iter()
                        .filter(|h| h.status == HypothesisStatus::Kept)
                    {
                        let (f1, f2) = h.focals.unwrap();
                        assert!(focal::passes_local_test(f1, f2, 0.05));
                        assert!(focal::within_band((f1 + f2) / 2.0, c.f_peak, 0.2));
                    }
                }
            }
            // Each final cluster has its 8-point F, and it fits its points.
            for cluster in &seg.clusters {
                assert!(cluster.size >= 8);
                assert!(cluster.f.is_some());
            }
        }
    }
}

#[test]
fn labels_do_not_depend_on_the_thread_count() {
    let scene = quick_scene(2, 901);
    for method in [Method::Baseline, Method::Semical] {
        let one = in_pool(1, || segment(&scene, &config(method)).unwrap());
        let two = in_pool(2, || segment(&scene, &config(method)).unwrap());
        assert_eq!(one.labels, two.labels);
        assert_eq!(one.hypotheses, two.hypotheses);
        assert_eq!(one.consensus, two.consensus);
        assert_eq!(one.clusters, two.clusters);
    }
    // Another seed draws other samples.
    let a = segment(&scene, &config(Method::Baseline)).unwrap();
    let b = segment(
        &scene,
        &Params {
            seed: 7,
            ..config(Method::Baseline)
        },
    )
    .unwrap();
    assert_ne!(a.counts.refined, 0);
    assert_ne!(a.hypotheses, b.hypotheses);
}

#[test]
fn every_variant_runs_and_labels_every_point() {
    let scene = quick_scene(2, 900);
    let variants = [
        Params {
            refine: false,
            ..config(Method::Semical)
        },
        Params {
            eight_point: EightPoint::Plain,
            ..config(Method::Semical)
        },
        Params {
            focal_solver: FocalSolver::Bougnoux,
            ..config(Method::Semical)
        },
        Params {
            focal_solver: FocalSolver::Bougnoux,
            focal_failure: OnFailure::Prior,
            ..config(Method::Semical)
        },
        Params {
            local_test: LocalTest::ReferenceCode,
            focal_failure: OnFailure::Prior,
            truncate_focals: true,
            ..config(Method::Semical)
        },
        Params {
            linkage: Linkage::JLinkage,
            ..config(Method::Baseline)
        },
    ];
    for v in variants {
        let seg = segment(&scene, &v).unwrap();
        assert_eq!(seg.labels.len(), scene.len());
        let k = seg.clusters.len() as i32;
        assert!(
            seg.labels.iter().all(|&l| l == -1 || (0..k).contains(&l)),
            "{v:?}"
        );
        if !v.refine {
            // Raw minimal samples: nothing is lost to refinement.
            assert!(seg
                .hypotheses
                .iter()
                .all(|h| h.status != HypothesisStatus::RefineFailed));
        }
        if v.focal_failure == OnFailure::Prior {
            assert_eq!(seg.counts.focal_failures, 0, "{v:?}");
            // Every prior stand-in carries exactly the prior.
            let prior = scene.focal_prior();
            let at_prior = seg
                .hypotheses
                .iter()
                .filter(|h| h.focals == Some((prior, prior)))
                .count();
            assert!(seg.counts.focal_priors <= at_prior, "{v:?}");
            if v.focal_solver == FocalSolver::Bougnoux {
                // A closed-form answer is never exactly the prior: every
                // hypothesis at the prior is a stand-in, and there are some.
                assert_eq!(seg.counts.focal_priors, at_prior, "{v:?}");
                assert!(at_prior > 0, "{v:?}");
            }
        } else {
            assert_eq!(seg.counts.focal_priors, 0, "{v:?}");
        }
        if v.truncate_focals {
            assert!(seg
                .hypotheses
                .iter()
                .filter_map(|h| h.focals)
                .all(|(f1, f2)| f1.fract() == 0.0 && f2.fract() == 0.0));
        }
    }
}

#[test]
fn degenerate_input_is_reported_not_panicked_on() {
    let mut scene = quick_scene(1, 900);
    // All points on one line in both images: every 8-point system is rank-deficient.
    let n = scene.len();
    scene.points1 = (0..n).map(|i| [i as f64, 2.0 * i as f64]).collect();
    scene.points2 = (0..n).map(|i| [i as f64 + 1.0, 2.0 * i as f64]).collect();
    let seg = segment(&scene, &config(Method::Semical)).unwrap();
    assert!(seg.labels.iter().all(|&l| l == -1));
    assert!(
        seg.degenerate.as_deref().unwrap().contains("degenerate"),
        "{:?}",
        seg.degenerate
    );
    assert_eq!(seg.counts.kept, 0);

    let mut tiny = quick_scene(1, 900);
    tiny.points1.truncate(7);
    tiny.points2.truncate(7);
    let err = segment(&tiny, &config(Method::Baseline)).unwrap_err();
    assert!(
        matches!(err, SegmentationError::TooFewPoints { n: 7, needed: 8 }),
        "{err}"
    );

    let mut nan = quick_scene(1, 900);
    nan.points2[3][0] = f64::NAN;
    let err = segment(&nan, &config(Method::Baseline))
        .unwrap_err()
        .to_string();
    assert!(err.contains("row 3, column x2"), "{err}");

    let bad = Params {
        thr_px: -1.0,
        ..config(Method::Baseline)
    };
    let err = segment(&quick_scene(1, 900), &bad).unwrap_err().to_string();
    assert!(err.contains("`thr_px`"), "{err}");
}

#[test]
fn minimal_solvers_segment_a_synthetic_scene_and_all_solutions_add_hypotheses() {
    use segmentation::{MinimalSolutions, MinimalSolver};
    let scene = quick_scene(2, 900);
    let focal = scene.true_focal.unwrap();
    let at_truth = matches(&scene).with_focal_prior(focal);
    for solver in [
        MinimalSolver::SevenPoint,
        MinimalSolver::FivePoint,
        MinimalSolver::SixPointFocal,
    ] {
        let best = Params {
            minimal_solver: solver,
            ..config(Method::Baseline)
        };
        let seg = segmentation::segment(&at_truth, &best).unwrap();
        assert!(
            me(&scene, &seg) < 0.05,
            "{solver:?}: ME {}",
            me(&scene, &seg)
        );
        assert_eq!(seg.counts.generated, 300, "{solver:?}");
        let all = Params {
            minimal_solutions: MinimalSolutions::All,
            ..best
        };
        let seg_all = segmentation::segment(&at_truth, &all).unwrap();
        // The 5-point (up to 10) and 6-point (up to 15) solvers return several
        // solutions for most samples; the 7-point one or three.
        assert!(seg_all.counts.generated > 300, "{solver:?}");
        assert_eq!(seg_all.hypotheses.len(), seg_all.counts.generated);
    }
}

#[test]
fn the_default_segments_synthetic_scenes_with_five_point_hypotheses() {
    let params = Params {
        num_samples: 300,
        ..Params::default()
    };
    for (category, index) in [(1, 900), (2, 900), (2, 901)] {
        let scene = quick_scene(category, index);
        let seg = segment(&scene, &params).unwrap();
        assert!(seg.consensus.is_none() && seg.counts.kept == seg.counts.refined);
        assert_eq!(seg.focal_verdict, segmentation::FocalVerdict::NotEstimated);
        assert!(
            me(&scene, &seg) < 0.05,
            "{category}/{index}: ME {}",
            me(&scene, &seg)
        );
    }
}

#[test]
fn an_abstaining_filter_gives_the_baselines_labels_bit_for_bit() {
    use segmentation::{
        generate_hypotheses, segment_with, FocalVerdict, HypothesisFocals, ImplausibleFocal,
    };
    let scene = quick_scene(2, 900);
    let m = matches(&scene);
    let semical = Params {
        focal_solver: FocalSolver::External,
        ..config(Method::Semical)
    };
    let hypotheses = generate_hypotheses(&m, &semical).unwrap();
    // Every hypothesis answers a tiny focal (12 px for a prior of 1024 px),
    // except every tenth, which answers the prior: the consensus is
    // implausible and the filter would keep only the tiny ones.
    let answers: Vec<Option<(f64, f64)>> = (0..hypotheses.models.len())
        .map(|j| {
            Some(if j % 10 == 0 {
                (1024.0, 1024.0)
            } else {
                (12.0, 12.0)
            })
        })
        .collect();
    let focals =
        HypothesisFocals::from_answers(&answers, &hypotheses, &semical, m.focal_prior).unwrap();
    let filtered = segment_with(&m, &semical, &hypotheses, Some(&focals)).unwrap();
    assert_eq!(filtered.focal_verdict, FocalVerdict::Implausible);
    assert!(!filtered.focal_abstained);
    assert!(filtered.counts.kept < filtered.counts.refined);

    let abstain = Params {
        implausible_focal: ImplausibleFocal::Abstain,
        ..semical.clone()
    };
    let abstained = segment_with(&m, &abstain, &hypotheses, Some(&focals)).unwrap();
    assert!(abstained.focal_abstained);
    assert_eq!(abstained.counts.kept, abstained.counts.refined);
    let baseline = Params {
        method: Method::Baseline,
        ..abstain.clone()
    };
    let reference = segment_with(&m, &baseline, &hypotheses, None).unwrap();
    assert_eq!(abstained.labels, reference.labels);
    assert_eq!(abstained.clusters, reference.clusters);
    // The same through `segment` with the baseline's own hypotheses.
    let fresh = segment(
        &scene,
        &Params {
            focal_solver: FocalSolver::Kocur,
            ..baseline
        },
    )
    .unwrap();
    assert_eq!(fresh.labels, reference.labels);
}

/// Scene `<category>/<index>` of the `quick` preset without pixel noise
/// (its gross outliers kept).
fn noise_free_scene(category: u32, index: u32) -> Scene {
    use datasets::synthetic::{Preset, PresetParams, SyntheticParams};
    let PresetParams::Synthetic(quick) = Preset::Quick.params() else {
        panic!("quick is a synthetic preset");
    };
    PresetParams::Synthetic(SyntheticParams {
        noise_sigma: 0.0,
        ..quick
    })
    .generate_scene(1, category, index)
    .unwrap()
    .scene
}

/// The noise-free scenes 1/0900, 2/0900 and 2/0901 of the final-assignment
/// tests, each with its ground truth and its principal-point-centred
/// points under `params`.
fn noise_free_cases(params: &Params) -> Vec<(Scene, Vec<i32>, geometry::Correspondences)> {
    [(1, 900), (2, 900), (2, 901)]
        .into_iter()
        .map(|(category, index)| {
            let scene = noise_free_scene(category, index);
            let truth = scene.labels.clone().unwrap();
            let points = segmentation::centred_points(&matches(&scene), params).unwrap();
            (scene, truth, points)
        })
        .collect()
}

/// True when `labels` equal `truth` (0 = outlier, 1..k motions) up to a
/// renumbering on every match the truth calls an inlier (outliers of the
/// generator are gross mismatches).
fn same_partition_on_inliers(labels: &[i32], truth: &[i32]) -> bool {
    use std::collections::HashMap;
    let (mut forward, mut backward) = (HashMap::new(), HashMap::new());
    labels
        .iter()
        .zip(truth)
        .filter(|(_, &t)| t > 0)
        .all(|(&l, &t)| {
            l >= 0 && *forward.entry(l).or_insert(t) == t && *backward.entry(t).or_insert(l) == l
        })
}

#[test]
fn the_final_assignment_recovers_noise_free_labels_exactly() {
    use segmentation::reassign;
    let params = Params::default();
    for (scene, truth, points) in noise_free_cases(&params) {
        let motions = scene.num_motions();
        // A clustering (labels 0..motions) that left every fifth inlier
        // and every outlier out: the refits must take the left-out inliers
        // back. (A cluster holding a tenth of another motion's matches is
        // not refitted exactly by five IRLS iterations from its 8-point.)
        let perturbed: Vec<i32> = truth
            .iter()
            .enumerate()
            .map(|(i, &t)| if t == 0 || i % 5 == 0 { -1 } else { t - 1 })
            .collect();
        let labels = reassign(&points, &perturbed, motions, &params);
        let what = scene.name.clone();
        assert!(
            same_partition_on_inliers(&labels, &truth),
            "{what} {:?}",
            labels
                .iter()
                .zip(&truth)
                .map(|(&l, &t)| (l, t))
                .collect::<std::collections::BTreeSet<_>>()
        );
        // Numbered by first appearance.
        let firsts: Vec<i32> = labels.iter().fold(Vec::new(), |mut seen, &l| {
            if l >= 0 && !seen.contains(&l) {
                seen.push(l);
            }
            seen
        });
        assert_eq!(firsts, (0..motions as i32).collect::<Vec<_>>(), "{what}");
        // Gross mismatches lie off every motion's epipolar geometry: nearly
        // all end as outliers.
        let outliers: Vec<i32> = (0..truth.len())
            .filter(|&i| truth[i] == 0)
            .map(|i| labels[i])
            .collect();
        let kept = outliers.iter().filter(|&&l| l >= 0).count();
        assert!(
            kept * 10 <= outliers.len(),
            "{what}: {kept} of {}",
            outliers.len()
        );
        // With min_cluster_size above every motion, everything is an outlier.
        let strict = Params {
            min_cluster_size: truth.len(),
            ..params.clone()
        };
        assert!(reassign(&points, &perturbed, motions, &strict)
            .iter()
            .all(|&l| l == -1));
    }
}

#[test]
fn merges_by_refit_join_the_fragments_of_a_motion_and_keep_motions_apart() {
    use segmentation::{fit_cluster, merge_anchored, merge_refitted};
    for params in [Params::default(), Params::fast()] {
        for (scene, truth, points) in noise_free_cases(&params) {
            let motions = scene.num_motions();
            // Every motion split in two interleaved fragments (labels
            // 2 (t - 1) and 2 (t - 1) + 1), the gross outliers left out.
            let fragments: Vec<i32> = truth
                .iter()
                .enumerate()
                .map(|(i, &t)| {
                    if t == 0 {
                        -1
                    } else {
                        2 * (t - 1) + (i % 2) as i32
                    }
                })
                .collect();
            // Anchors: each fragment's own 8-point F.
            let anchors: Vec<_> = (0..2 * motions as i32)
                .map(|c| {
                    let idx: Vec<usize> = (0..fragments.len())
                        .filter(|&i| fragments[i] == c)
                        .collect();
                    fit_cluster(&points, &idx)
                })
                .collect();
            let what = scene.name.clone();
            for labels in [
                merge_refitted(&points, &fragments, 2 * motions, &params),
                merge_anchored(&points, &fragments, 2 * motions, &anchors, &params),
                merge_anchored(&points, &fragments, 2 * motions, &[], &params),
            ] {
                assert!(same_partition_on_inliers(&labels, &truth), "{what}");
                assert_eq!(labels.iter().max(), Some(&(motions as i32 - 1)), "{what}");
            }
            // One fragment per motion: nothing to merge, the labels stay.
            let halves: Vec<i32> = fragments
                .iter()
                .map(|&l| if l % 2 == 0 { l / 2 } else { -1 })
                .collect();
            let half_anchors: Vec<_> = anchors.iter().step_by(2).copied().collect();
            for kept in [
                merge_refitted(&points, &halves, motions, &params),
                merge_anchored(&points, &halves, motions, &half_anchors, &params),
            ] {
                let truth_halves: Vec<i32> = halves.iter().map(|&l| l + 1).collect();
                assert!(same_partition_on_inliers(&kept, &truth_halves), "{what}");
                assert_eq!(kept.iter().max(), Some(&(motions as i32 - 1)), "{what}");
            }
        }
    }
}

#[test]
fn outlier_recovery_takes_back_the_left_out_inliers_and_moves_no_one_else() {
    use segmentation::recover_outliers;
    for params in [Params::default(), Params::fast()] {
        for (scene, truth, points) in noise_free_cases(&params) {
            let motions = scene.num_motions();
            // Every third inlier and every gross outlier left out.
            let clustered: Vec<i32> = truth
                .iter()
                .enumerate()
                .map(|(i, &t)| if t == 0 || i % 3 == 0 { -1 } else { t - 1 })
                .collect();
            let labels = recover_outliers(&points, &clustered, motions, &params);
            let what = scene.name.clone();
            assert!(same_partition_on_inliers(&labels, &truth), "{what}");
            // Clustered matches keep their cluster (the numbering may change).
            assert!(same_partition_on_inliers(
                &labels,
                &clustered.iter().map(|&l| l + 1).collect::<Vec<_>>()
            ));
            // Gross mismatches lie off every motion's epipolar geometry.
            let outliers = truth.iter().filter(|&&t| t == 0).count();
            let joined = (0..truth.len())
                .filter(|&i| truth[i] == 0 && labels[i] >= 0)
                .count();
            assert!(joined * 10 <= outliers, "{what}: {joined} of {outliers}");
        }
    }
}

#[test]
fn segmenting_with_the_final_assignment_recovers_noise_free_labels() {
    use segmentation::{FinalAssignment, Sampling};
    // 2/0901 is left out: with localized samples at M 300 its labels are
    // not exact there (the direct test above covers the assignment).
    for (category, index) in [(2, 900)] {
        let scene = noise_free_scene(category, index);
        let truth = scene.labels.clone().unwrap();
        for sampling in [Sampling::Uniform, Sampling::Localized] {
            let params = Params {
                num_samples: 300,
                sampling,
                final_assignment: FinalAssignment::Refit,
                ..Params::default()
            };
            let seg = segment(&scene, &params).unwrap();
            let what = format!("{} {sampling:?}", scene.name);
            assert!(same_partition_on_inliers(&seg.labels, &truth), "{what}");
            assert_eq!(seg.clusters.len(), scene.num_motions(), "{what}");
            assert!(seg.clusters.iter().all(|c| c.size >= 8), "{what}");
        }
    }
}

#[test]
fn without_a_final_assignment_the_labels_are_the_clusterings() {
    use clustering::ClusteringParams;
    use segmentation::{generate_hypotheses, FinalAssignment};
    let scene = quick_scene(2, 901);
    let params = Params {
        num_samples: 300,
        final_assignment: FinalAssignment::None,
        ..Params::default()
    };
    let seg = segment(&scene, &params).unwrap();
    // The old path by hand: uniform samples (minimal_sample), preferences
    // of every refined hypothesis, T-Linkage and the size filter.
    let generated = generate_hypotheses(&matches(&scene), &params).unwrap();
    let n = scene.len();
    let size = params.sample_size();
    let uniform =
        segmentation::MinimalSampler::new(&scene.points1, segmentation::Sampling::Uniform, size);
    for j in 0..params.num_samples {
        assert_eq!(
            uniform.sample(params.seed, j, size),
            segmentation::minimal_sample(params.seed, j, n, size)
        );
    }
    let clustering_params = ClusteringParams {
        linkage: params.linkage,
        min_cluster_size: params.min_cluster_size,
        ..ClusteringParams::default()
    };
    let mut builder = clustering_params
        .preference_builder(n, params.thr_px * params.thr_px)
        .unwrap();
    let mut residuals = vec![0.0; n];
    for model in generated.models.iter().flatten() {
        geometry::sampson_distances_squared(model, &generated.points, &mut residuals);
        builder.push_residuals(&residuals).unwrap();
    }
    let clustering = clustering_params.cluster(&builder.finish());
    assert_eq!(seg.labels, clustering.labels);
    assert_eq!(seg.clusters.len(), clustering.clusters_after_filter);
}

#[test]
fn localized_sampling_does_not_depend_on_the_thread_count() {
    use segmentation::Sampling;
    let scene = quick_scene(2, 901);
    for base in [
        config(Method::Baseline),
        Params {
            num_samples: 300,
            ..Params::default()
        },
    ] {
        let params = Params {
            sampling: Sampling::Localized,
            ..base.clone()
        };
        let one = in_pool(1, || segment(&scene, &params).unwrap());
        let two = in_pool(2, || segment(&scene, &params).unwrap());
        assert_eq!(one.labels, two.labels);
        assert_eq!(one.hypotheses, two.hypotheses);
        assert_eq!(one.clusters, two.clusters);
        let (h1, h2) = hypotheses_on_one_and_two_threads(&scene, &params);
        assert_eq!(h1.models, h2.models);
        let uniform = segmentation::generate_hypotheses(&matches(&scene), &base).unwrap();
        assert_ne!(h1.models, uniform.models);
        assert!(me(&scene, &one) < 0.05, "ME {}", me(&scene, &one));
    }
}

#[test]
fn guided_sampling_starts_as_mixed_and_does_not_depend_on_the_thread_count() {
    use segmentation::{generate_hypotheses, Sampling};
    let scene = quick_scene(2, 901);
    let mixed = Params {
        num_samples: 300,
        sampling: Sampling::Mixed,
        ..Params::fast()
    };
    let guided = Params {
        sampling: Sampling::Guided,
        guided_batch: 100,
        ..mixed.clone()
    };
    let (h1, h2) = hypotheses_on_one_and_two_threads(&scene, &guided);
    assert_eq!((&h1.models, &h1.fitted), (&h2.models, &h2.fitted));
    let m = generate_hypotheses(&matches(&scene), &mixed).unwrap();
    // The first batch is mixed sampling's; the guided turns after it differ.
    assert_eq!(h1.models[..100], m.models[..100]);
    assert_ne!(h1.models[100..], m.models[100..]);
    let one = in_pool(1, || segment(&scene, &guided).unwrap());
    let two = in_pool(2, || segment(&scene, &guided).unwrap());
    assert_eq!(one.labels, two.labels);
    assert!(me(&scene, &one) < 0.05, "ME {}", me(&scene, &one));
    let zero = Params {
        guided_batch: 0,
        ..guided
    };
    assert!(segment(&scene, &zero).is_err());
}

#[test]
fn guided_sampling_with_every_five_point_root_counts_past_m() {
    use segmentation::{MinimalSolutions, Sampling};
    // Several hypotheses per sample: more than M go into the counts, and
    // the result still does not depend on the thread count.
    let scene = quick_scene(2, 900);
    let params = Params {
        num_samples: 120,
        sampling: Sampling::Guided,
        guided_batch: 60,
        minimal_solutions: MinimalSolutions::All,
        ..Params::fast()
    };
    let (h1, h2) = hypotheses_on_one_and_two_threads(&scene, &params);
    assert!(h1.models.len() > 120, "{} hypotheses", h1.models.len());
    assert_eq!((&h1.models, &h1.fitted), (&h2.models, &h2.fitted));
    let seg = segment(&scene, &params).unwrap();
    assert!(me(&scene, &seg) < 0.1, "ME {}", me(&scene, &seg));
}

#[test]
fn a_size_rule_above_the_floor_only_removes_clusters() {
    use segmentation::SizeRule;
    let scene = quick_scene(2, 900);
    let base = Params {
        num_samples: 300,
        ..Params::default()
    };
    let min_size = segment(&scene, &base).unwrap();
    for rule in [SizeRule::LargestGap, SizeRule::RelativeMin(0.2)] {
        let seg = segment(
            &scene,
            &Params {
                size_rule: rule,
                ..base.clone()
            },
        )
        .unwrap();
        assert!(seg.clusters.len() <= min_size.clusters.len(), "{rule:?}");
        // A point is either where it was or an outlier now.
        for (&a, &b) in min_size.labels.iter().zip(&seg.labels) {
            assert!(b == -1 || a != -1, "{rule:?}");
        }
    }
    let bad = Params {
        size_rule: SizeRule::RelativeMin(1.5),
        ..base
    };
    assert!(segment(&scene, &bad)
        .unwrap_err()
        .to_string()
        .contains("`size_rule`"));
}

#[test]
fn clustering_a_subset_recovers_noise_free_labels_at_any_thread_count() {
    use segmentation::SubsetExtension;
    for (category, index) in [(1, 900), (2, 900)] {
        let scene = noise_free_scene(category, index);
        let truth = scene.labels.clone().unwrap();
        for how in [
            SubsetExtension::Preference,
            SubsetExtension::Model,
            SubsetExtension::ModelRefit,
            SubsetExtension::PreferenceRefit,
            SubsetExtension::Neighbours,
        ] {
            let params = Params {
                num_samples: 300,
                cluster_subset: truth.len() / 2,
                subset_extension: how,
                ..Params::default()
            };
            let one = in_pool(1, || segment(&scene, &params).unwrap());
            let two = in_pool(2, || segment(&scene, &params).unwrap());
            let what = format!("{} {how:?}", scene.name);
            assert_eq!(one.labels, two.labels, "{what}");
            assert_eq!(one.labels.len(), truth.len(), "{what}");
            assert!(same_partition_on_inliers(&one.labels, &truth), "{what}");
            assert_eq!(one.clusters.len(), scene.num_motions(), "{what}");
            // The clusters' sizes count every match, not the subset's.
            let labelled = one.labels.iter().filter(|&&l| l >= 0).count();
            assert_eq!(one.clusters.iter().map(|c| c.size).sum::<usize>(), labelled);
        }
    }
}

#[test]
fn min_consensus_drops_exactly_the_solutions_that_explain_fewer_matches() {
    use segmentation::{generate_hypotheses, MinimalSolutions, MinimalSolver};
    let scene = quick_scene(2, 900);
    let m = matches(&scene);
    // Without refinement a hypothesis is its minimal solution, whose
    // consensus set can be counted here.
    let raw = Params {
        num_samples: 200,
        minimal_solver: MinimalSolver::FivePoint,
        minimal_solutions: MinimalSolutions::BestUnpolished,
        refine: false,
        ..Params::default()
    };
    let all = generate_hypotheses(&m, &raw).unwrap();
    let thr2 = raw.thr_px * raw.thr_px;
    let mut distances = vec![0.0; all.points.len()];
    let mut explained = |f: &nalgebra::Matrix3<f64>| {
        geometry::sampson_distances_squared(f, &all.points, &mut distances);
        distances.iter().filter(|&&d| d <= thr2).count()
    };
    let counts: Vec<Option<usize>> = all
        .models
        .iter()
        .map(|f| f.map(|f| explained(&f)))
        .collect();
    for k in [13, 20, 40] {
        let kept = generate_hypotheses(
            &m,
            &Params {
                min_consensus: k,
                ..raw.clone()
            },
        )
        .unwrap();
        assert_eq!(kept.fitted, all.fitted);
        let expected: Vec<_> = all
            .models
            .iter()
            .zip(&counts)
            .map(|(f, c)| f.filter(|_| c.unwrap() >= k))
            .collect();
        assert_eq!(kept.models, expected, "min_consensus {k}");
        let dropped = kept.models.iter().filter(|f| f.is_none()).count()
            - all.models.iter().filter(|f| f.is_none()).count();
        assert!(
            dropped > 0 && dropped < 200,
            "min_consensus {k}: {dropped} dropped"
        );
    }

    // With refinement the kept hypotheses are refined as before; up to 8
    // nothing changes (fewer than 8 matches were never refined), and the
    // 8-point, which refines from its sample, ignores the key.
    let refined = Params {
        refine: true,
        irls_iters: 1,
        ..raw.clone()
    };
    let before = generate_hypotheses(&m, &refined).unwrap();
    let with = |k: usize, p: &Params| {
        generate_hypotheses(
            &m,
            &Params {
                min_consensus: k,
                ..p.clone()
            },
        )
        .unwrap()
    };
    assert_eq!(with(8, &refined).models, before.models);
    let after = with(20, &refined);
    for ((a, b), c) in after.models.iter().zip(&before.models).zip(&counts) {
        assert_eq!(*a, b.filter(|_| c.is_some_and(|c| c >= 20)));
    }
    let eight = config(Method::Baseline);
    assert_eq!(
        with(1000, &eight).models,
        generate_hypotheses(&m, &eight).unwrap().models
    );
}
