//! IRLS-Tukey refinement of a fundamental-matrix hypothesis (step 3 of
//! Algorithm 1, Section 5.2.1 of the thesis).
//!
//! Starting from the minimal sample as the inlier set and an initial `F`,
//! each outer iteration
//! 1. takes the signed Sampson residuals `r_i` (square root of Eq. 23, see
//!    [`crate::sampson_distance_signed`]) of the current inliers under the
//!    current `F`;
//! 2. estimates their scale robustly, `σ = 1.4826 · median(|r − median(r)|)`
//!    (Eq. 34);
//! 3. weights them with Tukey's biweight (Eq. 33),
//!    `w_i = (1 − (r_i / (c σ))²)²` if `|r_i| ≤ c σ`, else 0, `c = 4.685`
//!    (unit weights when σ is 0 or not finite);
//! 4. refits `F` by the weighted 8-point on the current inliers
//!    ([`crate::eight_point_weighted`]: minimise `fᵀ Xᵀ W X f`, then rank 2);
//! 5. takes as new inliers all correspondences whose squared Sampson
//!    distance is `≤ min(thr², 4 (1.4826 · MAD_all)²)`, MAD_all the MAD of the
//!    signed residuals of all correspondences under the new `F` (the MAD term
//!    only when finite and positive);
//! 6. stops when the inlier set changed by less than `min_change` (1 %):
//!    `|old Δ new| / |old ∪ new| < min_change`;
//!
//! for at most `max_iters` (`irls_iters`, 5) iterations. Fewer than 8 inliers
//! is an error (the hypothesis is dropped).
//!
//! One rule the text leaves open: when the Tukey weights leave fewer than 8
//! correspondences with a positive weight, or a rank-deficient weighted
//! system, step 4 uses unit weights on the current inliers instead. This
//! happens on the first iteration from an exact 8-point fit, whose residuals
//! are rounding noise: with 8 matches the solution does not depend on the
//! (positive) weights anyway.
//!
//! # The reference code's variants
//!
//! The published code (`refine_F_nonlinear` in its `geometry.py`) differs in
//! four places; each is a field of [`IrlsParams`] whose default is the
//! text's behaviour above:
//! * [`IrlsParams::fit`] = [`IrlsFit::Plain`]: step 4 minimises `fᵀ Xᵀ W X f`
//!   in the given (principal-point-centred) pixel coordinates, without
//!   Hartley normalisation ([`crate::eight_point_weighted_plain`]), then
//!   rank 2;
//! * [`IrlsParams::unit_weight_fallback`] = false: step 4 always uses the
//!   Tukey weights; fewer than 8 positive weights or a null space of
//!   dimension > 1 ends the refinement with that error;
//! * [`IrlsParams::sigma_offset_px`] = 1e-12: step 2 uses
//!   `σ = 1.4826 · MAD + 10⁻¹²` px, so that residuals at the rounding
//!   level of an exact fit (below ~10⁻¹² px) keep positive weights;
//! * [`IrlsParams::polish`] = true: before step 1, `F` is polished on the
//!   sample by [`crate::polish_fundamental`] (PoseLib's
//!   `refine_fundamental`: Levenberg–Marquardt on the Cauchy-robust Sampson
//!   error, rank 2 by construction).
//!
//! [`IrlsParams::reference_code`] sets all four; the reference also starts
//! from the plain 8-point of the sample ([`crate::eight_point_plain`]).

use crate::eight_point::{fit_normalized, fit_plain, MIN_POINTS};
use crate::mad::{mad_below, mad_by_keys};
pub use crate::mad::{median_absolute_deviation, median_in_place};
use crate::polish::polish_at;
use crate::sampson::sampson_residuals_signed_at;
use crate::{sampson_residuals_signed, Correspondences, GeometryError};
use nalgebra::Matrix3;

mod params;
pub use params::{IrlsFit, IrlsParams, MAD_TO_SIGMA};

