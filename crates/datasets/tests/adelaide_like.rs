//! The `adelaide-like` preset: HOPE-F's process at AdelaideRMF's image
//! size, outlier shares and inliers per motion.

use datasets::hopef_synth::stats::HopefStats;
use datasets::synthetic::{Preset, PresetParams, SyntheticScene};

/// Validation scenes `0800..0800+per_category` of every category.
fn validation(per_category: u32) -> Vec<SyntheticScene> {
    let params = Preset::AdelaideLike.params();
    Preset::AdelaideLike
        .categories()
        .into_iter()
        .flat_map(|c| (800..800 + per_category).map(move |i| (c, i)))
        .map(|(c, i)| params.generate_scene(1, c, i).unwrap())
        .collect()
}

#[test]
fn the_preset_is_named_and_split_as_hopef() {
    let p = Preset::from_name("adelaide-like").unwrap();
    assert_eq!(p, Preset::AdelaideLike);
    assert_eq!(p.name(), "adelaide-like");
    assert_eq!(p.len(), 4000);
    assert_eq!(p.categories(), vec![1, 2, 3, 4]);
    let PresetParams::Hopef(params) = p.params() else {
        panic!("adelaide-like must use the HOPE-F-faithful generator");
    };
    assert_eq!(params, Preset::adelaide_like_params());
    assert!(params.validate().is_ok());
}

#[test]
fn scenes_have_adelaidermf_image_size_and_outlier_shares() {
    let scenes = validation(5);
    for s in &scenes {
        assert_eq!(s.scene.image_size, (640, 480), "{}", s.scene.name);
        // Keypoints lie in the image, up to the half-pixel offset and noise.
        for [x, y] in s.scene.points1.iter().chain(&s.scene.points2) {
            assert!((-2.0..642.0).contains(x) && (-2.0..482.0).contains(y));
        }
    }
    let stats = HopefStats::compute(&scenes).unwrap();
    // AdelaideRMF: 27-73 % outliers (mean 43 %); the hopef preset: 36 %.
    let mean = stats.outlier_share.mean;
    assert!((0.38..0.58).contains(&mean), "mean outlier share {mean}");
    assert!(stats.outlier_share.quantiles[6] > 0.5);
    // At least 35 matches per object within HOPE-F's labelling band; a few
    // of them may be labelled with a neighbour, so the labelled counts are
    // checked on their 10 % quantile.
    let q10 = stats.matches_per_object.quantiles[1];
    assert!(q10 >= 30.0, "10 % quantile of matches per object {q10}");
}
