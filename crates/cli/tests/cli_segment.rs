//! `sctl segment` on a user's match file.

mod support;
use support::sctl;

use datasets::synthetic::Preset;
use metrics::ClusteringMetrics;
use predicates::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Writes a synthetic two-motion scene as `x1,y1,x2,y2,label` and returns
/// its ground-truth labels.
fn write_matches(path: &Path) -> Vec<i32> {
    let scene = Preset::Quick
        .params()
        .generate_scene(1, 2, 900)
        .unwrap()
        .scene;
    let labels = scene.labels.clone().unwrap();
    let mut text = String::from("x1,y1,x2,y2,label\n");
    for ((p, q), label) in scene.points1.iter().zip(&scene.points2).zip(&labels) {
        let _ = writeln!(text, "{},{},{},{},{label}", p[0], p[1], q[0], q[1]);
    }
    std::fs::write(path, text).unwrap();
    assert_eq!(scene.image_size, (1024, 768));
    labels
}

/// `sctl segment --matches MATCHES --width 1024 --height 768` (the size of
/// [`write_matches`]'s scene).
fn segment_1024x768(matches: &Path) -> assert_cmd::Command {
    let mut cmd = sctl();
    cmd.arg("segment")
        .arg("--matches")
        .arg(matches)
        .args(["--width", "1024", "--height", "768"]);
    cmd
}

#[test]
fn segments_a_match_file_and_writes_one_label_per_row() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    let truth = write_matches(&matches);
    let params = dir.path().join("params.toml");
    std::fs::write(&params, "[pipeline]\nnum_samples = 300\n").unwrap();
    let out = dir.path().join("labels.txt");
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .args(["--width", "1024", "--height", "768", "--config"])
        .arg(&params)
        .arg("--out")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("2 motion(s) found"))
        .stdout(predicate::str::contains(
            "five-point hypotheses at the focal prior 1024 px",
        ))
        .stdout(predicate::str::contains("against the file's labels: ME"))
        .stdout(predicate::str::contains("(all points: "));
    let labels: Vec<i32> = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    assert_eq!(labels.len(), truth.len());
    let m = ClusteringMetrics::compute(&labels, &truth).unwrap();
    assert!(m.me < 0.05, "ME {}", m.me);

    // Without --out only the summary is printed, on stdout.
    let output = segment_1024x768(&matches)
        .arg("--config")
        .arg(&params)
        .output()
        .unwrap();
    assert!(output.status.success());
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("motion(s) found"), "{stdout}");
    assert!(!stdout.lines().any(|l| l == "-1" || l == "0"), "{stdout}");

    // With --out - the labels go to stdout, the summary to stderr; the
    // image size may come from the sidecar.
    std::fs::write(dir.path().join("pair.toml"), "width = 1024\nheight = 768\n").unwrap();
    let output = sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .arg("--config")
        .arg(&params)
        .args(["--threads", "1", "--out", "-"])
        .output()
        .unwrap();
    assert!(output.status.success());
    let stdout: Vec<i32> = String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    assert_eq!(stdout, labels, "the same labels at 1 thread");
    assert!(String::from_utf8(output.stderr)
        .unwrap()
        .contains("motion(s) found"));

    // The samples depend on the seed, not on the file's name: the same
    // labels and the same hypothesis counts (which differ between samples)
    // under another name, and other counts under another seed.
    let summary = |file: &Path, config: &Path| {
        let output = sctl()
            .arg("segment")
            .arg("--matches")
            .arg(file)
            .args([
                "--width", "1024", "--height", "768", "--out", "-", "--config",
            ])
            .arg(config)
            .output()
            .unwrap();
        assert!(output.status.success());
        let stderr = String::from_utf8(output.stderr).unwrap();
        let counts = stderr[stderr.find("hypotheses kept").unwrap()..]
            .lines()
            .next()
            .unwrap()
            .to_string();
        (String::from_utf8(output.stdout).unwrap(), counts)
    };
    // The thesis's semical: its filter keeps seed-dependent counts.
    let thesis =
        "[pipeline]\nmethod = \"semical\"\nminimal_solver = \"eight-point\"\nnum_samples = 300\n";
    let semical = dir.path().join("semical.toml");
    std::fs::write(&semical, thesis).unwrap();
    let renamed = dir.path().join("another name.csv");
    std::fs::copy(&matches, &renamed).unwrap();
    let (original, counts) = summary(&matches, &semical);
    assert_eq!(summary(&renamed, &semical), (original, counts.clone()));
    let other_seed = dir.path().join("seed.toml");
    std::fs::write(&other_seed, format!("{thesis}seed = 7\n")).unwrap();
    assert_ne!(summary(&matches, &other_seed).1, counts);
}

