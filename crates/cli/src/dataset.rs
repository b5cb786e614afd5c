//! The scenes an experiment runs on, from its `[dataset]` table.
//!
//! The data root is resolved as the `--data-root` flag, else
//! `SCTL_DATA_ROOT`, else `dataset.data_root`, else `datasets/` in the
//! workspace; AdelaideRMF is read from `<root>/adelaidermf/F`, HOPE-F from
//! `<root>/hopef`, user files relative to the root.

use crate::config::{DatasetConfig, DatasetKind, Split};
use anyhow::{bail, Context, Result};
use datasets::adelaidermf::{self, AdelaideRmf};
use datasets::hopef::{self, HopeF, Selection};
use datasets::synthetic::Preset;
use datasets::{DataRootSources, Scene};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// The default synthetic preset.
pub const DEFAULT_PRESET: &str = "quick";
/// The default synthetic generator seed.
pub const DEFAULT_GENERATOR_SEED: u64 = 1;

/// The data root for `dataset` given the `--data-root` flag.
pub fn data_root(dataset: &DatasetConfig, flag: Option<&Path>) -> PathBuf {
    let sources = DataRootSources {
        flag: flag.map(Path::to_path_buf),
        env: datasets::data_root_env(),
        config: dataset.data_root.clone(),
    };
    datasets::resolve_data_root(&sources, &datasets::workspace_datasets_dir()).path
}

impl From<Split> for hopef::Split {
    fn from(s: Split) -> Self {
        match s {
            Split::Train => hopef::Split::Train,
            Split::Val => hopef::Split::Val,
            Split::Test => hopef::Split::Test,
        }
    }
}

/// Keeps the entries whose name is in `wanted` (all when `None`), in their
/// order; a wanted name that is not there is an error listing the known ones.
fn select_named<T>(
    items: Vec<T>,
    name: impl Fn(&T) -> String,
    wanted: Option<&[String]>,
) -> Result<Vec<T>> {
    let Some(wanted) = wanted else {
        return Ok(items);
    };
    let names: Vec<String> = items.iter().map(&name).collect();
    if let Some(missing) = wanted.iter().find(|w| !names.contains(w)) {
        let mut known = names.join(", ");
        if known.len() > 300 {
            known.truncate(300);
            known.push_str(", …");
        }
        bail!("dataset.scenes: unknown scene `{missing}` (selected scenes: {known})");
    }
    Ok(items
        .into_iter()
        .zip(names)
        .filter(|(_, n)| wanted.contains(n))
        .map(|(item, _)| item)
        .collect())
}

/// True when `index` lies in the inclusive `range` (or there is no range).
fn in_range(range: Option<[u32; 2]>, index: u32) -> bool {
    range.map_or(true, |[a, b]| (a..=b).contains(&index))
}

/// Loads the scenes of `dataset` (with their images when `images`), in the
/// dataset's order, checking each.
pub fn load_scenes(
    dataset: &DatasetConfig,
    data_root_flag: Option<&Path>,
    images: bool,
) -> Result<Vec<Scene>> {
    let root = data_root(dataset, data_root_flag);
    let scenes = match dataset.kind {
        DatasetKind::Adelaidermf => adelaidermf_scenes(dataset, &root, images)?,
        DatasetKind::Hopef => hopef_scenes(dataset, &root, images)?,
        DatasetKind::Synthetic => synthetic_scenes(dataset)?,
        DatasetKind::Csv => csv_scenes(dataset, &root)?,
    };
    if scenes.is_empty() {
        bail!(
            "dataset: the selection holds no scene (kind = \"{}\", data root {})",
            dataset.kind.name(),
            root.display()
        );
    }
    let mut seen = std::collections::HashSet::new();
    for s in &scenes {
        if !seen.insert(s.name.as_str()) {
            bail!(
                "dataset: two scenes are named `{}`; scene names must be unique",
                s.name
            );
        }
    }
    Ok(scenes)
}

/// The scenes of the synthetic `preset`, every category, indices
/// `first..=last`, generator seed 1: those `sctl run` runs with
/// `kind = "synthetic"`, that preset and `index_range = [first, last]` (the
/// lab examples' validation scenes, so that their figures and a run's
/// agree).
pub fn preset_scenes(preset: Preset, first: u32, last: u32) -> Result<Vec<Scene>> {
    synthetic_scenes(&DatasetConfig {
        kind: DatasetKind::Synthetic,
        data_root: None,
        scenes: None,
        split: None,
        categories: None,
        index_range: Some([first, last]),
        preset: Some(preset.name().to_string()),
        generator_seed: None,
        files: None,
        width: None,
        height: None,
    })
}

/// Refuses an `index_range` reaching past the AdelaideRMF scenes (indices
/// `0..count`): clamping it would run fewer scenes than asked without a word.
fn check_adelaidermf_range(range: Option<[u32; 2]>, count: usize) -> Result<()> {
    match range {
        Some([first, last]) if last as usize >= count => bail!(
            "dataset.index_range = [{first}, {last}]: AdelaideRMF has {count} scenes, \
             indices 0 to {}",
            count - 1
        ),
        _ => Ok(()),
    }
}