/// A refined hypothesis.
#[derive(Debug, Clone, PartialEq)]
pub struct RefinedModel {
    /// The refined fundamental matrix: rank 2, unit Frobenius norm.
    pub f: Matrix3<f64>,
    /// Inlier mask over all correspondences (`inliers[i]` is true when match
    /// `i` is an inlier of `f` by step 5), length N.
    pub inliers: Vec<bool>,
    /// Number of outer iterations run (1 ..= `max_iters`).
    pub iterations: usize,
}

impl RefinedModel {
    /// Number of inliers.
    pub fn inlier_count(&self) -> usize {
        self.inliers.iter().filter(|&&b| b).count()
    }

    /// Indices of the inliers, increasing.
    pub fn inlier_indices(&self) -> Vec<usize> {
        (0..self.inliers.len())
            .filter(|&i| self.inliers[i])
            .collect()
    }
}

/// The result of [`IrlsWorkspace::run`]; the inlier set itself stays in the
/// workspace ([`IrlsWorkspace::inlier_mask`], [`IrlsWorkspace::inlier_indices`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IrlsSummary {
    /// The refined fundamental matrix: rank 2, unit Frobenius norm.
    pub f: Matrix3<f64>,
    /// Number of outer iterations run (1 ..= `max_iters`).
    pub iterations: usize,
    /// Number of inliers of `f`.
    pub inlier_count: usize,
}

/// Scratch buffers for IRLS-Tukey refinement, reused across calls so that a
/// refinement allocates nothing once the buffers have grown to N.
///
/// ```
/// use geometry::{Correspondences, IrlsParams, IrlsWorkspace};
/// use nalgebra::{Matrix3, Vector3};
/// // 30 matches of a rigid scene (rotation about y, translation) with about
/// // ±0.3 px of noise, and 5 gross outliers.
/// let (c, s) = (0.1f64.cos(), 0.1f64.sin());
/// let r = Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
/// let t = Vector3::new(1.0, 0.2, 0.1);
/// let (mut p1, mut p2) = (vec![], vec![]);
/// for i in 0..30 {
///     let x = Vector3::new((i % 6) as f64 - 2.5, (i / 6) as f64 - 2.0, 5.0 + (i * 7 % 5) as f64);
///     let y = r * x + t;
///     let noise = 0.3 * (i as f64 * 2.3).sin();
///     p1.push([800.0 * x.x / x.z, 800.0 * x.y / x.z]);
///     p2.push([800.0 * y.x / y.z + noise, 800.0 * y.y / y.z - noise]);
/// }
/// for i in 0..5 {
///     p1.push([40.0 * i as f64, -100.0]);
///     p2.push([-90.0, 33.0 * i as f64]);
/// }
/// let points = Correspondences::new(&p1, &p2).unwrap();
/// let mut workspace = IrlsWorkspace::new();
/// let sample = [0, 4, 9, 13, 17, 20, 26, 29];
/// let refined = workspace.run(&points, &sample, None, &IrlsParams::default()).unwrap();
/// // The outliers are rejected; the inliers are those within the scale bound.
/// assert!(workspace.inlier_indices().iter().all(|&i| i < 30));
/// assert!(refined.inlier_count >= 20);
/// ```
#[derive(Debug, Clone, Default)]
pub struct IrlsWorkspace {
    /// Inlier mask over all correspondences.
    mask: Vec<bool>,
    /// Indices of the current inliers, increasing.
    inliers: Vec<usize>,
    /// Scratch of [`collect_inliers`](Self::collect_inliers): one slot per
    /// correspondence (it only grows, so that it is not refilled).
    positions: Vec<usize>,
    /// Signed Sampson residuals of all correspondences under the current F.
    residuals_all: Vec<f64>,
    /// Signed residuals of the current inliers.
    residuals_in: Vec<f64>,
    /// Tukey weights of the current inliers.
    weights: Vec<f64>,
    /// Scratch for the medians: order-preserving integer keys.
    keys: Vec<u64>,
    /// Scratch for the polish: the sample's normalised matches.
    polish: Vec<[f64; 4]>,
}

