//! Prototype (SCTL_PROTO_EMP): the NFA's background drawn from the data's
//! own marginals instead of uniform over the images: `x₁` one of the
//! matches' image-1 points, `x₂` from a histogram of their image-2 points
//! (8 × 8 cells over the image, Laplace-smoothed), independent of `x₁`:
//! random pairings of the data's keypoints, which is what a mismatch is.

use super::background::{clip, Background, ImageRect};
use geometry::Correspondences;
use nalgebra::{Matrix3, Vector3};

/// Cells per side of the image-2 histogram.
const CELLS: usize = 8;
/// Most image-1 points averaged over.
const X1_MAX: usize = 2048;
/// Nodes of the midpoint rule along a line.
const NODES: usize = 32;

/// The data's marginals.
pub struct Empirical {
    /// Every match's image-1 point.
    x1: Vec<Vector3<f64>>,
    /// Every match's image-2 cell.
    cells: Vec<usize>,
    /// Matches per cell.
    counts: Vec<usize>,
    image: ImageRect,
    /// Leave the group's own matches out of the marginals.
    leave_out: bool,
}

impl Empirical {
    pub fn new(points: &Correspondences, image: &ImageRect, leave_out: bool) -> Self {
        let n = points.len();
        let x1 = (0..n)
            .map(|i| {
                let p = points.point1(i);
                Vector3::new(p[0], p[1], 1.0)
            })
            .collect();
        let cells: Vec<usize> = (0..n).map(|i| cell(image, points.point2(i))).collect();
        let mut counts = vec![0usize; CELLS * CELLS];
        for &c in &cells {
            counts[c] += 1;
        }
        Self {
            x1,
            cells,
            counts,
            image: *image,
            leave_out,
        }
    }

    /// The background of `f` under these marginals, without the matches
    /// of `group` when leaving out.
    pub fn background(&self, f: &Matrix3<f64>, group: &[usize]) -> Background {
        let norm = f.norm();
        if !(norm.is_finite() && norm > 0.0) {
            return Background::from_slopes(vec![f64::INFINITY]);
        }
        let n = self.x1.len();
        let mut inside = vec![false; n];
        let mut counts = self.counts.clone();
        if self.leave_out {
            for &m in group {
                inside[m] = true;
                counts[self.cells[m]] -= 1;
            }
        }
        let rest = n - if self.leave_out { group.len() } else { 0 };
        let [w, h] = self.image.sides();
        let area = w * h / (CELLS * CELLS) as f64;
        let total = (rest + CELLS * CELLS) as f64;
        let density: Vec<f64> = counts
            .iter()
            .map(|&c| (c + 1) as f64 / total / area)
            .collect();
        let stride = rest.div_ceil(X1_MAX).max(1);
        let f = f / norm;
        let ft = f.transpose();
        let slopes = (0..n)
            .filter(|&m| !inside[m])
            .step_by(stride)
            .map(|m| self.slope(&f, &ft, &self.x1[m], &density))
            .collect();
        Background::from_slopes(slopes)
    }

    fn slope(
        &self,
        f: &Matrix3<f64>,
        ft: &Matrix3<f64>,
        x1: &Vector3<f64>,
        density: &[f64],
    ) -> f64 {
        let l = f * x1;
        let g1 = l.x * l.x + l.y * l.y;
        if g1.is_nan() || g1 <= f64::MIN_POSITIVE {
            return f64::INFINITY;
        }
        let Some((p, q)) = clip(&l, g1, &self.image) else {
            return 0.0;
        };
        let step = (q - p) / NODES as f64;
        let ds = step.norm();
        let integral: f64 = (0..NODES)
            .map(|k| {
                let x2 = p + step * (k as f64 + 0.5);
                let m = ft * Vector3::new(x2.x, x2.y, 1.0);
                let d = density[cell(&self.image, [x2.x, x2.y])];
                d * (1.0 + (m.x * m.x + m.y * m.y) / g1).sqrt()
            })
            .sum::<f64>()
            * ds;
        2.0 * integral
    }
}

/// The histogram cell of `p` (points outside go to the nearest cell).
fn cell(image: &ImageRect, p: [f64; 2]) -> usize {
    let [w, h] = image.sides();
    let ix = (((p[0] - image.min[0]) / w * CELLS as f64).floor().max(0.0) as usize).min(CELLS - 1);
    let iy = (((p[1] - image.min[1]) / h * CELLS as f64).floor().max(0.0) as usize).min(CELLS - 1);
    iy * CELLS + ix
}
