//! The 3-D world of a HOPE-F scene: the static camera placed as
//! `blender_render.py` places it, box- and cylinder-shaped objects standing
//! on the ground plane `z = 0`, their planar poses, and ray tests for
//! occlusion.
//!
//! World frame: z up, the ground plane is `z = 0`. Camera (Blender): rotation
//! `R_b = R_z(azimuth) R_x(tilt)`, centre `C = R_b (0, 0, d)`, looking along
//! its local −z at the origin. Pixels follow OpenCV: `X_c = S R_bᵀ (X − C)`
//! with `S = diag(1, −1, −1)`, `x = K X_c` (x right, y down).

use super::params::HopefParams;
use crate::synthetic::uniform;
use nalgebra::{Matrix3, Rotation3, Vector2, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The one camera of both views.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Camera {
    /// Intrinsics (principal point `(W/2, H/2)`).
    pub k: Matrix3<f64>,
    /// `K⁻¹`.
    pub k_inv: Matrix3<f64>,
    /// World-to-camera rotation (OpenCV axes), `S R_bᵀ`.
    pub world_to_camera: Matrix3<f64>,
    /// Blender's camera-to-world rotation `R_b` (HOPE-F's `R`).
    pub blender_rotation: Matrix3<f64>,
    /// Camera centre `C`.
    pub centre: Vector3<f64>,
    /// Distance `d` from the origin (HOPE-F's `t = (0, 0, −d)`).
    pub distance: f64,
    /// Image width and height in pixels.
    pub size: [f64; 2],
}

impl Camera {
    /// Draws focal, distance, tilt and azimuth (in that order).
    pub fn draw(rng: &mut ChaCha8Rng, params: &HopefParams) -> Self {
        let [w, h] = params.image_size.map(f64::from);
        let focal = uniform(rng, params.focal_px());
        let tilt = uniform(rng, params.camera_tilt_deg).to_radians();
        let azimuth = uniform(rng, params.camera_azimuth_deg).to_radians();
        let distance = uniform(rng, params.camera_distance);
        Self::new(focal, [w, h], tilt, azimuth, distance)
    }

    /// The camera with focal `focal` px, image `size`, tilt and azimuth in
    /// radians, at `distance` from the origin.
    pub fn new(focal: f64, size: [f64; 2], tilt: f64, azimuth: f64, distance: f64) -> Self {
        let k = Matrix3::new(
            focal,
            0.0,
            size[0] / 2.0,
            0.0,
            focal,
            size[1] / 2.0,
            0.0,
            0.0,
            1.0,
        );
        let k_inv = Matrix3::new(
            1.0 / focal,
            0.0,
            -size[0] / (2.0 * focal),
            0.0,
            1.0 / focal,
            -size[1] / (2.0 * focal),
            0.0,
            0.0,
            1.0,
        );
        let blender_rotation = *(Rotation3::from_axis_angle(&Vector3::z_axis(), azimuth)
            * Rotation3::from_axis_angle(&Vector3::x_axis(), tilt))
        .matrix();
        let flip = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0));
        Self {
            k,
            k_inv,
            world_to_camera: flip * blender_rotation.transpose(),
            blender_rotation,
            centre: blender_rotation * Vector3::new(0.0, 0.0, distance),
            distance,
            size,
        }
    }

    /// Focal length in pixels.
    pub fn focal(&self) -> f64 {
        self.k[(0, 0)]
    }

    /// The pixel of world point `x`, or `None` behind the camera.
    pub fn project(&self, x: &Vector3<f64>) -> Option<[f64; 2]> {
        let c = self.world_to_camera * (x - self.centre);
        if c.z <= 1e-9 {
            return None;
        }
        let p = self.k * c;
        Some([p.x / p.z, p.y / p.z])
    }

    /// True when `p` lies in the image, `0 ≤ x ≤ W−1`, `0 ≤ y ≤ H−1`.
    pub fn inside(&self, p: [f64; 2]) -> bool {
        (0.0..=self.size[0] - 1.0).contains(&p[0]) && (0.0..=self.size[1] - 1.0).contains(&p[1])
    }
}

