//! Ground truth of a HOPE-F scene: each object's fundamental matrix from its
//! planar motion under the static camera, HOPE-F's labelling and acceptance
//! rules (`prepare_features_and_gt.py`), and what each match really is.

use super::world::{Camera, Pose, Shape};
use crate::synthetic::fundamental;
use geometry::sampson_distance;
use nalgebra::{Matrix3, Vector3};

/// What a match really is (known to the generator, not to HOPE-F's labels).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatchSource {
    /// A feature of object `object` (0-based) matched to itself.
    Correct {
        /// The object, 0-based (label `object + 1` if within the band).
        object: usize,
    },
    /// A feature of object `object1` in image 1 paired with a feature of
    /// object `object2` in image 2 (0-based; they may be equal).
    Mismatch {
        /// Object of the image-1 feature.
        object1: usize,
        /// Object of the image-2 feature.
        object2: usize,
    },
}

/// One object's ground truth.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectTruth {
    /// Its solid (object frame: footprint centred on the origin, on `z = 0`).
    pub shape: Shape,
    /// Its poses in views 1 and 2.
    pub poses: [Pose; 2],
    /// Its texture features per unit² of surface.
    pub texture_density: f64,
}

impl ObjectTruth {
    /// The world motion `X₂ = R X₁ + t` from view 1 to view 2:
    /// `R = R_z(yaw₂ − yaw₁)`, `t = t₂ − R t₁`.
    pub fn motion(&self) -> (Matrix3<f64>, Vector3<f64>) {
        let [a, b] = &self.poses;
        let r = b.rotation() * a.rotation().transpose();
        (r, b.translation() - r * a.translation())
    }

    /// `yaw₂ − yaw₁` in degrees.
    pub fn relative_yaw_deg(&self) -> f64 {
        (self.poses[1].yaw - self.poses[0].yaw).to_degrees()
    }
}

/// The generator's record of a HOPE-F scene, beyond what the
/// [`crate::Scene`] holds.
#[derive(Debug, Clone, PartialEq)]
pub struct HopefTruth {
    /// Blender's camera-to-world rotation `R_b` (HOPE-F's `R`).
    pub camera_rotation: Matrix3<f64>,
    /// Camera distance `d` from the origin (HOPE-F's `t = (0, 0, −d)`).
    pub camera_distance: f64,
    /// The objects, in label order.
    pub objects: Vec<ObjectTruth>,
    /// What each match is, in the scene's order.
    pub sources: Vec<MatchSource>,
    /// Descriptor distance ratio of each match (HOPE-F's `ratios`).
    pub ratios: Vec<f64>,
    /// Draws needed to meet the acceptance rule (1 = the first).
    pub attempts: u32,
}

/// The fundamental matrix of an object moving by the world motion `(R, t)`
/// under the static `camera`: in camera coordinates `X_c = W (X − C)` the
/// motion is `R_c = W R Wᵀ`, `T_c = W (R C + t − C)`, and
/// `F = K⁻ᵀ [T_c]ₓ R_c K⁻¹` (Hartley & Zisserman, Eq. 9.12), unit
/// Frobenius norm. `None` when the object does not move (`T_c = 0`).
pub(crate) fn object_fundamental(
    camera: &Camera,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
) -> Option<Matrix3<f64>> {
    let w = &camera.world_to_camera;
    let r_c = w * r * w.transpose();
    let t_c = w * (r * camera.centre + t - camera.centre);
    if t_c.norm() < 1e-9 * camera.distance {
        return None;
    }
    let f = fundamental(&camera.k_inv, &r_c, &t_c);
    f.iter().all(|v| v.is_finite()).then_some(f)
}

/// HOPE-F's label of a match: 1 + the index of the F with the smallest
/// Sampson distance if that distance is below `threshold`, else 0 (ties: the
/// first, as NumPy's `argmin`).
pub fn hopef_label(
    fundamentals: &[Matrix3<f64>],
    p1: [f64; 2],
    p2: [f64; 2],
    threshold: f64,
) -> i32 {
    let mut best = (f64::INFINITY, 0);
    for (j, f) in fundamentals.iter().enumerate() {
        let d = sampson_distance(f, p1, p2);
        if d < best.0 {
            best = (d, j);
        }
    }
    if best.0 < threshold {
        best.1 as i32 + 1
    } else {
        0
    }
}

/// HOPE-F's acceptance rule: every F has at least `min_inliers` matches
/// (any label) with Sampson distance below `threshold`.
pub fn hopef_accepts(
    fundamentals: &[Matrix3<f64>],
    points1: &[[f64; 2]],
    points2: &[[f64; 2]],
    threshold: f64,
    min_inliers: usize,
) -> bool {
    fundamentals.iter().all(|f| {
        points1
            .iter()
            .zip(points2)
            .filter(|(a, b)| sampson_distance(f, **a, **b) < threshold)
            .count()
            >= min_inliers
    })
}
