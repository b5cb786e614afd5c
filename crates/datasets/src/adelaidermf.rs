//! AdelaideRMF (Wong, Chin, Yu, Suter, ICCV 2011): the 19 two-view
//! fundamental-matrix scenes, one MATLAB v5 `.mat` file each (docs/method.md,
//! "Datasets").
//!
//! Variables used: `data` (6 × N, rows x1, y1, 1, x2, y2, 1), `label`
//! (1 × N, 0 = gross outlier), `img1` / `img2` (H × W × 3 `uint8`, or H × W
//! grayscale for `boardgame` and `dinobooks`), all column-major. The
//! homogeneous rows are 1 in every file; a point whose third coordinate is
//! another finite non-zero value is divided by it. The principal point is
//! the image centre ((W-1)/2, (H-1)/2); no focal length is known.

use crate::mat::{parse_mat_selected, MatFile, MatValues, MatVariable};
use crate::{centre_principal_point, DatasetError, Scene};
use std::path::{Path, PathBuf};

/// The 19 fundamental-matrix scenes of AdelaideRMF (the "Fundamental Matrix
/// Data" list of the dataset's readme), in alphabetical order.
pub const FUNDAMENTAL_SCENES: [&str; 19] = [
    "biscuit",
    "biscuitbook",
    "biscuitbookbox",
    "boardgame",
    "book",
    "breadcartoychips",
    "breadcube",
    "breadcubechips",
    "breadtoy",
    "breadtoycar",
    "carchipscube",
    "cube",
    "cubebreadtoychips",
    "cubechips",
    "cubetoy",
    "dinobooks",
    "game",
    "gamebiscuit",
    "toycubecar",
];

pub use crate::scene::LoadOptions;

/// A directory holding the AdelaideRMF `.mat` files (`<data root>/adelaidermf/F`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AdelaideRmf {
    dir: PathBuf,
}

impl AdelaideRmf {
    /// Opens the dataset directory; [`DatasetError::DatasetMissing`] (with
    /// where to get it) when it is not a directory.
    pub fn open(dir: impl AsRef<Path>) -> Result<Self, DatasetError> {
        let dir = dir.as_ref();
        if !dir.is_dir() {
            return Err(DatasetError::DatasetMissing {
                what: "AdelaideRMF",
                path: dir.to_path_buf(),
            });
        }
        Ok(Self {
            dir: dir.to_path_buf(),
        })
    }

    /// The dataset directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The scene names: [`FUNDAMENTAL_SCENES`].
    pub fn scene_names(&self) -> &'static [&'static str] {
        &FUNDAMENTAL_SCENES
    }

    /// Path of the named scene's file; [`DatasetError::UnknownScene`] for a
    /// name not in [`FUNDAMENTAL_SCENES`].
    pub fn scene_path(&self, name: &str) -> Result<PathBuf, DatasetError> {
        if !FUNDAMENTAL_SCENES.contains(&name) {
            return Err(DatasetError::UnknownScene {
                dataset: "AdelaideRMF",
                name: name.to_string(),
                known: FUNDAMENTAL_SCENES.iter().map(|s| s.to_string()).collect(),
            });
        }
        Ok(self.dir.join(format!("{name}.mat")))
    }

    /// Loads the named scene with its images.
    ///
    /// ```no_run
    /// let data = datasets::adelaidermf::AdelaideRmf::open("datasets/adelaidermf/F")?;
    /// let scene = data.load("biscuit")?;
    /// assert_eq!(scene.num_motions(), 1);
    /// # Ok::<(), datasets::DatasetError>(())
    /// ```
    pub fn load(&self, name: &str) -> Result<Scene, DatasetError> {
        self.load_with(name, LoadOptions::default())
    }

    /// Loads the named scene.
    pub fn load_with(&self, name: &str, options: LoadOptions) -> Result<Scene, DatasetError> {
        load_scene_with(self.scene_path(name)?, options)
    }

    /// Loads all 19 scenes, in [`FUNDAMENTAL_SCENES`] order.
    pub fn load_all(&self, options: LoadOptions) -> Result<Vec<Scene>, DatasetError> {
        FUNDAMENTAL_SCENES
            .iter()
            .map(|name| self.load_with(name, options))
            .collect()
    }
}