#[test]
fn bad_inputs_fail_with_the_file_and_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches);
    // No image size and no sidecar.
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .assert()
        .failure()
        .stderr(predicate::str::contains("pair.csv"));
    // A coordinate that is not a number.
    let broken = dir.path().join("broken.csv");
    std::fs::write(&broken, "x1,y1,x2,y2\n1,2,3,4\n5,6,x,8\n").unwrap();
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&broken)
        .args(["--width", "640", "--height", "480"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("broken.csv").and(predicate::str::contains("x2")));
    // A bad parameter file names its key; an unknown profile, in the file
    // or on the command line, lists the profiles.
    let params = dir.path().join("params.toml");
    let bad_config = |text: &str, message: &str| {
        std::fs::write(&params, text).unwrap();
        segment_1024x768(&matches)
            .arg("--config")
            .arg(&params)
            .assert()
            .failure()
            .stderr(predicate::str::contains(message));
    };
    bad_config(
        "[pipeline]\nlinkage = \"k-linkage\"\n",
        "params.toml:2: pipeline.linkage: unknown variant `k-linkage`",
    );
    bad_config(
        "[pipeline]\nprofile = \"quick\"\n",
        "params.toml:2: pipeline.profile: unknown profile `quick`; expected one of: default, thesis",
    );
    segment_1024x768(&matches)
        .args(["--profile", "quick"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "unknown profile `quick`; expected one of: default, thesis",
        ));
    // A memory bound below the clustering's need stops at once and says
    // what it would need: the quick scene's 150 matches at M 20 000 need
    // more than 1 MB.
    bad_config(
        "[pipeline]\nmax_memory_mb = 1\nnum_samples = 20000\n",
        "x 20000 hypotheses would need about",
    );
    bad_config(
        "[pipeline]\nmax_memory_mb = 1\nnum_samples = 20000\n",
        "above max_memory_mb = 1: lower num_samples or raise max_memory_mb",
    );
    // --width needs --height.
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .args(["--width", "1024"])
        .assert()
        .failure();
}

/// A `width × height` PNG of one colour.
fn write_png(path: &Path, size: (u32, u32), colour: [u8; 3]) {
    image::RgbImage::from_pixel(size.0, size.1, image::Rgb(colour))
        .save_with_format(path, image::ImageFormat::Png)
        .unwrap();
}

fn count_pixels(path: &Path, colour: [u8; 3]) -> usize {
    let image = image::open(path).unwrap().to_rgb8();
    image.pixels().filter(|p| p.0 == colour).count()
}

