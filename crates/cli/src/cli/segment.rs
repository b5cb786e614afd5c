//! `sctl segment --matches FILE`: segments one pair of the user's own
//! matches and writes one label per input row (−1 = outlier), optionally
//! with a figure of the clusters over the two images. The samples are drawn
//! with the config's seed as it is (not mixed with the file name), so the
//! labels are those of the library and the Python package on the same input.

use super::print_out;
use crate::config::PipelineConfig;
use crate::dataset::load_match_file;
use crate::evaluate::{ground_truth_models, scene_result};
use crate::output::{write_atomic, SceneResult};
use crate::pipeline::{matches, Segmentation};
use crate::plots::{clusters_over_images, PlotFormat};
use anyhow::{bail, Context, Result};
use datasets::Scene;
use image::{ImageFormat, ImageReader, RgbImage};
use segmentation::{FocalVerdict, MinimalSolver, Params, Profile, StageTimings};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Options of `sctl segment`.
#[derive(clap::Args)]
pub struct Args {
    /// Matches: CSV with header `x1,y1,x2,y2[,label]`, or `.txt` lines
    /// `x1 y1 x2 y2 [label]` (pixels; label 0 = outlier, used for metrics).
    #[arg(long, value_name = "FILE")]
    pub matches: PathBuf,
    /// Image width in pixels [default: from the sidecar FILE.toml].
    #[arg(long, value_name = "W", requires = "height", allow_hyphen_values = true, value_parser = parse_pixels)]
    pub width: Option<u32>,
    /// Image height in pixels [default: from the sidecar FILE.toml].
    #[arg(long, value_name = "H", requires = "width", allow_hyphen_values = true, value_parser = parse_pixels)]
    pub height: Option<u32>,
    /// Focal length prior in pixels [default: the sidecar's `focal_prior`,
    /// else max(W, H)]. The five-point default solves the essential matrices
    /// at this focal; semical uses it as the prior of the focal-length KDE
    /// (its plausibility band and the fallback of failed solves). The prior
    /// need not be right: with the five-point hypotheses of the previous
    /// default, 0.5-4 x the true focal cost at most 1.2 points of ME
    /// (HOPE-F-faithful validation scenes 11.2-12.4 %, AdelaideRMF
    /// 3.7-4.3 %), 0.25 x about 1.5 points (results/focal_prior/); the
    /// default's semi-calibrated models at 0.5 x and 2 x max(W, H) move the
    /// validation ME by less than 0.2 points (results/notes/selection.md).
    #[arg(long, value_name = "PX", allow_hyphen_values = true, value_parser = parse_focal)]
    pub focal: Option<f64>,
    /// Parameters: a TOML file with a `[pipeline]` table (an experiment file
    /// works too); the keys it does not give take the values of its
    /// `profile` key, or of --profile when given [default: the parameters of
    /// --profile; those of `default` are five-point hypotheses at the focal
    /// prior, no focal filter, at most 1000 matches clustered, the motions
    /// chosen by their a-contrario significance (NFA < 1)].
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Named parameter set: default (one configuration for 8 to 50 000
    /// matches) | thesis (the thesis text's Algorithm 1). The `fast` and
    /// `large` profiles of earlier versions were folded into the default.
    /// With --config it replaces the file's
    /// `profile` key; the keys the file gives still override it [default:
    /// the file's `profile`, else default].
    #[arg(long, value_name = "NAME", value_parser = parse_profile)]
    pub profile: Option<Profile>,
    /// Write the labels, one per input row (-1 = outlier), to FILE, or to
    /// standard output with `--out -` (the summary then goes to stderr)
    /// [default: no labels, the summary alone on standard output].
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Worker threads, 1 to 1024 [default: every core].
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = super::parse_threads)]
    pub threads: Option<usize>,
    /// Draw the clusters over both images (outliers as grey crosses) into
    /// this file: `.png` or `.svg`. Without --image1/--image2 the points are
    /// drawn on blank canvases of the image size. Written through a temporary
    /// file: a failure leaves no partial figure.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// First image (PNG or JPEG, W x H pixels), drawn under the clusters of --plot.
    #[arg(long, value_name = "FILE", requires_all = ["image2", "plot"])]
    pub image1: Option<PathBuf>,
    /// Second image (PNG or JPEG, W x H pixels), drawn under the clusters of --plot.
    #[arg(long, value_name = "FILE", requires_all = ["image1", "plot"])]
    pub image2: Option<PathBuf>,
}

/// The profile called `name`; an unknown name is an error listing the
/// profiles (or saying what became of a retired one).
fn parse_profile(name: &str) -> Result<Profile, String> {
    Profile::from_name(name).ok_or_else(|| Profile::unknown(name))
}

