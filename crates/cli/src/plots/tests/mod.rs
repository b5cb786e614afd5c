//! The figures of `plots`: every function writes a decodable PNG of
//! the expected size that is not one flat colour and whose title was
//! rendered, and an SVG with the expected text; empty input draws a "no
//! data" figure; bad input is an error naming the file; the cluster figure
//! puts each point at its pixel in its cluster's colour.

use super::clusters::ClustersLayout;
use super::me_scatter::ScenePair;
use super::me_vs_samples::Series;
use super::test_png::decode_chart as decode_png;
use super::{
    cluster_colour, clusters_over_images, focal_error_histogram, focal_kde, me_scatter,
    me_vs_samples, FocalKdePlot, PlotError, CHART_SIZE, OUTLIER_COLOUR, PEAK_COLOUR,
    TRUE_FOCAL_COLOUR,
};
use image::{Rgb, RgbImage};
use plotters::style::RGBColor;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Ground-truth labels (0 = outlier, 1..k = motion) as plot labels (−1 =
/// outlier, 0..k−1 = cluster), so that [`clusters_over_images`] can draw the
/// ground truth: `j ↦ j − 1` for `j > 0`, anything else `↦ −1`.
fn ground_truth_plot_labels(ground_truth: &[i32]) -> Vec<i32> {
    ground_truth
        .iter()
        .map(|&j| if j > 0 { j - 1 } else { -1 })
        .collect()
}

#[test]
fn ground_truth_plot_labels_example() {
    assert_eq!(ground_truth_plot_labels(&[0, 1, 2, 1]), vec![-1, 0, 1, 0]);
}

fn rgb(c: RGBColor) -> Rgb<u8> {
    Rgb([c.0, c.1, c.2])
}

fn count_colour(image: &RgbImage, colour: RGBColor) -> usize {
    image.pixels().filter(|&&p| p == rgb(colour)).count()
}

/// The SVG document, checked to be one and to contain every `needle`.
fn read_svg(path: &Path, needles: &[&str]) -> String {
    let svg = std::fs::read_to_string(path).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    assert!(svg.trim_end().ends_with("</svg>"));
    for needle in needles {
        assert!(svg.contains(needle), "{} lacks {needle:?}", path.display());
    }
    svg
}

fn out(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    dir.path().join(name)
}

fn me_series() -> Vec<Series> {
    vec![
        Series {
            label: "baseline".into(),
            points: vec![
                (3000, 15.6, 12.2),
                (500, 16.4, 11.0),
                (1000, 16.0, 12.0),
                (5000, 15.5, 12.0),
            ],
        },
        Series {
            label: "semical".into(),
            points: vec![
                (500, 13.0, 12.5),
                (1000, 11.8, 12.4),
                (3000, 10.5, 12.4),
                (5000, 10.5, 12.3),
            ],
        },
    ]
}

#[test]
fn me_vs_samples_draws_every_series() {
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "fig10.png");
    me_vs_samples(&me_series(), &png).unwrap();
    let image = decode_png(&png, CHART_SIZE);
    // Each line and marker is drawn in its series colour.
    assert!(count_colour(&image, cluster_colour(0)) > 100);
    assert!(count_colour(&image, cluster_colour(1)) > 100);
    // Only one series: the second colour is absent.
    let one = out(&dir, "fig10_one.png");
    me_vs_samples(&me_series()[..1], &one).unwrap();
    assert_eq!(
        count_colour(&decode_png(&one, CHART_SIZE), cluster_colour(1)),
        0
    );

    let svg = out(&dir, "fig10.svg");
    me_vs_samples(&me_series(), &svg).unwrap();
    read_svg(
        &svg,
        &["ME (%)", "M (sampled hypotheses)", "baseline", "semical"],
    );
}

fn focal_values() -> Vec<f64> {
    // 400 estimates around 1000 px and 100 scattered ones.
    let mut values: Vec<f64> = (0..400)
        .map(|i| 1000.0 + 40.0 * ((i as f64) * 0.7).sin() + 15.0 * ((i as f64) * 1.3).cos())
        .collect();
    values.extend((0..100).map(|i| 500.0 + 12.0 * i as f64));
    values
}