/// An object's solid, in its own frame: the footprint centred on the origin,
/// standing on `z = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A box of extents `(x, y, z)`, `z` vertical.
    Box {
        /// Full extents along the object's x, y and z axes.
        extents: [f64; 3],
    },
    /// A vertical cylinder.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
    },
}

impl Shape {
    /// Draws a box (probability `box_share`) or a cylinder of the
    /// parameters' sizes; a box stands on a random one of its sides.
    pub(crate) fn draw(rng: &mut ChaCha8Rng, params: &HopefParams) -> Self {
        if rng.gen_bool(params.box_share) {
            let long = uniform(rng, params.box_long_side);
            let mut extents = [
                long,
                long * uniform(rng, params.box_middle_ratio),
                long * uniform(rng, params.box_short_ratio),
            ];
            let vertical = rng.gen_range(0..3);
            extents.swap(vertical, 2);
            if rng.gen_bool(0.5) {
                extents.swap(0, 1);
            }
            Shape::Box { extents }
        } else {
            Shape::Cylinder {
                radius: uniform(rng, params.cylinder_diameter) / 2.0,
                height: uniform(rng, params.cylinder_height),
            }
        }
    }

    /// The interval `[s_in, s_out]` of ray parameters (object frame, unit
    /// direction `d` from `o`) inside the solid, or `None` if the ray misses.
    fn ray_interval(&self, o: &Vector3<f64>, d: &Vector3<f64>) -> Option<[f64; 2]> {
        let parts = match *self {
            Shape::Box { extents } => [
                slab(o.x, d.x, -extents[0] / 2.0, extents[0] / 2.0)?,
                slab(o.y, d.y, -extents[1] / 2.0, extents[1] / 2.0)?,
                slab(o.z, d.z, 0.0, extents[2])?,
            ],
            Shape::Cylinder { radius, height } => [
                disc(o, d, radius)?,
                slab(o.z, d.z, 0.0, height)?,
                [f64::NEG_INFINITY, f64::INFINITY],
            ],
        };
        let lo = parts.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
        let hi = parts.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        (lo <= hi).then_some([lo, hi])
    }

    /// The faces that can carry texture (not the bottom, which rests on the
    /// ground), with their areas.
    pub(crate) fn faces(&self) -> Vec<(Face, f64)> {
        match *self {
            Shape::Box { extents: [x, y, z] } => {
                let (hx, hy) = (x / 2.0, y / 2.0);
                let rect = |origin: [f64; 3], u: [f64; 3], v: [f64; 3], normal: [f64; 3]| {
                    let (u, v) = (Vector3::from(u), Vector3::from(v));
                    let area = u.norm() * v.norm();
                    let face = Face::Rectangle {
                        origin: Vector3::from(origin),
                        u,
                        v,
                        normal: Vector3::from(normal),
                    };
                    (face, area)
                };
                vec![
                    rect(
                        [hx, -hy, 0.0],
                        [0.0, y, 0.0],
                        [0.0, 0.0, z],
                        [1.0, 0.0, 0.0],
                    ),
                    rect(
                        [-hx, -hy, 0.0],
                        [0.0, y, 0.0],
                        [0.0, 0.0, z],
                        [-1.0, 0.0, 0.0],
                    ),
                    rect(
                        [-hx, hy, 0.0],
                        [x, 0.0, 0.0],
                        [0.0, 0.0, z],
                        [0.0, 1.0, 0.0],
                    ),
                    rect(
                        [-hx, -hy, 0.0],
                        [x, 0.0, 0.0],
                        [0.0, 0.0, z],
                        [0.0, -1.0, 0.0],
                    ),
                    rect([-hx, -hy, z], [x, 0.0, 0.0], [0.0, y, 0.0], [0.0, 0.0, 1.0]),
                ]
            }
            Shape::Cylinder { radius, height } => vec![
                (
                    Face::RoundSide { radius, height },
                    std::f64::consts::TAU * radius * height,
                ),
                (
                    Face::Disc { radius, height },
                    std::f64::consts::PI * radius * radius,
                ),
            ],
        }
    }
}

