//! The surfaces of the `objects-3d` family's objects: an ellipsoid's
//! surface, a rectangular patch with a sinusoidal relief, a box's faces;
//! each inside the unit sphere about the origin (scaled and placed by the
//! caller).

use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::objects3d_params::SurfaceMix;
use super::sampling::random_unit;

/// One object's surface, in its own frame, inside the unit sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Surface {
    /// `x²/a² + y²/b² + z²/c² = 1`, semi-axes in `[0.3, 1]`.
    Ellipsoid { axes: Vector3<f64> },
    /// `z = amplitude · sin(fx x + φx) · cos(fy y + φy)` over
    /// `|x| ≤ half[0]`, `|y| ≤ half[1]` (halves in `[0.4, 0.65]`,
    /// amplitude in `[0.1, 0.3]`: never flat, so F stays determined).
    ReliefPlane {
        half: [f64; 2],
        amplitude: f64,
        frequency: [f64; 2],
        phase: [f64; 2],
    },
    /// The faces of a box with half-diagonal 1.
    Box { dims: Vector3<f64> },
}

impl Surface {
    /// A surface of a kind drawn from `mix`, its proportions drawn too.
    pub(super) fn draw(rng: &mut ChaCha8Rng, mix: &SurfaceMix) -> Self {
        let total = mix.ellipsoids + mix.relief_planes + mix.boxes;
        let pick = rng.gen_range(0.0..total);
        if pick < mix.ellipsoids {
            Surface::Ellipsoid {
                axes: Vector3::from_fn(|_, _| rng.gen_range(0.3..=1.0)),
            }
        } else if pick < mix.ellipsoids + mix.relief_planes {
            Surface::ReliefPlane {
                half: [rng.gen_range(0.4..=0.65), rng.gen_range(0.4..=0.65)],
                amplitude: rng.gen_range(0.1..=0.3),
                frequency: [rng.gen_range(2.0..=8.0), rng.gen_range(2.0..=8.0)],
                phase: [
                    rng.gen_range(0.0..std::f64::consts::TAU),
                    rng.gen_range(0.0..std::f64::consts::TAU),
                ],
            }
        } else {
            let dims: Vector3<f64> = Vector3::from_fn(|_, _| rng.gen_range(0.3..=1.0));
            Surface::Box {
                dims: dims * (2.0 / dims.norm()),
            }
        }
    }

    /// A random point on the surface (ellipsoid: a uniform direction
    /// scaled by the axes; relief: uniform over the patch's footprint; box:
    /// uniform by area).
    pub(super) fn sample(&self, rng: &mut ChaCha8Rng) -> Vector3<f64> {
        match *self {
            Surface::Ellipsoid { axes } => random_unit(rng).into_inner().component_mul(&axes),
            Surface::ReliefPlane {
                half,
                amplitude,
                frequency,
                phase,
            } => {
                let x = rng.gen_range(-half[0]..=half[0]);
                let y = rng.gen_range(-half[1]..=half[1]);
                let z = amplitude
                    * (frequency[0] * x + phase[0]).sin()
                    * (frequency[1] * y + phase[1]).cos();
                Vector3::new(x, y, z)
            }
            Surface::Box { dims } => {
                let areas = [dims.y * dims.z, dims.x * dims.z, dims.x * dims.y];
                let mut pick = rng.gen_range(0.0..areas.iter().sum::<f64>());
                let axis = (0..2)
                    .find(|&a| {
                        pick -= areas[a];
                        pick < 0.0
                    })
                    .unwrap_or(2);
                let mut p: Vector3<f64> =
                    Vector3::from_fn(|i, _| rng.gen_range(-0.5..0.5) * dims[i]);
                p[axis] = if rng.gen_bool(0.5) { 0.5 } else { -0.5 } * dims[axis];
                p
            }
        }
    }
}