/// The column holding the most pixels of `colour` and that count.
fn densest_column(image: &RgbImage, colour: RGBColor) -> (u32, usize) {
    let mut counts = vec![0usize; image.width() as usize];
    for (x, _, &p) in image.enumerate_pixels() {
        counts[x as usize] += usize::from(p == rgb(colour));
    }
    let (x, &n) = counts
        .iter()
        .enumerate()
        .max_by_key(|&(x, &n)| (n, std::cmp::Reverse(x)))
        .unwrap();
    (x as u32, n)
}

#[test]
fn focal_kde_draws_the_curve_peak_band_and_true_focal() {
    let values = focal_values();
    let consensus = focal::focal_consensus(&values, &focal::ConsensusParams::default()).unwrap();
    let plot = FocalKdePlot::from_consensus(&values, &consensus, 0.25, Some(1200.0), "scene demo");
    assert_eq!(
        plot.band,
        Some((consensus.f_peak * 0.75, consensus.f_peak * 1.25))
    );
    assert!(
        (consensus.f_peak - 1000.0).abs() < 60.0,
        "{}",
        consensus.f_peak
    );

    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "fig8.png");
    focal_kde(&plot, &png).unwrap();
    let image = decode_png(&png, CHART_SIZE);
    // Both lines are vertical, and the f_peak line (~1000) lies left of the
    // true-focal line (1200).
    let (peak_x, peak_n) = densest_column(&image, PEAK_COLOUR);
    let (true_x, true_n) = densest_column(&image, TRUE_FOCAL_COLOUR);
    assert!(
        peak_n > 400,
        "f_peak line: {peak_n} pixels in column {peak_x}"
    );
    assert!(
        true_n > 200,
        "true focal line: {true_n} pixels in column {true_x}"
    );
    assert!(
        peak_x + 20 < true_x,
        "f_peak at {peak_x}, true focal at {true_x}"
    );

    // Without f_peak and the true focal their lines are gone.
    let bare = FocalKdePlot {
        f_peak: None,
        true_focal: None,
        band: None,
        ..plot
    };
    let png_bare = out(&dir, "fig8_bare.png");
    focal_kde(&bare, &png_bare).unwrap();
    let image = decode_png(&png_bare, CHART_SIZE);
    assert_eq!(count_colour(&image, PEAK_COLOUR), 0);
    assert_eq!(count_colour(&image, TRUE_FOCAL_COLOUR), 0);

    let svg = out(&dir, "fig8.svg");
    focal_kde(&plot, &svg).unwrap();
    read_svg(
        &svg,
        &[
            "scene demo",
            "density",
            "focal length f_avg (px)",
            &format!("f_peak = {:.1}", consensus.f_peak),
            "true focal = 1200.0",
            "Gaussian KDE",
            "f_avg estimates (n = 500",
        ],
    );
}

#[test]
fn focal_kde_rejects_a_grid_without_matching_density() {
    let dir = tempfile::tempdir().unwrap();
    let path = out(&dir, "bad.png");
    let plot = FocalKdePlot {
        values: &[1.0, 2.0],
        grid: &[1.0, 2.0, 3.0],
        density: &[0.1, 0.2],
        f_peak: None,
        band: None,
        true_focal: None,
        title: "bad",
    };
    let err = focal_kde(&plot, &path).unwrap_err();
    assert!(matches!(err, PlotError::InvalidInput { .. }));
    assert_eq!(
        err.to_string(),
        format!(
            "{}: invalid plot input: `grid` has 3 points but `density` has 2",
            path.display()
        )
    );
    assert!(!path.exists());
}