impl IrlsWorkspace {
    /// An empty workspace; buffers grow on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// Inlier mask of the last successful [`run`](Self::run) (length N).
    pub fn inlier_mask(&self) -> &[bool] {
        &self.mask
    }

    /// Increasing inlier indices of the last successful [`run`](Self::run).
    pub fn inlier_indices(&self) -> &[usize] {
        &self.inliers
    }

    /// IRLS-Tukey refinement (steps 3a–3f, Eqs. 23, 33, 34) of the hypothesis
    /// fitted to `sample` (indices into `points`, at least 8), starting from
    /// `initial` or, when `None`, from the 8-point of the sample in the
    /// variant of `params.fit` (Hartley-normalised by default). See the
    /// [module documentation](self) for the iteration and the variants.
    ///
    /// Errors: invalid `params` ([`GeometryError::InvalidParameter`]); fewer
    /// than 8 sample indices ([`GeometryError::TooFewPoints`]); an index out
    /// of range; a non-finite or zero `initial`; a degenerate sample or
    /// inlier set ([`GeometryError::Degenerate`],
    /// [`GeometryError::TooFewWeightedPoints`]; with
    /// `unit_weight_fallback = false` also a degenerate weighted system);
    /// fewer than 8 inliers after an iteration
    /// ([`GeometryError::TooFewInliers`]).
    pub fn run(
        &mut self,
        points: &Correspondences,
        sample: &[usize],
        initial: Option<&Matrix3<f64>>,
        params: &IrlsParams,
    ) -> Result<IrlsSummary, GeometryError> {
        let mut f = self.start(points, sample, initial, params)?;
        let mut iterations = 0;
        for iteration in 1..=params.max_iters {
            iterations = iteration;
            f = self.weighted_refit(points, params)?;
            // After the last iteration the change decides nothing and is
            // not counted.
            let measure = iteration < params.max_iters;
            let change = self.update_inliers(points, &f, params, iteration, measure)?;
            // 3f: converged when the set changed by less than min_change.
            let converged = change.map_or(true, |c| {
                (c.changed as f64) < params.min_change * c.union as f64
            });
            if converged {
                break;
            }
            // 3a of the next iteration: residuals of the new inliers.
            self.residuals_in.clear();
            let all = &self.residuals_all;
            self.residuals_in
                .extend(self.inliers.iter().map(|&i| all[i]));
        }
        Ok(IrlsSummary {
            f,
            iterations,
            inlier_count: self.inliers.len(),
        })
    }

    /// The start of [`run`](Self::run): checks, the initial model, the
    /// sample as the inlier set (polished first when asked) and its
    /// residuals (step 3a).
    fn start(
        &mut self,
        points: &Correspondences,
        sample: &[usize],
        initial: Option<&Matrix3<f64>>,
        params: &IrlsParams,
    ) -> Result<Matrix3<f64>, GeometryError> {
        params.validate()?;
        let n = points.len();
        if sample.len() < MIN_POINTS {
            return Err(GeometryError::TooFewPoints {
                got: sample.len(),
                needed: MIN_POINTS,
            });
        }
        if let Some(&index) = sample.iter().find(|&&i| i >= n) {
            return Err(GeometryError::IndexOutOfRange { index, len: n });
        }
        let mut f = match initial {
            Some(f) => checked_initial(f)?,
            None => refit(params.fit, points, sample.iter().map(|&i| (i, 1.0)))?,
        };

        // Start: the inlier set is the sample (duplicates collapse).
        self.mask.clear();
        self.mask.resize(n, false);
        for &i in sample {
            self.mask[i] = true;
        }
        self.collect_inliers();
        if params.polish {
            f = polish_at(points, &self.inliers, &f, &mut self.polish)?.f;
        }
        self.residuals_in.resize(self.inliers.len(), 0.0);
        sampson_residuals_signed_at(&f, points, &self.inliers, &mut self.residuals_in);
        self.residuals_all.resize(n, 0.0);
        Ok(f)
    }

