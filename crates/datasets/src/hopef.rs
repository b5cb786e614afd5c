//! HOPE-F (Kluger & Rosenhahn, AAAI 2024): 4 × 1000 rendered scenes of 1–4
//! independently moving objects (docs/method.md, "Datasets").
//!
//! On-disk layout, under the dataset root:
//!
//! ```text
//! <root>/<k>/<NNNN>/features_and_ground_truth.npz   points1, points2 (N x 3), labels (N, int64), F (k x 3 x 3), ratios (N)
//! <root>/<k>/<NNNN>/camera_parameters.npz           K (3 x 3), R, t
//! <root>/<k>/<NNNN>/render0.png, render1.png         only in the full download
//! ```
//!
//! `k` = 1..4 is the number of objects; `NNNN` = 0000–0999, split into
//! train 0000–0799, validation 0800–0899 and test 0900–0999 per category.
//!
//! Decisions this loader makes:
//! * Points are homogeneous N × 3 rows; each is divided by its third
//!   coordinate (1 in HOPE-F, so the division is exact and the result is the
//!   first two columns). A third coordinate of 0 or non-finite is an error.
//!   N × 2 arrays are accepted as plain pixels.
//! * Principal point `(K[0,2], K[1,2])`, true focal `K[0,0]` (docs/method.md,
//!   "Input").
//! * Image size: that of `render0.png` when present; else the optional
//!   `image_size` array (W, H) of `camera_parameters.npz` (written by
//!   [`crate::synthetic::write_hopef_layout`], absent in HOPE-F); else
//!   [`DEFAULT_IMAGE_SIZE`], HOPE-F's render size.
//! * `F` may be k × 3 × 3 or a single 3 × 3; `F[j]` belongs to label j + 1.
//! * `ratios` (SIFT ratio-test values) is not read.

use crate::npz::{NpyArray, NpyData, NpzArchive};
use crate::{DatasetError, Scene};
use nalgebra::Matrix3;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Feature and ground-truth archive of a scene folder.
pub const FEATURES_FILE: &str = "features_and_ground_truth.npz";
/// Camera archive of a scene folder.
pub const CAMERA_FILE: &str = "camera_parameters.npz";
/// First rendered image (full download only).
pub const RENDER0_FILE: &str = "render0.png";
/// Second rendered image (full download only).
pub const RENDER1_FILE: &str = "render1.png";
/// Image size `(W, H)` assumed without renders or an `image_size` array:
/// HOPE-F renders at 1024 × 1024 (Blender resolution in the dataset's
/// `blender_render.py`).
pub const DEFAULT_IMAGE_SIZE: (u32, u32) = (1024, 1024);
/// The object-count categories of HOPE-F.
pub const CATEGORIES: RangeInclusive<u32> = 1..=4;

/// A split of the scene indices of each category.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Split {
    /// 0000–0799.
    Train,
    /// 0800–0899.
    Val,
    /// 0900–0999 (the 400 scenes the thesis evaluates).
    Test,
}

impl Split {
    /// The folder indices of the split.
    ///
    /// ```
    /// use datasets::hopef::Split;
    /// assert_eq!(Split::Test.indices(), 900..=999);
    /// ```
    pub fn indices(self) -> RangeInclusive<u32> {
        match self {
            Split::Train => 0..=799,
            Split::Val => 800..=899,
            Split::Test => 900..=999,
        }
    }
}

impl FromStr for Split {
    type Err = String;

    /// `train`, `val` (or `validation`), `test`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "train" => Ok(Split::Train),
            "val" | "validation" => Ok(Split::Val),
            "test" => Ok(Split::Test),
            other => Err(format!("unknown split `{other}` (train, val, test)")),
        }
    }
}

/// Which scene folders of each category to take.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Selection {
    /// Every folder present.
    All,
    /// The folders of a split.
    Split(Split),
    /// Folders whose index lies in the range.
    Indices(RangeInclusive<u32>),
}

impl Selection {
    fn contains(&self, index: u32) -> bool {
        match self {
            Selection::All => true,
            Selection::Split(split) => split.indices().contains(&index),
            Selection::Indices(range) => range.contains(&index),
        }
    }
}

/// A scene folder: `<root>/<category>/<index as 4 digits>`.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct SceneRef {
    /// Number of objects (the parent folder name).
    pub category: u32,
    /// Scene index (the folder name).
    pub index: u32,
    /// The folder.
    pub dir: PathBuf,
}

impl SceneRef {
    /// The scene name, `<category>/<NNNN>`.
    pub fn name(&self) -> String {
        scene_name(self.category, self.index)
    }
}

/// The name of a HOPE-F scene: `<category>/<index as 4 digits>`.
///
/// ```
/// assert_eq!(datasets::hopef::scene_name(3, 907), "3/0907");
/// ```
pub fn scene_name(category: u32, index: u32) -> String {
    format!("{category}/{index:04}")
}