/// Parses `--width`/`--height`: a whole number of pixels, 1 to
/// [`MAX_IMAGE_SIDE`]; anything else (negative values included) is an
/// error naming the value.
fn parse_pixels(text: &str) -> Result<u32, String> {
    match text.trim().parse::<i64>() {
        Ok(n) if (1..=i64::from(MAX_IMAGE_SIDE)).contains(&n) => Ok(n as u32),
        Ok(n) => Err(format!("{n} pixels: give 1 to {MAX_IMAGE_SIDE}")),
        Err(_) => Err(format!(
            "`{}` is not a whole number of pixels",
            crate::output::echo(text)
        )),
    }
}

/// The largest image side `--width`/`--height` accept, in pixels: ten times
/// the largest sensors made (about 20 000 px), far below u32 overflow in the
/// pixel arithmetic of the figures.
const MAX_IMAGE_SIDE: u32 = 200_000;

/// Parses `--focal`: a finite focal length in pixels, > 0.
fn parse_focal(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(f) if f.is_finite() && f > 0.0 => Ok(f),
        Ok(f) => Err(format!("{f}: give a focal length in pixels, > 0")),
        Err(_) => Err(format!(
            "`{}` is not a number of pixels",
            crate::output::echo(text)
        )),
    }
}

/// Reads a PNG or JPEG image as RGB and checks that it is `size` pixels;
/// any other format, an unreadable file or another size is an error naming
/// the file.
fn load_image(path: &Path, size: (u32, u32)) -> Result<RgbImage> {
    let reader = ImageReader::open(path)
        .with_context(|| format!("{}: cannot open the image", path.display()))?
        .with_guessed_format()
        .with_context(|| format!("{}: cannot read the image", path.display()))?;
    match reader.format() {
        Some(ImageFormat::Png | ImageFormat::Jpeg) => {}
        Some(other) => bail!(
            "{}: {} images are not supported: give a PNG or JPEG image",
            path.display(),
            format!("{other:?}").to_uppercase()
        ),
        None => bail!("{}: neither a PNG nor a JPEG image", path.display()),
    }
    let image = reader
        .decode()
        .with_context(|| format!("{}: cannot decode the image", path.display()))?
        .to_rgb8();
    if image.dimensions() != size {
        bail!(
            "{}: the image is {} x {} pixels but the matches are for {} x {} (--width/--height)",
            path.display(),
            image.width(),
            image.height(),
            size.0,
            size.1
        );
    }
    Ok(image)
}

/// Segments the matches, writes the labels and prints a summary.
pub fn run(args: Args) -> Result<()> {
    let config = match &args.config {
        Some(path) => PipelineConfig::load_with_profile(path, args.profile)?,
        None => PipelineConfig::of_profile(args.profile.unwrap_or_default()),
    };
    if let Some(plot) = &args.plot {
        PlotFormat::from_path(plot)?;
    }
    let scene = load_match_file(&args.matches, args.width.zip(args.height))?;
    let focal_prior = match args.focal {
        Some(f) => f,
        None => sidecar_focal_prior(&args.matches)?.unwrap_or_else(|| scene.focal_prior()),
    };
    // The library's input check, before any work: a refused coordinate is
    // an error naming the file; its warnings are printed at once.
    let input_warnings = segmentation::check_matches(&matches(&scene))
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.matches.display()))?;
    for warning in &input_warnings {
        eprintln!("warning: {}: {warning}", args.matches.display());
    }
    let images = match (&args.image1, &args.image2) {
        (Some(a), Some(b)) => Some((
            load_image(a, scene.image_size)?,
            load_image(b, scene.image_size)?,
        )),
        _ => None,
    };
    let segmentation = crate::experiment::thread_pool(args.threads.unwrap_or(0))?
        .install(|| {
            let input = matches(&scene).with_focal_prior(focal_prior);
            segmentation::segment(&input, &config.params())
        })
        // The library's message names its cause already: not its chain too.
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.matches.display()))?;
    // segmentation.warnings repeats the input warnings printed above.
    let result = scene_result(&scene, &segmentation, &ground_truth_models(&scene))?;

    let mut summary = summary_text(
        &scene,
        &segmentation,
        &result,
        &config.params(),
        focal_prior,
    );
    if let Some(plot) = &args.plot {
        draw_plot(&scene, &segmentation, &result, images.as_ref(), plot)?;
        let _ = write!(summary, "\n  clusters drawn in {}", plot.display());
    }
    write_outputs(args.out.as_deref(), &segmentation.labels, &summary)
}

/// The clusters over both images (or blank canvases) into `plot`.
fn draw_plot(
    scene: &Scene,
    segmentation: &Segmentation,
    result: &SceneResult,
    images: Option<&(RgbImage, RgbImage)>,
    plot: &Path,
) -> Result<()> {
    let title = format!(
        "{}: {} motion(s), {} outliers",
        scene.name, result.motions, result.outliers
    );
    clusters_over_images(
        scene.image_size,
        images.map(|(a, b)| (a, b)),
        &scene.points1,
        &scene.points2,
        &segmentation.labels,
        &title,
        plot,
    )?;
    Ok(())
}