    /// Steps 3b–3d: the robust scale of the inlier residuals, their Tukey
    /// weights and the weighted 8-point on the current inliers.
    fn weighted_refit(
        &mut self,
        points: &Correspondences,
        params: &IrlsParams,
    ) -> Result<Matrix3<f64>, GeometryError> {
        // 3b-c: robust scale of the inlier residuals and Tukey weights.
        let sigma =
            MAD_TO_SIGMA * mad_by_keys(&self.residuals_in, &mut self.keys) + params.sigma_offset_px;
        self.weights.clear();
        if sigma.is_finite() && sigma > 0.0 {
            let cs = params.tukey_c * sigma;
            self.weights
                .extend(self.residuals_in.iter().map(|&r| tukey_weight(r / cs)));
        } else {
            self.weights.resize(self.inliers.len(), 1.0);
        }

        // 3d: weighted 8-point on the current inliers.
        let weighted = refit(
            params.fit,
            points,
            self.inliers
                .iter()
                .copied()
                .zip(self.weights.iter().copied()),
        );
        let f = match weighted {
            Ok(f) => f,
            Err(GeometryError::TooFewWeightedPoints { .. } | GeometryError::Degenerate(_))
                if params.unit_weight_fallback =>
            {
                refit(params.fit, points, self.inliers.iter().map(|&i| (i, 1.0)))?
            }
            Err(e) => return Err(e),
        };
        if let Some(k) = f.iter().position(|v| !v.is_finite()) {
            return Err(GeometryError::NonFiniteMatrix {
                row: k % 3,
                col: k / 3,
            });
        }
        Ok(f)
    }

    /// Step 3e: the new inlier set from the residuals of all
    /// correspondences to `f`, and how much it changed (`None` unless
    /// `measure`).
    fn update_inliers(
        &mut self,
        points: &Correspondences,
        f: &Matrix3<f64>,
        params: &IrlsParams,
        iteration: usize,
        measure: bool,
    ) -> Result<Option<InlierChange>, GeometryError> {
        let thr2 = params.thr_px * params.thr_px;
        sampson_residuals_signed(f, points, &mut self.residuals_all);
        // min(thr², 4σ²) is thr² whenever MAD ≥ thr / (2 · 1.4826); the
        // exact MAD is only needed below that (the margin covers rounding).
        let mad_limit = params.thr_px / (2.0 * MAD_TO_SIGMA) * (1.0 + 1e-12);
        let bound = match mad_below(&self.residuals_all, &mut self.keys, mad_limit) {
            Some(mad) => {
                let sigma_all = MAD_TO_SIGMA * mad;
                if sigma_all.is_finite() && sigma_all > 0.0 {
                    thr2.min(4.0 * sigma_all * sigma_all)
                } else {
                    thr2
                }
            }
            None => thr2,
        };
        let flags = self.mask.iter_mut().zip(&self.residuals_all);
        let change = if measure {
            let mut change = InlierChange::default();
            for (inlier, &r) in flags {
                let new = r * r <= bound;
                change.changed += usize::from(new != *inlier);
                change.union += usize::from(new || *inlier);
                *inlier = new;
            }
            Some(change)
        } else {
            flags.for_each(|(inlier, &r)| *inlier = r * r <= bound);
            None
        };
        self.collect_inliers();
        if self.inliers.len() < MIN_POINTS {
            return Err(GeometryError::TooFewInliers {
                got: self.inliers.len(),
                needed: MIN_POINTS,
                iteration,
            });
        }
        Ok(change)
    }

    /// [`run`](Self::run), returning the inlier mask as an owned
    /// [`RefinedModel`].
    pub fn refine(
        &mut self,
        points: &Correspondences,
        sample: &[usize],
        initial: Option<&Matrix3<f64>>,
        params: &IrlsParams,
    ) -> Result<RefinedModel, GeometryError> {
        let summary = self.run(points, sample, initial, params)?;
        Ok(RefinedModel {
            f: summary.f,
            inliers: self.mask.clone(),
            iterations: summary.iterations,
        })
    }