#[test]
fn focal_error_histogram_marks_the_band() {
    let errors = [0.02, -0.1, 0.24, 0.4, 0.9, f64::NAN];
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "fig9.png");
    focal_error_histogram(&errors, 0.25, &png).unwrap();
    decode_png(&png, CHART_SIZE);
    let svg = out(&dir, "fig9.svg");
    focal_error_histogram(&errors, 0.25, &svg).unwrap();
    // |−0.1| counts as 0.1; NaN is left out.
    read_svg(
        &svg,
        &[
            "|f_peak − f_true| / f_true",
            "scenes",
            "within τ_range = 0.25: 3 of 5 scenes",
        ],
    );
    let err = focal_error_histogram(&errors, 0.0, &svg).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "{}: invalid plot input: `tau_range` must be a positive number up to 1e12, got 0",
            svg.display()
        )
    );
}

#[test]
fn me_scatter_counts_wins_and_losses() {
    let pair = |scene: &str, baseline_me, method_me| ScenePair {
        scene: scene.into(),
        baseline_me,
        method_me,
    };
    let pairs = [
        pair("biscuit", 20.0, 5.0),
        pair("book", 12.0, 3.0),
        pair("cube", 4.0, 9.0),
        pair("game", 7.5, 7.5),
        pair("broken", f64::NAN, 1.0),
    ];
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "scatter.png");
    me_scatter(&pairs, &png).unwrap();
    let image = decode_png(&png, CHART_SIZE);
    assert!(
        count_colour(&image, PEAK_COLOUR) > 20,
        "the worse scene is drawn"
    );
    let svg = out(&dir, "scatter.svg");
    me_scatter(&pairs, &svg).unwrap();
    let text = read_svg(
        &svg,
        &[
            "baseline ME (%)",
            "semical ME (%)",
            "semical better: 2",
            "semical worse: 1",
            "tied: 1",
            "biscuit",
            "game",
        ],
    );
    assert!(!text.contains("broken"));
}

#[test]
fn empty_input_draws_a_no_data_figure() {
    let dir = tempfile::tempdir().unwrap();
    let nan_series = [Series {
        label: "nan".into(),
        points: vec![(100, f64::NAN, 1.0)],
    }];
    let no_kde = FocalKdePlot {
        values: &[],
        grid: &[],
        density: &[],
        f_peak: None,
        band: None,
        true_focal: None,
        title: "empty scene",
    };
    let nan_kde = FocalKdePlot {
        values: &[f64::NAN, f64::INFINITY],
        grid: &[f64::NAN],
        density: &[1.0],
        ..no_kde
    };
    for ext in ["png", "svg"] {
        let path = |name: &str| out(&dir, &format!("{name}.{ext}"));
        me_vs_samples(&[], path("me_empty")).unwrap();
        me_vs_samples(&nan_series, path("me_nan")).unwrap();
        focal_kde(&no_kde, path("kde_empty")).unwrap();
        focal_kde(&nan_kde, path("kde_nan")).unwrap();
        clusters_over_images(
            (64, 48),
            None,
            &[],
            &[],
            &[],
            "nothing",
            path("clusters_empty"),
        )
        .unwrap();
        focal_error_histogram(&[], 0.2, path("fig9_empty")).unwrap();
        focal_error_histogram(&[f64::NAN], 0.2, path("fig9_nan")).unwrap();
        me_scatter(&[], path("scatter_empty")).unwrap();
    }
    for name in [
        "me_empty",
        "me_nan",
        "kde_empty",
        "kde_nan",
        "fig9_empty",
        "fig9_nan",
        "scatter_empty",
    ] {
        decode_png(&out(&dir, &format!("{name}.png")), CHART_SIZE);
    }
    read_svg(&out(&dir, "me_empty.svg"), &["no data"]);
    read_svg(
        &out(&dir, "kde_nan.svg"),
        &["empty scene", "no focal estimates"],
    );
    read_svg(
        &out(&dir, "fig9_empty.svg"),
        &["no scene with a known focal length"],
    );
    read_svg(&out(&dir, "scatter_empty.svg"), &["no data"]);
    read_svg(
        &out(&dir, "clusters_empty.svg"),
        &["no correspondences", "outliers (0)"],
    );
    decode_png(
        &out(&dir, "clusters_empty.png"),
        ClustersLayout::new((64, 48)).unwrap().canvas_size,
    );
}