/// The ray parameters `s` with `min ≤ origin + s dir ≤ max`, or `None`.
fn slab(origin: f64, dir: f64, min: f64, max: f64) -> Option<[f64; 2]> {
    if dir.abs() < 1e-12 {
        return (min..=max)
            .contains(&origin)
            .then_some([f64::NEG_INFINITY, f64::INFINITY]);
    }
    let (a, b) = ((min - origin) / dir, (max - origin) / dir);
    Some([a.min(b), a.max(b)])
}

/// The ray parameters `s` with `|o_xy + s d_xy| ≤ radius` (a vertical
/// infinite cylinder about the z axis), or `None`.
fn disc(o: &Vector3<f64>, d: &Vector3<f64>, radius: f64) -> Option<[f64; 2]> {
    // a s² + 2 b s + c ≤ 0.
    let a = d.x * d.x + d.y * d.y;
    let b = o.x * d.x + o.y * d.y;
    let c = o.x * o.x + o.y * o.y - radius * radius;
    if a < 1e-12 {
        return (c <= 0.0).then_some([f64::NEG_INFINITY, f64::INFINITY]);
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    Some([(-b - root) / a, (-b + root) / a])
}

/// A textured face of a [`Shape`], in the object's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Face {
    /// The parallelogram `origin + a u + b v`, `a, b ∈ [0, 1]`.
    Rectangle {
        /// One corner.
        origin: Vector3<f64>,
        /// First edge.
        u: Vector3<f64>,
        /// Second edge.
        v: Vector3<f64>,
        /// Outward unit normal.
        normal: Vector3<f64>,
    },
    /// The round side of a vertical cylinder on `z = 0`.
    RoundSide {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
    },
    /// The top cap of a vertical cylinder on `z = 0`.
    Disc {
        /// Radius.
        radius: f64,
        /// Height of the cap.
        height: f64,
    },
}

impl Face {
    /// A uniform point on the face, with its outward unit normal.
    pub(crate) fn sample(&self, rng: &mut ChaCha8Rng) -> (Vector3<f64>, Vector3<f64>) {
        match *self {
            Face::Rectangle {
                origin,
                u,
                v,
                normal,
            } => (
                origin + u * rng.gen_range(0.0..=1.0) + v * rng.gen_range(0.0..=1.0),
                normal,
            ),
            Face::RoundSide { radius, height } => {
                let theta = rng.gen_range(0.0..std::f64::consts::TAU);
                let n = Vector3::new(theta.cos(), theta.sin(), 0.0);
                (n * radius + Vector3::z() * rng.gen_range(0.0..=height), n)
            }
            Face::Disc { radius, height } => {
                let theta = rng.gen_range(0.0..std::f64::consts::TAU);
                let rho = radius * rng.gen::<f64>().sqrt();
                (
                    Vector3::new(rho * theta.cos(), rho * theta.sin(), height),
                    Vector3::z(),
                )
            }
        }
    }
}

/// An object's placement in one view: position on the ground and yaw about
/// the vertical through its footprint centre (`X = R_z(yaw) X_obj + t`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position `(x, y)` on the ground plane.
    pub position: Vector2<f64>,
    /// Yaw in radians.
    pub yaw: f64,
}

impl Pose {
    /// The rotation `R_z(yaw)`.
    pub fn rotation(&self) -> Matrix3<f64> {
        *Rotation3::from_axis_angle(&Vector3::z_axis(), self.yaw).matrix()
    }

    /// The translation `(x, y, 0)`.
    pub fn translation(&self) -> Vector3<f64> {
        Vector3::new(self.position.x, self.position.y, 0.0)
    }

    /// World coordinates of the object-frame point `p`.
    pub fn object_to_world(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.rotation() * p + self.translation()
    }

    /// Object-frame coordinates of the world point `x`.
    fn world_to_object(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.rotation().transpose() * (x - self.translation())
    }
}