/// Loads one AdelaideRMF `.mat` file, images included. The scene is named
/// after the file stem.
pub fn load_scene(path: impl AsRef<Path>) -> Result<Scene, DatasetError> {
    load_scene_with(path, LoadOptions::default())
}

/// Loads one AdelaideRMF `.mat` file.
pub fn load_scene_with(
    path: impl AsRef<Path>,
    options: LoadOptions,
) -> Result<Scene, DatasetError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|e| DatasetError::io(path, e))?;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    parse_scene(&bytes, &name, path, options)
}

/// Builds a scene from the bytes of an AdelaideRMF `.mat` file; `path` is
/// only used in error messages. Never panics.
pub fn parse_scene(
    bytes: &[u8],
    name: &str,
    path: &Path,
    options: LoadOptions,
) -> Result<Scene, DatasetError> {
    // The images are inflated only when asked for: their size is in the
    // variables' headers.
    let wanted = |name: &str| options.images || !matches!(name, "img1" | "img2");
    let mat = parse_mat_selected(bytes, wanted).map_err(|source| DatasetError::Mat {
        path: path.to_path_buf(),
        source,
    })?;
    scene_from_mat(&mat, name, path, options)
}

/// Builds a scene from a parsed AdelaideRMF `.mat` file (see the module
/// documentation for the variables), validated with [`Scene::validate`].
pub fn scene_from_mat(
    mat: &MatFile,
    name: &str,
    path: &Path,
    options: LoadOptions,
) -> Result<Scene, DatasetError> {
    let file = MatScene { mat, path };
    let points = file.points()?;
    let labels = file.labels()?;
    let (image_size, images) = file.images(options)?;
    let scene = Scene {
        name: name.to_string(),
        points1: points.points1,
        points2: points.points2,
        labels: Some(labels),
        image_size,
        principal_point: centre_principal_point(image_size),
        true_focal: None,
        gt_fundamentals: Vec::new(),
        images,
    };
    scene.validate().map_err(|e| e.in_file(path))?;
    Ok(scene)
}

/// The variables of one AdelaideRMF file, read field by field with errors
/// that name the file and the variable.
struct MatScene<'a> {
    mat: &'a MatFile,
    path: &'a Path,
}

/// The correspondences of a scene, in pixels.
struct Correspondences {
    points1: Vec<[f64; 2]>,
    points2: Vec<[f64; 2]>,
}

