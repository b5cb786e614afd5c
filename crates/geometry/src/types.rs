//! Checked input types: a set of point correspondences and a fundamental matrix.

use crate::GeometryError;
use nalgebra::Matrix3;

/// N point correspondences `(x1, y1) ↔ (x2, y2)` in pixels, stored as four
/// coordinate columns so that the batch distance loops read memory linearly.
///
/// Every coordinate is finite: the constructors check it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Correspondences {
    x1: Vec<f64>,
    y1: Vec<f64>,
    x2: Vec<f64>,
    y2: Vec<f64>,
}

impl Correspondences {
    /// Builds a set from two N × 2 pixel arrays (image 1, image 2).
    ///
    /// Errors on a length mismatch or a non-finite coordinate.
    ///
    /// ```
    /// use geometry::Correspondences;
    /// let c = Correspondences::new(&[[0.0, 1.0], [2.0, 3.0]], &[[1.0, 1.0], [2.0, 2.0]]).unwrap();
    /// assert_eq!(c.len(), 2);
    /// assert_eq!(c.point2(1), [2.0, 2.0]);
    /// assert!(Correspondences::new(&[[f64::NAN, 0.0]], &[[0.0, 0.0]]).is_err());
    /// ```
    pub fn new(points1: &[[f64; 2]], points2: &[[f64; 2]]) -> Result<Self, GeometryError> {
        if points1.len() != points2.len() {
            return Err(GeometryError::LengthMismatch {
                points1: points1.len(),
                points2: points2.len(),
            });
        }
        let column = |pts: &[[f64; 2]], k: usize| pts.iter().map(|p| p[k]).collect::<Vec<_>>();
        Self::from_columns(
            column(points1, 0),
            column(points1, 1),
            column(points2, 0),
            column(points2, 1),
        )
    }

    /// Builds a set from the four coordinate columns `x1, y1, x2, y2`.
    pub fn from_columns(
        x1: Vec<f64>,
        y1: Vec<f64>,
        x2: Vec<f64>,
        y2: Vec<f64>,
    ) -> Result<Self, GeometryError> {
        if x1.len() != y1.len() || x2.len() != y2.len() || x1.len() != x2.len() {
            return Err(GeometryError::LengthMismatch {
                points1: x1.len().min(y1.len()),
                points2: x2.len().min(y2.len()),
            });
        }
        for (field, col) in [("x1", &x1), ("y1", &y1), ("x2", &x2), ("y2", &y2)] {
            if let Some(index) = col.iter().position(|v| !v.is_finite()) {
                return Err(GeometryError::NonFinite { field, index });
            }
        }
        Ok(Self { x1, y1, x2, y2 })
    }

    /// Number of correspondences N.
    pub fn len(&self) -> usize {
        self.x1.len()
    }

    /// True when the set holds no correspondence.
    pub fn is_empty(&self) -> bool {
        self.x1.is_empty()
    }

    /// The point of correspondence `i` in image 1. Panics if `i >= len()`.
    pub fn point1(&self, i: usize) -> [f64; 2] {
        [self.x1[i], self.y1[i]]
    }

    /// The point of correspondence `i` in image 2. Panics if `i >= len()`.
    pub fn point2(&self, i: usize) -> [f64; 2] {
        [self.x2[i], self.y2[i]]
    }

    /// The coordinate columns `(x1, y1, x2, y2)`.
    pub fn columns(&self) -> (&[f64], &[f64], &[f64], &[f64]) {
        (&self.x1, &self.y1, &self.x2, &self.y2)
    }

    /// The correspondences at `indices`, in that order.
    pub fn subset(&self, indices: &[usize]) -> Result<Self, GeometryError> {
        let len = self.len();
        if let Some(&index) = indices.iter().find(|&&i| i >= len) {
            return Err(GeometryError::IndexOutOfRange { index, len });
        }
        let pick = |col: &[f64]| indices.iter().map(|&i| col[i]).collect::<Vec<_>>();
        Ok(Self {
            x1: pick(&self.x1),
            y1: pick(&self.y1),
            x2: pick(&self.x2),
            y2: pick(&self.y2),
        })
    }

    /// The same correspondences with `offset1` subtracted from every image-1
    /// point and `offset2` from every image-2 point (e.g. moving the principal
    /// point to the origin).
    pub fn shifted(&self, offset1: [f64; 2], offset2: [f64; 2]) -> Self {
        let sub = |col: &[f64], o: f64| col.iter().map(|v| v - o).collect::<Vec<_>>();
        Self {
            x1: sub(&self.x1, offset1[0]),
            y1: sub(&self.y1, offset1[1]),
            x2: sub(&self.x2, offset2[0]),
            y2: sub(&self.y2, offset2[1]),
        }
    }
}

/// A fundamental matrix `F` (`x2ᵀ F x1 = 0`): finite and non-zero.
///
/// Rank 2 is not enforced here; the estimators return rank-2 matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FundamentalMatrix(Matrix3<f64>);

impl FundamentalMatrix {
    /// Checks that every entry is finite and the matrix is not zero.
    ///
    /// ```
    /// use geometry::FundamentalMatrix;
    /// use nalgebra::Matrix3;
    /// assert!(FundamentalMatrix::new(Matrix3::zeros()).is_err());
    /// let f = FundamentalMatrix::new(Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0)).unwrap();
    /// assert_eq!(f.matrix()[(1, 2)], -1.0);
    /// ```
    pub fn new(matrix: Matrix3<f64>) -> Result<Self, GeometryError> {
        for row in 0..3 {
            for col in 0..3 {
                if !matrix[(row, col)].is_finite() {
                    return Err(GeometryError::NonFiniteMatrix { row, col });
                }
            }
        }
        if matrix.norm() == 0.0 {
            return Err(GeometryError::ZeroMatrix);
        }
        Ok(Self(matrix))
    }

    /// The 3 × 3 matrix.
    pub fn matrix(&self) -> &Matrix3<f64> {
        &self.0
    }

    /// `F / ‖F‖_Frobenius`.
    pub fn normalized(&self) -> Matrix3<f64> {
        self.0 / self.0.norm()
    }
}
