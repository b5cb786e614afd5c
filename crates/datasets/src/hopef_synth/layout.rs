//! The per-object files of HOPE-F's layout, `object_<i>.npz`, as
//! `blender_render.py` writes them: `rot_euler_0`, `rot_euler_1` (minus the
//! yaw of views 1 and 2, radians, scalars), `t_0`, `t_1` (the object's
//! location in each view, 3-vectors). HOPE-F's `id` (the mesh file name) is
//! replaced by `shape` (int64 scalar: 0 box, 1 cylinder) and `dimensions`
//! (box extents x, y, z; cylinder diameter, diameter, height).
//!
//! With the camera's `R`, `t` and `K`, these give back each object's F by
//! `prepare_features_and_gt.py`'s own formula.

use super::truth::HopefTruth;
use super::world::{Pose, Shape};
use crate::npz::NpyArray;
use crate::synthetic::write_npz_file;
use crate::DatasetError;
use std::path::Path;

/// File name of object `i`'s poses (0-based, as HOPE-F).
pub fn object_file(i: usize) -> String {
    format!("object_{i}.npz")
}

fn scalar(v: f64) -> NpyArray {
    NpyArray {
        shape: vec![],
        data: crate::npz::NpyData::Float(vec![v]),
        descr: "<f8".into(),
    }
}

fn vector(values: Vec<f64>) -> NpyArray {
    NpyArray {
        shape: vec![values.len()],
        data: crate::npz::NpyData::Float(values),
        descr: "<f8".into(),
    }
}

fn location(pose: &Pose) -> NpyArray {
    vector(pose.translation().iter().copied().collect())
}

/// Writes `object_<i>.npz` for every object of `truth` into `dir`.
pub fn write_objects(dir: &Path, truth: &HopefTruth) -> Result<(), DatasetError> {
    for (i, object) in truth.objects.iter().enumerate() {
        let [a, b] = &object.poses;
        let (code, dimensions) = match object.shape {
            Shape::Box { extents } => (0, extents.to_vec()),
            Shape::Cylinder { radius, height } => (1, vec![2.0 * radius, 2.0 * radius, height]),
        };
        let shape = NpyArray {
            shape: vec![],
            data: crate::npz::NpyData::Int(vec![code]),
            descr: "<i8".into(),
        };
        write_npz_file(
            &dir.join(object_file(i)),
            &[
                ("rot_euler_0", &scalar(-a.yaw)),
                ("rot_euler_1", &scalar(-b.yaw)),
                ("t_0", &location(a)),
                ("t_1", &location(b)),
                ("shape", &shape),
                ("dimensions", &vector(dimensions)),
            ],
        )?;
    }
    Ok(())
}