impl MatScene<'_> {
    /// A [`DatasetError::BadField`] for the variable `field`.
    fn bad(&self, field: &str, problem: String) -> DatasetError {
        DatasetError::BadField {
            path: self.path.to_path_buf(),
            field: format!("variable `{field}`"),
            problem,
        }
    }

    /// The variable `field`, or [`DatasetError::MissingField`].
    fn var(&self, field: &str) -> Result<&MatVariable, DatasetError> {
        self.mat
            .get(field)
            .ok_or_else(|| DatasetError::MissingField {
                path: self.path.to_path_buf(),
                field: format!("variable `{field}`"),
            })
    }

    /// `data`: 6 × N columns `(x1, y1, w1, x2, y2, w2)`, dehomogenised.
    fn points(&self) -> Result<Correspondences, DatasetError> {
        let bad = |field: &str, problem: String| self.bad(field, problem);
        let data = self.var("data")?;
        let values = data
            .to_f64()
            .ok_or_else(|| bad("data", format!("class {:?} is not numeric", data.class)))?;
        if data.dims.len() != 2 || data.dims[0] != 6 {
            return Err(bad(
                "data",
                format!("dimensions {:?}, expected 6 x N", data.dims),
            ));
        }
        let n = data.dims[1];
        let mut points1 = Vec::with_capacity(n);
        let mut points2 = Vec::with_capacity(n);
        for (i, column) in values.chunks_exact(6).enumerate() {
            for (image, w, points) in [(1, 2, &mut points1), (2, 5, &mut points2)] {
                let point = [column[w - 2], column[w - 1], column[w]];
                points.push(dehomogenise(point).ok_or_else(|| {
                    bad(
                        "data",
                        format!(
                            "column {i}: image-{image} point has third coordinate {}",
                            column[w]
                        ),
                    )
                })?);
            }
        }
        Ok(Correspondences { points1, points2 })
    }

    /// `label`: a vector of integers 0, 1, 2, ….
    fn labels(&self) -> Result<Vec<i32>, DatasetError> {
        let bad = |field: &str, problem: String| self.bad(field, problem);
        let label = self.var("label")?;
        let label_values = label
            .to_f64()
            .ok_or_else(|| bad("label", format!("class {:?} is not numeric", label.class)))?;
        if label.dims.iter().filter(|&&d| d != 1).count() > 1 {
            return Err(bad(
                "label",
                format!("dimensions {:?}, expected a vector", label.dims),
            ));
        }
        label_values
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                if v.fract() == 0.0 && (0.0..=f64::from(i32::MAX)).contains(&v) {
                    Ok(v as i32)
                } else {
                    Err(bad(
                        "label",
                        format!("element {i} is {v}, not a label 0, 1, 2, …"),
                    ))
                }
            })
            .collect()
    }

    /// `img1`, `img2`: their common size, and the images when asked for.
    fn images(&self, options: LoadOptions) -> Result<ImagesRead, DatasetError> {
        let bad = |field: &str, problem: String| self.bad(field, problem);
        let img1 = self.var("img1")?;
        let img2 = self.var("img2")?;
        let size1 = image_size(img1).map_err(|p| bad("img1", p))?;
        let size2 = image_size(img2).map_err(|p| bad("img2", p))?;
        if size1 != size2 {
            return Err(bad(
                "img2",
                format!("size {size2:?} differs from img1 {size1:?}"),
            ));
        }
        let images = if options.images {
            Some((
                to_rgb(img1).map_err(|p| bad("img1", p))?,
                to_rgb(img2).map_err(|p| bad("img2", p))?,
            ))
        } else {
            None
        };
        Ok((size1, images))
    }
}

/// The image size and, when loaded, the image pair.
type ImagesRead = ((u32, u32), Option<(image::RgbImage, image::RgbImage)>);

/// `(x / w, y / w)`, or `None` when `w` is zero or not finite (a point at
/// infinity or garbage).
fn dehomogenise([x, y, w]: [f64; 3]) -> Option<[f64; 2]> {
    if w == 1.0 {
        Some([x, y])
    } else if w.is_finite() && w != 0.0 {
        Some([x / w, y / w])
    } else {
        None
    }
}

/// `(W, H)` of an H × W or H × W × 3 image variable.
fn image_size(var: &MatVariable) -> Result<(u32, u32), String> {
    let ok_dims = match var.dims.as_slice() {
        [_, _] => true,
        [_, _, c] => *c == 3 || *c == 1,
        _ => false,
    };
    if !ok_dims {
        return Err(format!(
            "dimensions {:?}, expected H x W or H x W x 3",
            var.dims
        ));
    }
    let h = u32::try_from(var.dims[0]).map_err(|_| "height too large".to_string())?;
    let w = u32::try_from(var.dims[1]).map_err(|_| "width too large".to_string())?;
    if w == 0 || h == 0 {
        return Err(format!("empty image {:?}", var.dims));
    }
    Ok((w, h))
}

/// Converts a column-major H × W (grayscale) or H × W × 3 `uint8` MATLAB
/// image to a row-major RGB image.
fn to_rgb(var: &MatVariable) -> Result<image::RgbImage, String> {
    let (w, h) = image_size(var)?;
    let bytes = match &var.values {
        MatValues::UInt8(b) => b,
        _ => return Err(format!("class {:?}, expected uint8", var.class)),
    };
    let (w, h) = (w as usize, h as usize);
    let channels = var.dims.get(2).copied().unwrap_or(1);
    // numel == bytes.len() is guaranteed by the MAT reader.
    let plane = w * h;
    let mut rgb = Vec::with_capacity(plane * 3);
    for row in 0..h {
        for col in 0..w {
            let at = row + h * col;
            for c in 0..3 {
                let channel = if channels == 3 { c } else { 0 };
                rgb.push(bytes[at + plane * channel]);
            }
        }
    }
    image::RgbImage::from_raw(w as u32, h as u32, rgb)
        .ok_or_else(|| "image buffer size".to_string())
}