pub use crate::scene::LoadOptions;

/// A HOPE-F dataset root (`<data root>/hopef`, or any directory in the same
/// layout, such as the output of [`crate::synthetic::write_hopef_layout`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HopeF {
    root: PathBuf,
}

impl HopeF {
    /// Opens the dataset root; [`DatasetError::DatasetMissing`] (with where
    /// to get it) when it is not a directory.
    pub fn open(root: impl AsRef<Path>) -> Result<Self, DatasetError> {
        let root = root.as_ref();
        if !root.is_dir() {
            return Err(DatasetError::DatasetMissing {
                what: "HOPE-F",
                path: root.to_path_buf(),
            });
        }
        Ok(Self {
            root: root.to_path_buf(),
        })
    }

    /// The dataset root.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The scene folders of the given categories (all present categories when
    /// `categories` is empty) that match `selection`, sorted by category then
    /// index. Folders are found on disk: names that are not numbers are
    /// ignored, missing ones are simply absent.
    ///
    /// ```
    /// use datasets::hopef::{HopeF, Selection, Split};
    /// # let dir = tempfile::tempdir().unwrap();
    /// # for (k, i) in [(1, 5), (1, 850), (2, 950), (2, 999)] {
    /// #     std::fs::create_dir_all(dir.path().join(k.to_string()).join(format!("{i:04}"))).unwrap();
    /// # }
    /// let data = HopeF::open(dir.path())?;
    /// let test: Vec<String> = data.select(&[], &Selection::Split(Split::Test))?
    ///     .iter().map(|s| s.name()).collect();
    /// assert_eq!(test, ["2/0950", "2/0999"]);
    /// assert_eq!(data.select(&[1], &Selection::All)?.len(), 2);
    /// # Ok::<(), datasets::DatasetError>(())
    /// ```
    pub fn select(
        &self,
        categories: &[u32],
        selection: &Selection,
    ) -> Result<Vec<SceneRef>, DatasetError> {
        let categories = if categories.is_empty() {
            self.categories()?
        } else {
            categories.to_vec()
        };
        let mut out = Vec::new();
        for category in categories {
            let dir = self.root.join(category.to_string());
            if !dir.is_dir() {
                continue;
            }
            for index in numbered_subdirs(&dir)? {
                if selection.contains(index) {
                    out.push(SceneRef {
                        category,
                        index,
                        dir: dir.join(format!("{index:04}")),
                    });
                }
            }
        }
        out.sort();
        Ok(out)
    }

    /// The category folders present (numeric names), ascending.
    pub fn categories(&self) -> Result<Vec<u32>, DatasetError> {
        numbered_subdirs(&self.root)
    }

    /// The scene called `<category>/<NNNN>`;
    /// [`DatasetError::UnknownScene`] when no such folder exists.
    pub fn find(&self, name: &str) -> Result<SceneRef, DatasetError> {
        let unknown = || DatasetError::UnknownScene {
            dataset: "HOPE-F",
            name: name.to_string(),
            known: Vec::new(),
        };
        let (category, index) = name.split_once('/').ok_or_else(unknown)?;
        let category: u32 = category.parse().map_err(|_| unknown())?;
        let index: u32 = index.parse().map_err(|_| unknown())?;
        let dir = self
            .root
            .join(category.to_string())
            .join(format!("{index:04}"));
        if !dir.is_dir() {
            return Err(unknown());
        }
        Ok(SceneRef {
            category,
            index,
            dir,
        })
    }

    /// Loads one scene folder.
    pub fn load(&self, scene: &SceneRef, options: LoadOptions) -> Result<Scene, DatasetError> {
        load_scene_named(&scene.dir, &scene.name(), options)
    }
}

/// Sub-directories of `dir` whose names are decimal numbers, as numbers,
/// ascending.
fn numbered_subdirs(dir: &Path) -> Result<Vec<u32>, DatasetError> {
    let entries = std::fs::read_dir(dir).map_err(|e| DatasetError::io(dir, e))?;
    let mut out = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| DatasetError::io(dir, e))?;
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if name.is_empty() || !name.bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        if let (Ok(n), true) = (name.parse::<u32>(), entry.path().is_dir()) {
            out.push(n);
        }
    }
    out.sort_unstable();
    Ok(out)
}