    /// The indices of the mask's set flags, increasing, into `inliers`
    /// (found without a branch: each index is stored and kept when set).
    fn collect_inliers(&mut self) {
        let n = self.mask.len();
        if self.positions.len() < n {
            self.positions.resize(n, 0);
        }
        let mut m = 0;
        for (i, &set) in self.mask.iter().enumerate() {
            self.positions[m] = i;
            m += usize::from(set);
        }
        self.inliers.clear();
        self.inliers.extend_from_slice(&self.positions[..m]);
    }
}

/// IRLS-Tukey refinement (step 3 of Algorithm 1; Eqs. 23, 33, 34) with a
/// fresh [`IrlsWorkspace`]; see [`IrlsWorkspace::run`] for the arguments and
/// errors. Calls in a loop should reuse one workspace instead.
///
/// ```
/// use geometry::{refine_irls_tukey, Correspondences, IrlsParams};
/// use nalgebra::{Matrix3, Vector3};
/// let (c, s) = (0.2f64.cos(), 0.2f64.sin());
/// let r = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
/// let t = Vector3::new(0.5, -1.0, 0.2);
/// let (mut p1, mut p2) = (vec![], vec![]);
/// for i in 0..40 {
///     let x = Vector3::new((i % 8) as f64 - 3.5, (i / 8) as f64 - 2.0, 6.0 + (i * 5 % 7) as f64);
///     let y = r * x + t;
///     let noise = 0.4 * (i as f64 * 1.7).cos();
///     p1.push([700.0 * x.x / x.z + noise, 700.0 * x.y / x.z]);
///     p2.push([700.0 * y.x / y.z, 700.0 * y.y / y.z + noise]);
/// }
/// p2[3] = [250.0, 250.0]; // one gross outlier
/// let points = Correspondences::new(&p1, &p2).unwrap();
/// let sample = [0, 5, 11, 16, 22, 27, 33, 38];
/// let model = refine_irls_tukey(&points, &sample, None, &IrlsParams::default()).unwrap();
/// assert!(!model.inliers[3]);
/// assert!(model.inlier_count() >= 30 && model.iterations <= 5);
/// ```
pub fn refine_irls_tukey(
    points: &Correspondences,
    sample: &[usize],
    initial: Option<&Matrix3<f64>>,
    params: &IrlsParams,
) -> Result<RefinedModel, GeometryError> {
    IrlsWorkspace::new().refine(points, sample, initial, params)
}

/// Tukey's biweight (Eq. 33) of the standardised residual `u = r / (c σ)`:
/// `(1 − u²)²` for `|u| ≤ 1`, else 0.
#[inline]
pub fn tukey_weight(u: f64) -> f64 {
    if u.abs() <= 1.0 {
        let v = 1.0 - u * u;
        v * v
    } else {
        0.0
    }
}

/// The weighted 8-point of step 3d in the frame `fit` selects, on
/// `(index, weight)` pairs.
fn refit<I>(fit: IrlsFit, points: &Correspondences, items: I) -> Result<Matrix3<f64>, GeometryError>
where
    I: Iterator<Item = (usize, f64)> + Clone,
{
    match fit {
        IrlsFit::Normalized => fit_normalized(points, items),
        IrlsFit::Plain => fit_plain(points, items),
    }
}

/// Checks a caller-supplied starting matrix: finite and non-zero.
fn checked_initial(f: &Matrix3<f64>) -> Result<Matrix3<f64>, GeometryError> {
    for row in 0..3 {
        for col in 0..3 {
            if !f[(row, col)].is_finite() {
                return Err(GeometryError::NonFiniteMatrix { row, col });
            }
        }
    }
    if f.iter().all(|&v| v == 0.0) {
        return Err(GeometryError::ZeroMatrix);
    }
    Ok(*f)
}

/// How much one IRLS iteration changed the inlier set (step 3f).
#[derive(Debug, Default, Clone, Copy)]
struct InlierChange {
    /// Correspondences whose inlier flag flipped.
    changed: usize,
    /// Correspondences that are inliers before or after.
    union: usize,
}

#[cfg(test)]
mod tests;
