//! `sctl inspect`: one JSON line per scene of a dataset, with its size and
//! ground-truth summary; a scene that fails to load is reported on stderr
//! (naming the file) and makes the command exit non-zero.

use anyhow::{bail, Context};
use datasets::adelaidermf::{self, AdelaideRmf};
use datasets::hopef::{self, HopeF, Selection, Split};
use datasets::{
    data_root_env, resolve_data_root, workspace_datasets_dir, DataRoot, DataRootSources, Scene,
};
use std::io::Write;
use std::path::PathBuf;

/// Which dataset to read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DatasetKind {
    /// AdelaideRMF's 19 fundamental-matrix scenes, from `<data root>/adelaidermf/F`.
    Adelaidermf,
    /// HOPE-F scene folders, from `<data root>/hopef`.
    Hopef,
}

/// Options of `sctl inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The dataset.
    #[arg(long, value_enum)]
    pub dataset: DatasetKind,
    /// Data root (default: $SCTL_DATA_ROOT, else datasets/ in the workspace).
    #[arg(long, value_name = "DIR")]
    pub data_root: Option<PathBuf>,
    /// Read the dataset from this directory instead of its place under the
    /// data root (e.g. the output of `sctl synth` with `--dataset hopef`).
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
    /// Only this scene: an AdelaideRMF name (`biscuit`) or a HOPE-F folder (`2/0901`).
    #[arg(long, value_name = "NAME")]
    pub scene: Option<String>,
    /// HOPE-F only: the split to list (train, val, test); default all folders.
    #[arg(long)]
    pub split: Option<Split>,
}

/// The JSON summary of one scene, printed as one line.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SceneSummary {
    /// Scene name.
    pub name: String,
    /// Number of correspondences N.
    pub n: usize,
    /// Distinct labels > 0.
    pub motions: usize,
    /// Labels equal to 0.
    pub outliers: usize,
    /// Image width W in pixels.
    pub width: u32,
    /// Image height H in pixels.
    pub height: u32,
    /// Whether the image pair was loaded.
    pub has_images: bool,
    /// Ground-truth focal length in pixels (null when unknown).
    pub true_focal: Option<f64>,
}

impl SceneSummary {
    /// The summary of a loaded scene.
    pub fn of(scene: &Scene) -> Self {
        Self {
            name: scene.name.clone(),
            n: scene.len(),
            motions: scene.num_motions(),
            outliers: scene.num_outliers(),
            width: scene.image_size.0,
            height: scene.image_size.1,
            has_images: scene.images.is_some(),
            true_focal: scene.true_focal,
        }
    }
}

/// One scene, loaded when called.
type Loader = Box<dyn Fn() -> Result<Scene, datasets::DatasetError>>;

/// The loaders of the AdelaideRMF scenes asked for.
fn adelaidermf_loaders(args: &Args, root: &DataRoot) -> anyhow::Result<Vec<Loader>> {
    if args.split.is_some() {
        bail!("--split applies to HOPE-F only");
    }
    let dir = args.dir.clone().unwrap_or_else(|| root.adelaidermf_dir());
    let data = AdelaideRmf::open(&dir)?;
    let names: Vec<String> = match &args.scene {
        Some(name) => {
            data.scene_path(name)?;
            vec![name.clone()]
        }
        None => data.scene_names().iter().map(|s| s.to_string()).collect(),
    };
    Ok(names
        .into_iter()
        .map(|name| {
            let data = data.clone();
            Box::new(move || data.load_with(&name, adelaidermf::LoadOptions::default())) as Loader
        })
        .collect())
}

/// The loaders of the HOPE-F scenes asked for.
fn hopef_loaders(args: &Args, root: &DataRoot) -> anyhow::Result<Vec<Loader>> {
    let dir = args.dir.clone().unwrap_or_else(|| root.hopef_dir());
    let data = HopeF::open(&dir)?;
    let refs = match &args.scene {
        Some(name) => vec![data.find(name)?],
        None => {
            let selection = args.split.map_or(Selection::All, Selection::Split);
            data.select(&[], &selection)?
        }
    };
    if refs.is_empty() {
        bail!(
            "no HOPE-F scene folders (<k>/<NNNN>) under {}",
            dir.display()
        );
    }
    Ok(refs
        .into_iter()
        .map(|r| {
            let data = data.clone();
            Box::new(move || data.load(&r, hopef::LoadOptions::default())) as Loader
        })
        .collect())
}

/// Runs `sctl inspect`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let root = resolve_data_root(
        &DataRootSources {
            flag: args.data_root.clone(),
            env: data_root_env(),
            config: None,
        },
        &workspace_datasets_dir(),
    );
    let loaders = match args.dataset {
        DatasetKind::Adelaidermf => adelaidermf_loaders(&args, &root)?,
        DatasetKind::Hopef => hopef_loaders(&args, &root)?,
    };

    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let total = loaders.len();
    let mut failed = 0;
    for load in loaders {
        match load() {
            Ok(scene) => {
                let line = serde_json::to_string(&SceneSummary::of(&scene))?;
                match writeln!(out, "{line}") {
                    // The reader went away (`sctl inspect … | head`): stop quietly.
                    Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return Ok(()),
                    other => other.context("writing to stdout")?,
                }
            }
            Err(err) => {
                failed += 1;
                eprintln!("error: {err}");
            }
        }
    }
    match out.flush() {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return Ok(()),
        other => other.context("writing to stdout")?,
    }
    if failed > 0 {
        bail!("{failed} of {total} scenes failed to load");
    }
    Ok(())
}