#[test]
fn plot_draws_the_clusters_over_the_images_or_blank_canvases() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches);
    let params = dir.path().join("params.toml");
    std::fs::write(&params, "[pipeline]\nnum_samples = 300\n").unwrap();
    let segment = || {
        let mut cmd = sctl();
        cmd.arg("segment")
            .arg("--matches")
            .arg(&matches)
            .args(["--width", "1024", "--height", "768", "--config"])
            .arg(&params)
            .arg("--out")
            .arg(dir.path().join("labels.txt"));
        cmd
    };

    let blank = dir.path().join("blank.png");
    segment()
        .arg("--plot")
        .arg(&blank)
        .assert()
        .success()
        .stdout(predicate::str::contains("clusters drawn in"));
    // Two 800 x 600 panels (the 1024 x 768 image scaled by 0.78125).
    let figure = image::open(&blank).unwrap().to_rgb8();
    assert!(figure.width() > 1600 && figure.height() > 600);
    // Cluster 0's colour (the first palette entry) marks points.
    let cluster0 = [31, 119, 180];
    assert!(count_pixels(&blank, cluster0) > 100);

    // Over the images: their colour fills most of both panels.
    let teal = [10, 200, 150];
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    write_png(&a, (1024, 768), teal);
    write_png(&b, (1024, 768), teal);
    let over = dir.path().join("over.png");
    segment()
        .arg("--plot")
        .arg(&over)
        .arg("--image1")
        .arg(&a)
        .arg("--image2")
        .arg(&b)
        .assert()
        .success();
    assert_eq!(count_pixels(&blank, teal), 0);
    assert!(
        count_pixels(&over, teal) > 2 * 800 * 600 * 8 / 10,
        "the images are not under the points"
    );
    assert!(count_pixels(&over, cluster0) > 100);

    // SVG by extension.
    let svg = dir.path().join("clusters.svg");
    segment().arg("--plot").arg(&svg).assert().success();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("motion(s)"));
}

#[test]
fn bad_plot_arguments_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches);
    let good = dir.path().join("good.png");
    write_png(&good, (1024, 768), [0, 0, 0]);
    let segment = |image1: &Path, plot: &str| {
        let mut cmd = sctl();
        cmd.arg("segment")
            .arg("--matches")
            .arg(&matches)
            .args(["--width", "1024", "--height", "768", "--plot"])
            .arg(dir.path().join(plot))
            .arg("--image1")
            .arg(image1)
            .arg("--image2")
            .arg(&good);
        cmd
    };
    let missing = dir.path().join("missing.png");
    segment(&missing, "out.png")
        .assert()
        .failure()
        .stderr(predicate::str::contains(format!(
            "{}: cannot open the image",
            missing.display()
        )));
    let jpeg = dir.path().join("photo.jpg");
    std::fs::write(
        &jpeg,
        b"\xff\xd8\xff\xe0\x00\x10JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00",
    )
    .unwrap();
    segment(&jpeg, "out.png")
        .assert()
        .failure()
        .stderr(predicate::str::contains(format!(
            "{}: cannot decode the image",
            jpeg.display()
        )));
    let small = dir.path().join("small.png");
    write_png(&small, (640, 480), [0, 0, 0]);
    segment(&small, "out.png")
        .assert()
        .failure()
        .stderr(predicate::str::contains(format!(
            "{}: the image is 640 x 480 pixels but the matches are for 1024 x 768",
            small.display()
        )));
    let not_an_image = dir.path().join("text.png");
    std::fs::write(&not_an_image, "hello").unwrap();
    segment(&not_an_image, "out.png")
        .assert()
        .failure()
        .stderr(predicate::str::contains(not_an_image.display().to_string()));
    // The figure's own format is checked before any work.
    segment(&good, "out.pdf")
        .assert()
        .failure()
        .stderr(predicate::str::contains("out.pdf: unsupported plot format"));
    assert!(!dir.path().join("out.png").exists());
    // Images need --plot and each other.
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .args(["--width", "1024", "--height", "768", "--image1"])
        .arg(&good)
        .assert()
        .failure()
        .stderr(predicate::str::contains("--image2"));
}

/// A `[pipeline]` file giving every key of `params`.
fn write_explicit_config(path: &Path, params: segmentation::Params) {
    let mut file = toml::Table::new();
    file.insert(
        "pipeline".into(),
        toml::Value::Table(
            toml::Table::try_from(sctl::config::PipelineConfig::from_params(params)).unwrap(),
        ),
    );
    std::fs::write(path, toml::to_string(&file).unwrap()).unwrap();
}