/// Loads a scene folder, images included when present. The scene is named
/// `<parent folder>/<folder>` (e.g. `2/0901`).
///
/// ```
/// use datasets::synthetic::{generate_hopef_scene, write_hopef_layout, SyntheticParams};
/// let root = tempfile::tempdir().unwrap();
/// let written = generate_hopef_scene(&SyntheticParams::default(), 5, 2, 901)?;
/// write_hopef_layout(root.path(), std::slice::from_ref(&written))?;
/// let scene = datasets::hopef::load_scene(root.path().join("2/0901"))?;
/// assert_eq!(scene.name, "2/0901");
/// assert_eq!(scene.num_motions(), 2);
/// assert_eq!(scene, written.scene);
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn load_scene(dir: impl AsRef<Path>) -> Result<Scene, DatasetError> {
    load_scene_with(dir, LoadOptions::default())
}

/// Loads a scene folder.
pub fn load_scene_with(dir: impl AsRef<Path>, options: LoadOptions) -> Result<Scene, DatasetError> {
    let dir = dir.as_ref();
    let name = default_name(dir);
    load_scene_named(dir, &name, options)
}

fn default_name(dir: &Path) -> String {
    let last = |p: Option<&Path>| {
        p.and_then(Path::file_name)
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    format!("{}/{}", last(dir.parent()), last(Some(dir)))
}

fn read(path: &Path) -> Result<Vec<u8>, DatasetError> {
    std::fs::read(path).map_err(|e| DatasetError::io(path, e))
}

fn load_scene_named(dir: &Path, name: &str, options: LoadOptions) -> Result<Scene, DatasetError> {
    let features_path = dir.join(FEATURES_FILE);
    let camera_path = dir.join(CAMERA_FILE);
    let features = parse_features(&read(&features_path)?, &features_path)?;
    let camera = parse_camera(&read(&camera_path)?, &camera_path)?;

    let render0 = dir.join(RENDER0_FILE);
    let render1 = dir.join(RENDER1_FILE);
    let mut images = None;
    let image_size = if render0.is_file() {
        if options.images && render1.is_file() {
            let a = read_png(&render0)?;
            let b = read_png(&render1)?;
            let size = a.dimensions();
            images = Some((a, b));
            size
        } else {
            image::image_dimensions(&render0).map_err(|source| DatasetError::Image {
                path: render0.clone(),
                source,
            })?
        }
    } else {
        camera.image_size.unwrap_or(DEFAULT_IMAGE_SIZE)
    };

    let scene = Scene {
        name: name.to_string(),
        points1: features.points1,
        points2: features.points2,
        labels: Some(features.labels),
        image_size,
        principal_point: camera.principal_point,
        true_focal: Some(camera.focal),
        gt_fundamentals: features.fundamentals,
        images,
    };
    scene.validate().map_err(|e| e.in_file(&features_path))?;
    Ok(scene)
}

fn read_png(path: &Path) -> Result<image::RgbImage, DatasetError> {
    image::open(path)
        .map(|img| img.to_rgb8())
        .map_err(|source| DatasetError::Image {
            path: path.to_path_buf(),
            source,
        })
}

/// The contents of `features_and_ground_truth.npz` that a scene needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Features {
    /// Image-1 points, pixels.
    pub points1: Vec<[f64; 2]>,
    /// Image-2 points, pixels.
    pub points2: Vec<[f64; 2]>,
    /// Labels, 0 = outlier.
    pub labels: Vec<i32>,
    /// Ground-truth F per object.
    pub fundamentals: Vec<Matrix3<f64>>,
}

/// The contents of `camera_parameters.npz` that a scene needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// `(K[0,2], K[1,2])`.
    pub principal_point: [f64; 2],
    /// `K[0,0]`.
    pub focal: f64,
    /// The optional `image_size` array `(W, H)`.
    pub image_size: Option<(u32, u32)>,
}

struct Archive<'a> {
    npz: NpzArchive<'a>,
    path: &'a Path,
}

impl<'a> Archive<'a> {
    fn open(bytes: &'a [u8], path: &'a Path) -> Result<Self, DatasetError> {
        let npz = NpzArchive::new(bytes).map_err(|source| DatasetError::Npz {
            path: path.to_path_buf(),
            array: None,
            source,
        })?;
        Ok(Self { npz, path })
    }

    fn optional(&mut self, name: &str) -> Result<Option<NpyArray>, DatasetError> {
        self.npz.array(name).map_err(|source| DatasetError::Npz {
            path: self.path.to_path_buf(),
            array: Some(name.to_string()),
            source,
        })
    }

    fn required(&mut self, name: &str) -> Result<NpyArray, DatasetError> {
        self.optional(name)?
            .ok_or_else(|| DatasetError::MissingField {
                path: self.path.to_path_buf(),
                field: format!("array `{name}`"),
            })
    }

    fn bad(&self, name: &str, problem: String) -> DatasetError {
        DatasetError::BadField {
            path: self.path.to_path_buf(),
            field: format!("array `{name}`"),
            problem,
        }
    }
}