/// The poses of `count` objects in one view: the base positions `(±b, ±b)`
/// shuffled, each plus a uniform offset in `[−j, j]²` and a yaw uniform in
/// `[−y, y]` degrees (`blender_render.py`, per render).
pub(crate) fn draw_poses(rng: &mut ChaCha8Rng, params: &HopefParams, count: usize) -> Vec<Pose> {
    use rand::seq::SliceRandom;
    let b = params.base_offset;
    let mut bases = [[-b, -b], [b, -b], [-b, b], [b, b]];
    bases.shuffle(rng);
    let j = params.position_jitter;
    let y = params.yaw_deg;
    (0..count)
        .map(|i| {
            let base = bases[i % bases.len()];
            let offset = [uniform(rng, [-j, j]), uniform(rng, [-j, j])];
            Pose {
                position: Vector2::new(base[0] + offset[0], base[1] + offset[1]),
                yaw: uniform(rng, [-y, y]).to_radians(),
            }
        })
        .collect()
}

/// True when the segment from `from` to `to` (world) passes through the
/// solid `shape` placed at `pose`, excluding `margin` at both ends.
pub(crate) fn blocks(
    shape: &Shape,
    pose: &Pose,
    from: &Vector3<f64>,
    to: &Vector3<f64>,
    margin: f64,
) -> bool {
    let length = (to - from).norm();
    if length <= 2.0 * margin {
        return false;
    }
    let o = pose.world_to_object(from);
    let d = pose.rotation().transpose() * ((to - from) / length);
    shape
        .ray_interval(&o, &d)
        .is_some_and(|[lo, hi]| lo < length - margin && hi > margin)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_looks_at_the_origin_from_its_distance() {
        let cam = Camera::new(1000.0, [1024.0, 1024.0], 0.7, 2.0, 4.0);
        let p = cam.project(&Vector3::zeros()).unwrap();
        assert!((p[0] - 512.0).abs() < 1e-9 && (p[1] - 512.0).abs() < 1e-9);
        assert!((cam.centre.norm() - 4.0).abs() < 1e-12);
        // Height d cos(tilt) above the ground.
        assert!((cam.centre.z - 4.0 * 0.7f64.cos()).abs() < 1e-12);
        // Up in the world is up in the image (smaller y).
        let up = cam.project(&Vector3::new(0.0, 0.0, 0.5)).unwrap();
        assert!(up[1] < 512.0);
    }

    #[test]
    fn ray_intervals_of_a_box_and_a_cylinder() {
        let boxed = Shape::Box {
            extents: [2.0, 4.0, 1.0],
        };
        let o = Vector3::new(-5.0, 0.0, 0.5);
        let [lo, hi] = boxed.ray_interval(&o, &Vector3::x()).unwrap();
        assert!((lo - 4.0).abs() < 1e-12 && (hi - 6.0).abs() < 1e-12);
        assert!(boxed
            .ray_interval(&Vector3::new(-5.0, 0.0, 1.5), &Vector3::x())
            .is_none());
        let can = Shape::Cylinder {
            radius: 1.0,
            height: 2.0,
        };
        let [lo, hi] = can.ray_interval(&o, &Vector3::x()).unwrap();
        assert!((lo - 4.0).abs() < 1e-12 && (hi - 6.0).abs() < 1e-12);
        let down = Vector3::new(0.5, 0.0, 10.0);
        let [lo, hi] = can.ray_interval(&down, &-Vector3::z()).unwrap();
        assert!((lo - 8.0).abs() < 1e-12 && (hi - 10.0).abs() < 1e-12);
        assert!(can
            .ray_interval(&Vector3::new(1.5, 0.0, 10.0), &-Vector3::z())
            .is_none());
    }

    #[test]
    fn blocking_respects_pose_and_segment_ends() {
        let can = Shape::Cylinder {
            radius: 0.5,
            height: 1.0,
        };
        let pose = Pose {
            position: Vector2::new(2.0, 0.0),
            yaw: 0.3,
        };
        let from = Vector3::new(0.0, 0.0, 0.5);
        assert!(blocks(
            &can,
            &pose,
            &from,
            &Vector3::new(4.0, 0.0, 0.5),
            1e-6
        ));
        // The segment stops before the solid.
        assert!(!blocks(
            &can,
            &pose,
            &from,
            &Vector3::new(1.4, 0.0, 0.5),
            1e-6
        ));
        // A point on the near surface is not hidden by its own solid.
        assert!(!blocks(
            &can,
            &pose,
            &from,
            &Vector3::new(1.5, 0.0, 0.5),
            1e-6
        ));
    }
}