#[test]
fn bad_paths_are_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let pdf = out(&dir, "fig.pdf");
    let err = me_scatter(&[], &pdf).unwrap_err();
    assert!(matches!(err, PlotError::UnsupportedFormat { .. }));
    assert!(err.to_string().starts_with(&pdf.display().to_string()));
    for name in ["missing/fig.png", "missing/fig.svg"] {
        let path = out(&dir, name);
        let err = focal_error_histogram(&[0.1], 0.2, &path).unwrap_err();
        assert!(
            matches!(err, PlotError::Png { .. } | PlotError::Write { .. }),
            "{err:?}"
        );
        assert!(
            err.to_string().starts_with(&path.display().to_string()),
            "{err}"
        );
    }
}

#[test]
fn cluster_colours_are_distinct_and_never_the_outlier_grey() {
    let colours: Vec<RGBColor> = (0..200).map(cluster_colour).collect();
    let distinct: HashSet<(u8, u8, u8)> = colours.iter().map(|c| (c.0, c.1, c.2)).collect();
    assert_eq!(distinct.len(), colours.len());
    for c in &colours {
        assert_ne!(*c, OUTLIER_COLOUR);
        let sum = u32::from(c.0) + u32::from(c.1) + u32::from(c.2);
        assert!(
            sum < 600 && c.0.max(c.1).max(c.2) > 60,
            "{c:?} too close to white or black"
        );
    }
    // Neighbouring labels differ clearly (sum of channel differences).
    for pair in colours.windows(2) {
        let d: i32 = [
            (pair[0].0, pair[1].0),
            (pair[0].1, pair[1].1),
            (pair[0].2, pair[1].2),
        ]
        .iter()
        .map(|&(a, b)| (i32::from(a) - i32::from(b)).abs())
        .sum();
        assert!(d > 60, "{pair:?}");
    }
}

#[test]
fn extreme_values_are_left_out_without_failing() {
    let dir = tempfile::tempdir().unwrap();
    let big = f64::MAX;
    for ext in ["png", "svg"] {
        let path = |name: &str| out(&dir, &format!("{name}.{ext}"));
        let huge = [Series {
            label: "huge".into(),
            points: vec![(1, big, big), (usize::MAX, 1.0, 1.0), (7, 0.0, 0.0)],
        }];
        me_vs_samples(&huge, path("me")).unwrap();
        let wild = FocalKdePlot {
            values: &[big, -big, 1.0],
            grid: &[-big, big],
            density: &[big, 1.0],
            f_peak: Some(big),
            band: Some((-big, big)),
            true_focal: Some(-big),
            title: "wild",
        };
        focal_kde(&wild, path("kde_wild")).unwrap();
        // A range narrower than the floating-point resolution at 1e12.
        let narrow = FocalKdePlot {
            values: &[1e12, 1e12 - 1e-4],
            grid: &[1e12 - 1e-4, 1e12],
            density: &[1e-300, 1e-300],
            f_peak: Some(1e12),
            band: Some((1e12, 1e12)),
            true_focal: None,
            title: "narrow",
        };
        focal_kde(&narrow, path("kde_narrow")).unwrap();
        focal_error_histogram(&[big, 1e-300, 0.0], 1e-300, path("fig9_tiny")).unwrap();
        focal_error_histogram(&[1e12], 1e12, path("fig9_huge")).unwrap();
        let pairs = [ScenePair {
            scene: "s".into(),
            baseline_me: 1e12,
            method_me: -big,
        }];
        me_scatter(&pairs, path("scatter")).unwrap();
        clusters_over_images(
            (u32::MAX, 1),
            None,
            &[[big, -big]],
            &[[0.0, 0.0]],
            &[5],
            "wide",
            path("clusters"),
        )
        .unwrap();
    }
    read_svg(&out(&dir, "kde_wild.svg"), &["f_avg estimates (n = 1)"]);
    read_svg(&out(&dir, "scatter.svg"), &["no data"]);
    let err = focal_error_histogram(&[0.1], f64::INFINITY, out(&dir, "x.svg")).unwrap_err();
    assert!(matches!(err, PlotError::InvalidInput { .. }), "{err}");
}

mod cluster_figures;