#[test]
fn profile_sets_every_key_the_config_does_not_give() {
    use segmentation::Params;
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches);
    // Labels and summary of `sctl segment` with `args`, but for the summary's
    // last line (the time and memory it took, which vary from run to run).
    let segment = |args: &[&std::ffi::OsStr]| {
        let output = segment_1024x768(&matches)
            .args(["--out", "-"])
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert!(output.status.success(), "{stderr}");
        let (summary, cost) = stderr.trim_end().rsplit_once('\n').unwrap();
        assert!(cost.starts_with("  took "), "{stderr}");
        (
            String::from_utf8(output.stdout).unwrap(),
            summary.to_string(),
        )
    };
    let config = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let explicit = |name: &str, params: Params| {
        let path = dir.path().join(name);
        write_explicit_config(&path, params);
        path
    };
    let flag = std::ffi::OsStr::new("--config");
    // The flag alone: the profile's parameters, which are not the default's.
    assert_ne!(Params::thesis(), Params::default());
    let thesis_file = explicit("thesis_all.toml", Params::thesis());
    let (labels, summary) = segment(&["--profile".as_ref(), "thesis".as_ref()]);
    assert_eq!((labels, summary), segment(&[flag, thesis_file.as_os_str()]));

    // A file's own profile applies; the file's keys override it.
    let thesis_300 = Params::thesis().with(|q| q.sampling.num_samples = 300);
    assert_ne!(thesis_300.focal.method, Params::default().focal.method);
    let on_thesis = config(
        "on_thesis.toml",
        "[pipeline]\nprofile = \"thesis\"\nnum_samples = 300\n",
    );
    let thesis = explicit("thesis.toml", thesis_300);
    let from_file = segment(&[flag, on_thesis.as_os_str()]);
    assert!(from_file.1.contains("of 300 generated"), "{}", from_file.1);
    assert_eq!(from_file, segment(&[flag, thesis.as_os_str()]));

    // --profile replaces the file's profile; the file's keys still override.
    let default_300 = explicit(
        "default_300.toml",
        Params::default().with(|q| q.sampling.num_samples = 300),
    );
    let args = [
        flag,
        on_thesis.as_os_str(),
        "--profile".as_ref(),
        "default".as_ref(),
    ];
    let flagged = segment(&args);
    assert_ne!(flagged, from_file);
    assert_eq!(flagged, segment(&[flag, default_300.as_os_str()]));
}

#[test]
fn the_summary_says_how_many_matches_were_clustered() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    let n = write_matches(&matches).len();
    assert!(n > 100, "{n}");
    let config = dir.path().join("subset.toml");
    std::fs::write(
        &config,
        "[pipeline]\nnum_samples = 300\ncluster_subset = 100\nsubset_extension = \"preference-explained\"\n",
    )
    .unwrap();
    let output = segment_1024x768(&matches)
        .arg("--config")
        .arg(&config)
        .args(["--out", "-"])
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(output.status.success(), "{stderr}");
    let line = format!(
        "clustered 100 matches drawn at random; the other {} joined by preference-explained (cluster_subset)",
        n - 100
    );
    assert!(stderr.contains(&line), "{stderr}");
    assert_eq!(String::from_utf8(output.stdout).unwrap().lines().count(), n);
}

#[test]
fn input_warnings_go_to_stderr_one_line_each_and_absurd_values_fail() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches);
    let params = dir.path().join("params.toml");
    std::fs::write(&params, "[pipeline]\nnum_samples = 300\n").unwrap();
    // The size given as (height, width).
    sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .args(["--width", "768", "--height", "1024", "--config"])
        .arg(&params)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "pair.csv: every point fits an image of width 1024 and height 768 but not \
             image_size = (768, 1024)",
        ));
    let text = std::fs::read_to_string(&matches).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[3] = "1e200,5,6,7,0".into();
    std::fs::write(&matches, lines.join("\n")).unwrap();
    segment_1024x768(&matches)
        .assert()
        .failure()
        .stderr(predicate::str::contains(
        "pair.csv: match row 2, column x1: coordinate 1e200 is not a finite number within ±1e6 px",
    ));
}
