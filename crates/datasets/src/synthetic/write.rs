//! The writer of the HOPE-F on-disk layout: one folder per scene with
//! `features_and_ground_truth.npz` and `camera_parameters.npz` (and the
//! `hopef` preset's object files).

use std::path::Path;

use nalgebra::{Matrix3, Vector3};

use super::{write_records_csv, SyntheticScene, RECORDS_FILE};
use crate::hopef::{CAMERA_FILE, FEATURES_FILE};
use crate::hopef_synth;
use crate::npz::{write_npz, NpyArray};
use crate::DatasetError;

/// Writes scenes in the HOPE-F on-disk layout under `root`
/// (`<root>/<category>/<NNNN>/features_and_ground_truth.npz` and
/// `camera_parameters.npz`), readable by [`crate::hopef`] and by
/// `numpy.load`. Existing files of the same names are replaced.
///
/// Arrays: `points1`, `points2` (N × 3, third column 1), `labels` (N,
/// int64), `F` (motions × 3 × 3), `ratios` (N zeros: synthetic matches have
/// no descriptor ratio, and 0 passes any ratio test); `K`, `R` = `R_e`,
/// `t` = `t_e` and `image_size` = (W, H) (int64, an addition to HOPE-F's
/// arrays that makes the round trip lossless).
///
/// Scenes of the `hopef` preset are written as HOPE-F writes them: their
/// drawn `ratios`, the camera's `R` (Blender's camera-to-world rotation)
/// and `t` = (0, 0, −d), and one `object_<i>.npz` per object
/// ([`hopef_synth::layout`]).
///
/// Scenes of the randomised families (`driving-random`, `objects-3d`) also
/// have their drawn difficulty written to `<root>/`[`RECORDS_FILE`]
/// ([`write_records_csv`]).
pub fn write_hopef_layout(root: &Path, scenes: &[SyntheticScene]) -> Result<(), DatasetError> {
    write_hopef_layout_with(root, scenes, |_, _| {})
}

/// [`write_hopef_layout`], calling `progress(done, total)` after each scene.
pub fn write_hopef_layout_with(
    root: &Path,
    scenes: &[SyntheticScene],
    mut progress: impl FnMut(usize, usize),
) -> Result<(), DatasetError> {
    for (i, s) in scenes.iter().enumerate() {
        let dir = root
            .join(s.category.to_string())
            .join(format!("{:04}", s.index));
        write_hopef_scene(&dir, s)?;
        progress(i + 1, scenes.len());
    }
    write_records_csv(&root.join(RECORDS_FILE), scenes)?;
    Ok(())
}

/// The entries of a 3 × 3 matrix in row-major (NumPy C) order.
fn row_major(m: &Matrix3<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// Writes one scene's two `.npz` files into `dir` (created if needed).
pub fn write_hopef_scene(dir: &Path, s: &SyntheticScene) -> Result<(), DatasetError> {
    std::fs::create_dir_all(dir).map_err(|e| DatasetError::io(dir, e))?;
    let scene = &s.scene;
    let n = scene.len();
    let homogeneous = |pts: &[[f64; 2]]| {
        NpyArray::from_f64(
            vec![pts.len(), 3],
            pts.iter().flat_map(|p| [p[0], p[1], 1.0]).collect(),
        )
    };
    let labels: Vec<i64> = scene
        .labels
        .as_ref()
        .map(|l| l.iter().map(|&x| i64::from(x)).collect())
        .unwrap_or_else(|| vec![0; n]);
    let shape_err = || DatasetError::Generation {
        scene: scene.name.clone(),
        problem: "inconsistent array lengths".into(),
    };
    let points1 = homogeneous(&scene.points1).ok_or_else(shape_err)?;
    let points2 = homogeneous(&scene.points2).ok_or_else(shape_err)?;
    let labels = NpyArray::from_i64(vec![labels.len()], labels).ok_or_else(shape_err)?;
    let f = NpyArray::from_f64(
        vec![scene.gt_fundamentals.len(), 3, 3],
        scene.gt_fundamentals.iter().flat_map(row_major).collect(),
    )
    .ok_or_else(shape_err)?;
    let (ratios, rotation, translation) = match &s.hopef {
        Some(truth) => (
            truth.ratios.clone(),
            truth.camera_rotation,
            Vector3::new(0.0, 0.0, -truth.camera_distance),
        ),
        None => (vec![0.0; n], s.ego_rotation, s.ego_translation),
    };
    let ratios = NpyArray::from_f64(vec![n], ratios).ok_or_else(shape_err)?;
    let k = NpyArray::from_f64(vec![3, 3], row_major(&s.intrinsics)).ok_or_else(shape_err)?;
    let r = NpyArray::from_f64(vec![3, 3], row_major(&rotation)).ok_or_else(shape_err)?;
    let t =
        NpyArray::from_f64(vec![3], translation.iter().copied().collect()).ok_or_else(shape_err)?;
    let size = NpyArray::from_i64(
        vec![2],
        vec![i64::from(scene.image_size.0), i64::from(scene.image_size.1)],
    )
    .ok_or_else(shape_err)?;

    let write = |name: &str, arrays: &[(&str, &NpyArray)]| write_npz_file(&dir.join(name), arrays);
    write(
        FEATURES_FILE,
        &[
            ("F", &f),
            ("labels", &labels),
            ("points1", &points1),
            ("points2", &points2),
            ("ratios", &ratios),
        ],
    )?;
    write(
        CAMERA_FILE,
        &[("K", &k), ("R", &r), ("t", &t), ("image_size", &size)],
    )?;
    match &s.hopef {
        Some(truth) => hopef_synth::layout::write_objects(dir, truth),
        None => Ok(()),
    }
}

/// Writes `arrays` as the `.npz` archive `path`.
pub(crate) fn write_npz_file(
    path: &Path,
    arrays: &[(&str, &NpyArray)],
) -> Result<(), DatasetError> {
    let file = std::fs::File::create(path).map_err(|e| DatasetError::io(path, e))?;
    write_npz(std::io::BufWriter::new(file), arrays).map_err(|source| DatasetError::Npz {
        path: path.to_path_buf(),
        array: None,
        source,
    })
}