/// The labels, one per line: to `out` through a temporary file and a
/// rename (then the summary to stdout), to stdout for `-` (then the
/// summary to stderr), or nowhere (the summary alone to stdout).
fn write_outputs(out: Option<&Path>, labels: &[i32], summary: &str) -> Result<()> {
    let text: String = labels.iter().fold(String::new(), |mut s, l| {
        let _ = writeln!(s, "{l}");
        s
    });
    match out {
        Some(path) if path == Path::new("-") => {
            print_out(&text)?;
            eprintln!("{summary}");
            Ok(())
        }
        Some(path) => {
            write_atomic(path, &text)?;
            print_out(&format!(
                "{summary}\n  labels written to {}\n",
                path.display()
            ))
        }
        None => print_out(&format!("{summary}\n")),
    }
}

/// The summary printed after a segmentation: what was found, f_peak, the
/// metrics against the file's labels and any note.
fn summary_text(
    scene: &Scene,
    segmentation: &Segmentation,
    result: &SceneResult,
    params: &Params,
    focal_prior: f64,
) -> String {
    let mut summary = format!(
        "{}: {} matches, {} motion(s) found, {} outliers; hypotheses kept {} of {} generated ({} refined)",
        scene.name,
        scene.len(),
        result.motions,
        result.outliers,
        result.hypotheses_kept,
        result.hypotheses_generated,
        result.hypotheses_refined,
    );
    let clustered = params.clustered_matches(scene.len());
    if clustered < scene.len() {
        let _ = write!(
            summary,
            "\n  clustered {clustered} matches drawn at random; the other {} joined by {} (cluster_subset)",
            scene.len() - clustered,
            crate::sweep::format_value(
                &toml::Value::try_from(params.selection.subset_extension).expect("a switch serializes")
            ),
        );
    }
    for c in &segmentation.clusters {
        let _ = write!(summary, "\n  motion {}: {} matches", c.label, c.size);
    }
    summary.push_str(&focal_line(segmentation, result, params, focal_prior));
    if let (Some(me), Some(me_all), Some(fnr), Some(pur), Some(ari), Some(nmi)) = (
        result.me,
        result.me_all,
        result.fnr,
        result.pur,
        result.ari,
        result.nmi,
    ) {
        let _ = write!(
            summary,
            "\n  against the file's labels: ME {:.2} % (all points: {:.2} %), FNR {:.2} %, PUR {:.2} %, ARI {:.4}, NMI {:.4}",
            100.0 * me,
            100.0 * me_all,
            100.0 * fnr,
            100.0 * pur,
            ari,
            nmi
        );
    }
    if result.status != "ok" {
        let _ = write!(summary, "\n  note: {}", result.status);
    }
    summary.push_str(&cost_line(&segmentation.timings));
    summary
}

/// The summary's line on cost: the wall time of each stage and the
/// process's peak resident memory.
fn cost_line(t: &StageTimings) -> String {
    format!(
        "\n  took {:.2} s (sampling {:.2}, refinement {:.2}, focals {:.2}, consensus {:.2}, \
         preferences {:.2}, clustering {:.2}, cluster fits {:.2}){}",
        t.total,
        t.sampling,
        t.refine,
        t.focal,
        t.consensus,
        t.preferences,
        t.clustering,
        t.cluster_fit,
        super::peak_memory_text()
    )
}

/// The summary's line on the focal: f_peak and its verdict for semical, the
/// focal the five-point hypotheses were computed at otherwise. An
/// implausible or absent consensus is said in one line.
fn focal_line(
    segmentation: &Segmentation,
    result: &SceneResult,
    params: &Params,
    prior: f64,
) -> String {
    let [low, high] = segmentation::PLAUSIBLE_FOCAL_RANGE;
    match (result.f_peak, segmentation.focal_verdict) {
        (Some(f), FocalVerdict::Implausible) => format!(
            "\n  f_peak {f:.1} px is implausible (outside {low}-{high} x the focal prior {prior:.0} px): \
             the focal filter used it all the same"
        ),
        (Some(f), _) => format!("\n  f_peak {f:.1} px (focal prior {prior:.0} px)"),
        (None, FocalVerdict::NoConsensus) => {
            "\n  no focal consensus: no hypothesis passed the local test, every hypothesis was kept"
                .to_string()
        }
        (None, _) if params.sampling.minimal_solver == MinimalSolver::FivePoint => format!(
            "\n  no focal filter (baseline); five-point hypotheses at the focal prior {prior:.0} px"
        ),
        (None, _) => "\n  f_peak: none (baseline)".to_string(),
    }
}

/// The sidecar's `focal_prior` (`FILE.toml` beside the match file), when
/// the sidecar exists and gives one.
fn sidecar_focal_prior(matches: &std::path::Path) -> Result<Option<f64>> {
    let path = datasets::user::sidecar_path(matches);
    if !path.is_file() {
        return Ok(None);
    }
    Ok(datasets::user::read_sidecar(&path)?.focal_prior)
}