/// Parses `features_and_ground_truth.npz` from its bytes; `path` is used in
/// error messages. Checks shapes, dtypes and that `points1`, `points2` and
/// `labels` have the same length; never panics.
pub fn parse_features(bytes: &[u8], path: &Path) -> Result<Features, DatasetError> {
    let mut archive = Archive::open(bytes, path)?;
    let p1 = archive.required("points1")?;
    let p2 = archive.required("points2")?;
    let labels = archive.required("labels")?;
    let f = archive.required("F")?;

    let points1 = points(&archive, "points1", &p1)?;
    let points2 = points(&archive, "points2", &p2)?;
    if points2.len() != points1.len() {
        return Err(archive.bad(
            "points2",
            format!("{} points, points1 has {}", points2.len(), points1.len()),
        ));
    }
    if labels.shape.len() != 1 {
        return Err(archive.bad("labels", format!("shape {:?}, expected (N,)", labels.shape)));
    }
    let labels = match &labels.data {
        NpyData::Int(v) => v
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                i32::try_from(l)
                    .map_err(|_| archive.bad("labels", format!("element {i} is {l}, out of range")))
            })
            .collect::<Result<Vec<_>, _>>()?,
        NpyData::Float(_) => {
            return Err(archive.bad(
                "labels",
                format!("dtype {}, expected integers", labels.descr),
            ))
        }
    };
    if labels.len() != points1.len() {
        return Err(archive.bad(
            "labels",
            format!(
                "length {} does not match points1 ({} points)",
                labels.len(),
                points1.len()
            ),
        ));
    }
    let f_values = f.to_f64();
    let fundamentals = match f.shape.as_slice() {
        [_, 3, 3] | [3, 3] => f_values
            .chunks_exact(9)
            .map(Matrix3::from_row_slice)
            .collect(),
        other => return Err(archive.bad("F", format!("shape {other:?}, expected (k, 3, 3)"))),
    };
    Ok(Features {
        points1,
        points2,
        labels,
        fundamentals,
    })
}

/// N × 3 homogeneous (or N × 2) rows → pixels.
fn points(archive: &Archive, name: &str, array: &NpyArray) -> Result<Vec<[f64; 2]>, DatasetError> {
    let cols = match array.shape.as_slice() {
        [_, c @ (2 | 3)] => *c,
        other => return Err(archive.bad(name, format!("shape {other:?}, expected (N, 3)"))),
    };
    let values = array.to_f64();
    values
        .chunks_exact(cols)
        .enumerate()
        .map(|(i, row)| {
            if row.iter().any(|v| !v.is_finite()) {
                return Err(
                    archive.bad(name, format!("row {i} has a non-finite coordinate {row:?}"))
                );
            }
            match cols {
                2 => Ok([row[0], row[1]]),
                _ if row[2] == 1.0 => Ok([row[0], row[1]]),
                _ if row[2] != 0.0 => Ok([row[0] / row[2], row[1] / row[2]]),
                _ => Err(archive.bad(name, format!("row {i} is a point at infinity {row:?}"))),
            }
        })
        .collect()
}

/// Parses `camera_parameters.npz` from its bytes; `path` is used in error
/// messages. Reads `K` (3 × 3, finite, `K[0,0] > 0`) and the optional
/// `image_size`; never panics.
pub fn parse_camera(bytes: &[u8], path: &Path) -> Result<Camera, DatasetError> {
    let mut archive = Archive::open(bytes, path)?;
    let k = archive.required("K")?;
    if k.shape != [3, 3] {
        return Err(archive.bad("K", format!("shape {:?}, expected (3, 3)", k.shape)));
    }
    let kv = k.to_f64();
    if kv.iter().any(|v| !v.is_finite()) {
        return Err(archive.bad("K", "non-finite entry".to_string()));
    }
    if kv[0] <= 0.0 {
        return Err(archive.bad(
            "K",
            format!("K[0,0] = {} is not a positive focal length", kv[0]),
        ));
    }
    let image_size = match archive.optional("image_size")? {
        None => None,
        Some(a) => {
            let v = match (&a.shape[..], &a.data) {
                ([2], NpyData::Int(v)) => v.clone(),
                _ => {
                    return Err(archive.bad(
                        "image_size",
                        format!(
                            "shape {:?} dtype {}, expected 2 integers (W, H)",
                            a.shape, a.descr
                        ),
                    ))
                }
            };
            let dim = |x: i64| u32::try_from(x).ok().filter(|&d| d > 0);
            match (dim(v[0]), dim(v[1])) {
                (Some(w), Some(h)) => Some((w, h)),
                _ => return Err(archive.bad("image_size", format!("{v:?} is not a positive size"))),
            }
        }
    };
    Ok(Camera {
        principal_point: [kv[2], kv[5]],
        focal: kv[0],
        image_size,
    })
}