/// The selected AdelaideRMF sequences.
fn adelaidermf_scenes(dataset: &DatasetConfig, root: &Path, images: bool) -> Result<Vec<Scene>> {
    let wanted = dataset.scenes.as_deref();
    let data = AdelaideRmf::open(root.join("adelaidermf").join("F"))?;
    check_adelaidermf_range(dataset.index_range, data.scene_names().len())?;
    let names: Vec<(u32, &str)> = data
        .scene_names()
        .iter()
        .enumerate()
        .filter(|(i, _)| in_range(dataset.index_range, *i as u32))
        .map(|(i, n)| (i as u32, *n))
        .collect();
    let names = select_named(names, |(_, n)| n.to_string(), wanted)?;
    let options = adelaidermf::LoadOptions { images };
    names
        .par_iter()
        .map(|(_, n)| data.load_with(n, options).map_err(anyhow::Error::from))
        .collect::<Result<Vec<_>>>()
}

/// The selected HOPE-F scenes.
fn hopef_scenes(dataset: &DatasetConfig, root: &Path, images: bool) -> Result<Vec<Scene>> {
    let wanted = dataset.scenes.as_deref();
    let data = HopeF::open(root.join("hopef"))?;
    let selection = match dataset.split {
        Some(split) => Selection::Split(split.into()),
        None => Selection::All,
    };
    let categories = dataset.categories.clone().unwrap_or_default();
    let refs: Vec<hopef::SceneRef> = data
        .select(&categories, &selection)?
        .into_iter()
        .filter(|r| in_range(dataset.index_range, r.index))
        .collect();
    let refs = select_named(refs, hopef::SceneRef::name, wanted)?;
    let options = hopef::LoadOptions { images };
    refs.par_iter()
        .map(|r| data.load(r, options).map_err(anyhow::Error::from))
        .collect::<Result<Vec<_>>>()
}

/// The selected scenes of the synthetic generator.
fn synthetic_scenes(dataset: &DatasetConfig) -> Result<Vec<Scene>> {
    let wanted = dataset.scenes.as_deref();
    let preset_name = dataset.preset.as_deref().unwrap_or(DEFAULT_PRESET);
    let preset = Preset::from_name(preset_name).with_context(|| {
        let known: Vec<&str> = Preset::ALL.iter().map(|p| p.name()).collect();
        format!(
            "dataset.preset: unknown preset `{preset_name}` (known: {})",
            known.join(", ")
        )
    })?;
    let seed = dataset.generator_seed.unwrap_or(DEFAULT_GENERATOR_SEED);
    let mut refs: Vec<(u32, u32)> = Vec::new();
    for category in preset.categories() {
        if dataset
            .categories
            .as_ref()
            .is_some_and(|c| !c.contains(&category))
        {
            continue;
        }
        let split = dataset.split.map(hopef::Split::from);
        refs.extend(
            preset
                .indices()
                .filter(|&i| in_range(dataset.index_range, i))
                .filter(|i| split.map_or(true, |s| s.indices().contains(i)))
                .map(|i| (category, i)),
        );
    }
    let refs = select_named(refs, |&(c, i)| hopef::scene_name(c, i), wanted)?;
    let params = preset.params();
    refs.par_iter()
        .map(|&(c, i)| {
            params
                .generate_scene(seed, c, i)
                .map(|s| s.scene)
                .map_err(anyhow::Error::from)
        })
        .collect::<Result<Vec<_>>>()
}

/// The selected user match files.
fn csv_scenes(dataset: &DatasetConfig, root: &Path) -> Result<Vec<Scene>> {
    let wanted = dataset.scenes.as_deref();
    let files = dataset.files.clone().unwrap_or_default();
    let size = dataset.width.zip(dataset.height);
    let scenes = files
        .iter()
        .map(|f| {
            let path = if f.is_absolute() {
                f.clone()
            } else {
                root.join(f)
            };
            load_match_file(&path, size)
        })
        .collect::<Result<Vec<_>>>()?;
    select_named(scenes, |s| s.name.clone(), wanted)
}

/// Loads a user match file: `.txt` as AdelaideRMF-style `x1 y1 x2 y2
/// [label]` lines, anything else as CSV with a header.
pub fn load_match_file(path: &Path, image_size: Option<(u32, u32)>) -> Result<Scene> {
    let is_txt = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("txt"));
    Ok(if is_txt {
        datasets::user::load_matches_txt(path, image_size)?
    } else {
        datasets::user::load_csv(path, image_size)?
    })
}

#[cfg(test)]
mod range_tests {
    #[test]
    fn adelaidermf_ranges_past_the_scenes_are_refused() {
        assert!(super::check_adelaidermf_range(Some([0, 18]), 19).is_ok());
        assert!(super::check_adelaidermf_range(None, 19).is_ok());
        let err = super::check_adelaidermf_range(Some([17, 50]), 19).unwrap_err();
        assert_eq!(
            err.to_string(),
            "dataset.index_range = [17, 50]: AdelaideRMF has 19 scenes, indices 0 to 18"
        );
    }
}
