//! `sctl.segment` and its result, `sctl.Segmentation` (Algorithm 1 of the
//! thesis through `segmentation::segment`).

use crate::convert::{array1, from_json, matrix_array, pair, point_pairs, value_error};
use crate::interrupt::run_interruptible;
use crate::params::{params_from_kwargs, profile_from};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyUserWarning};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use segmentation::{Matches, Params, SegmentationError, StageTimings};
use std::ffi::CString;
use std::fmt::Write as _;

pyo3::create_exception!(
    sctl,
    SegmentationWarning,
    PyUserWarning,
    "Something suspicious in the input of ``sctl.segment``, which was still \
     segmented: points far outside the image, an image size given as \
     (height, width)."
);

/// The Python exception of a library error: `MemoryError` for the memory
/// bounds, `KeyboardInterrupt` for an interruption, `ValueError` otherwise.
fn segment_error(e: SegmentationError) -> PyErr {
    match e {
        SegmentationError::MemoryBound { .. } | SegmentationError::MemoryAvailable { .. } => {
            PyMemoryError::new_err(e.to_string())
        }
        SegmentationError::Interrupted => PyKeyboardInterrupt::new_err(e.to_string()),
        other => value_error(other.to_string()),
    }
}

/// `warnings.warn(message, sctl.SegmentationWarning)` at the caller's line.
fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let text = CString::new(message.replace('\0', " ")).expect("no NUL left");
    PyErr::warn(py, &py.get_type::<SegmentationWarning>(), &text, 1)
}

/// Segments point matches between two images of one camera into rigid
/// motions by T-Linkage. The default draws its hypotheses as essential
/// matrices from five-point samples at the focal prior (the one camera
/// enters the hypotheses; the best configuration measured). The thesis's
/// semi-calibrated T-Linkage (Algorithm 1 of "Two-View Motion Segmentation
/// with Semi-Calibrated Cameras via Hypothesis Filtering") is
/// ``method="semical", minimal_solver="eight-point"``.
///
/// Parameters
/// ----------
/// x1, x2 : array_like, shape (N, 2)
///     Matching points in image 1 and image 2, pixels (x right, y down).
/// image_size : (int, int)
///     Image size (width, height) in pixels.
/// principal_point : (float, float), optional
///     Principal point in pixels. Default: the image centre
///     ((W - 1) / 2, (H - 1) / 2).
/// focal_prior : float, optional
///     Prior focal length of the focal solvers (px). Default: max(W, H).
/// profile : str, default "default"
///     The named parameter set that gives every key not passed: "default"
///     (the defaults below: one configuration for 8 to 50 000 matches,
///     the motions chosen by their a-contrario significance) or "thesis"
///     (the thesis text's Algorithm 1: method="semical",
///     minimal_solver="eight-point"). The "fast" and "large" profiles of
///     earlier versions were folded into the default.
///     ``sctl.default_params(profile)`` lists its values.
/// seed : int, default 12345
///     Seed of the hypothesis sampling. The labels depend on the input, the
///     parameters and the seed only (not on the number of threads).
/// **params
///     Any key of the ``[pipeline]`` table, with the same name and default
///     (``sctl.default_params()`` lists them); each overrides the profile's.
///     The key table of the repository's README.md ("Parameter keys") and
///     the stub ``sctl/__init__.pyi`` list every key.
///
/// Returns
/// -------
/// Segmentation
///     ``labels`` (int32 array, 0, 1, ... per motion, -1 for outliers),
///     ``f_peak`` and ``focal_verdict``, ``motions``, ``outliers``, the hypothesis counts, the
///     stage ``timings`` and the ``clusters`` with their F.
///
/// Raises
/// ------
/// ValueError
///     For an unknown parameter or profile or a bad value (the message
///     names the key),
///     arrays of the wrong shape or with NaN, a coordinate beyond 1e6 px
///     (the message names the row and column), or fewer matches than one
///     minimal sample.
/// TypeError
///     For ``x1`` or ``x2`` None, or holding None (the message names it).
/// MemoryError
///     When the run would need more memory than ``max_memory_mb``, or by
///     default than the machine has available (the message gives both
///     figures and what to change).
/// KeyboardInterrupt
///     On Ctrl-C: the computation stops within a fraction of a second.
///
/// Warns
/// -----
/// SegmentationWarning
///     (a ``UserWarning``) for points far outside the image, or an
///     ``image_size`` that looks given as (height, width).
///
/// The computation releases the GIL.
#[pyfunction]
#[pyo3(
    signature = (x1, x2, image_size, *, principal_point=None, focal_prior=None, profile=None, **params),
    text_signature = "(x1, x2, image_size, *, principal_point=None, focal_prior=None, profile=\"default\", seed=12345, **params)"
)]
// One argument per keyword of the Python signature.
#[allow(clippy::too_many_arguments)]
pub fn segment(
    py: Python<'_>,
    x1: &Bound<'_, PyAny>,
    x2: &Bound<'_, PyAny>,
    image_size: &Bound<'_, PyAny>,
    principal_point: Option<&Bound<'_, PyAny>>,
    focal_prior: Option<&Bound<'_, PyAny>>,
    profile: Option<&Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<Segmentation> {
    let (p1, p2) = point_pairs(x1, x2)?;
    let size = crate::convert::image_size(image_size)?;
    let mut matches = Matches::new(&p1, &p2, size);
    if let Some(pp) = principal_point {
        matches = matches.with_principal_point(pair(pp, "principal_point")?);
    }
    if let Some(f) = focal_prior {
        let f: f64 = f
            .extract()
            .map_err(|_| value_error(format!("focal_prior: expected a number, got {f}")))?;
        matches = matches.with_focal_prior(f);
    }
    let params = params_from_kwargs(params, profile_from(profile)?)?;
    let result = run_interruptible(py, |cancel| {
        segmentation::segment_cancellable(&matches, &params, cancel)
    })?
    .map_err(segment_error)?;
    for warning in &result.warnings {
        warn(py, &warning.to_string())?;
    }
    Ok(Segmentation {
        labels: array1(py, result.labels.clone()).unbind(),
        principal_point: matches.principal_point,
        focal_prior: matches.focal_prior,
        image_size: size,
        params,
        result,
    })
}

/// The result of ``segment``: the labels and what is needed to trust them.
///
/// Every F (``clusters``) is in principal-point-centred pixel coordinates:
/// ``x2' F x1 = 0`` for ``x = (x - pp_x, y - pp_y, 1)``.
#[pyclass(frozen, module = "sctl")]
pub struct Segmentation {
    labels: Py<PyArray1<i32>>,
    principal_point: [f64; 2],
    focal_prior: f64,
    image_size: (u32, u32),
    params: Params,
    result: segmentation::Segmentation,
}

#[pymethods]
impl Segmentation {
    /// One label per match: 0, 1, ... for the motions, -1 for outliers (int32).
    #[getter]
    fn labels(&self, py: Python<'_>) -> Py<PyArray1<i32>> {
        self.labels.clone_ref(py)
    }

    /// f_peak, the consensus focal length (px) of the kept hypotheses
    /// (Eq. 37); None for the baseline or when no focal was estimated.
    #[getter]
    fn f_peak(&self) -> Option<f64> {
        self.result.f_peak()
    }

    /// Number of motions found (clusters after the size filter).
    #[getter]
    fn motions(&self) -> usize {
        self.result.clusters.len()
    }

    /// Number of matches labelled outlier (-1).
    #[getter]
    fn outliers(&self) -> usize {
        self.result.outliers()
    }

    /// Minimal samples drawn (M).
    #[getter]
    fn generated(&self) -> usize {
        self.result.counts.generated
    }

    /// Hypotheses that survived the 8-point fit and the refinement.
    #[getter]
    fn refined(&self) -> usize {
        self.result.counts.refined
    }

    /// Hypotheses that passed the local test (Eq. 36); ``refined`` for the baseline.
    #[getter]
    fn local_ok(&self) -> usize {
        self.result.counts.local_ok
    }

    /// Hypotheses that reached the clustering.
    #[getter]
    fn kept(&self) -> usize {
        self.result.counts.kept
    }

    /// Failed focal solves that left a hypothesis without focals.
    #[getter]
    fn focal_failures(&self) -> usize {
        self.result.counts.focal_failures
    }

    /// Hypotheses whose focals are the prior standing in for a failed solve.
    #[getter]
    fn focal_priors(&self) -> usize {
        self.result.counts.focal_priors
    }

    /// Wall time of each stage in seconds: sampling, refine, focal,
    /// consensus, preferences, clustering, cluster_fit, total.
    #[getter]
    fn timings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (name, value) in StageTimings::NAMES.iter().zip(self.result.timings.values()) {
            dict.set_item(name, value)?;
        }
        Ok(dict)
    }

    /// The motions as (label, size, F) tuples, F a 3 x 3 array (centred
    /// coordinates) or None when its 8-point fit is degenerate.
    #[getter]
    fn clusters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items = self
            .result
            .clusters
            .iter()
            .map(|c| (c.label, c.size, c.f.as_ref().map(|f| matrix_array(py, f))));
        PyList::new(py, items)
    }

    /// None, or why every match is an outlier.
    #[getter]
    fn degenerate(&self) -> Option<String> {
        self.result.degenerate.clone()
    }

    /// True when the focal filter kept every refined hypothesis because none
    /// passed the local test or none fell in the band.
    #[getter]
    fn consensus_fallback(&self) -> bool {
        self.result.consensus_fallback
    }

    /// The focal consensus against the focal prior: "plausible" (f_peak
    /// within 0.3-3 x the prior), "implausible", "none" (no hypothesis
    /// passed the local test), or None when no focal was estimated.
    #[getter]
    fn focal_verdict(&self) -> Option<&'static str> {
        match self.result.focal_verdict {
            segmentation::FocalVerdict::NotEstimated => None,
            v => Some(v.name()),
        }
    }

    /// The KDE focal consensus (Eq. 37) as a dict (f_peak, from_median,
    /// bandwidth, n, peaks as focal lengths, grid, density), or None.
    #[getter]
    fn consensus<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(c) = &self.result.consensus else {
            return Ok(None);
        };
        let dict = PyDict::new(py);
        dict.set_item("f_peak", c.f_peak)?;
        dict.set_item("from_median", c.from_median)?;
        dict.set_item("bandwidth", c.bandwidth)?;
        dict.set_item("n", c.n)?;
        let peaks: Vec<f64> = c.peaks.iter().map(|&i| c.grid[i]).collect();
        dict.set_item("peaks", array1(py, peaks))?;
        dict.set_item("grid", array1(py, c.grid.clone()))?;
        dict.set_item("density", array1(py, c.density.clone()))?;
        Ok(Some(dict))
    }

    /// The fate of each hypothesis, in sampling order: "degenerate",
    /// "refine-failed", "focal-failed", "local-test-failed", "outside-band"
    /// or "kept".
    #[getter]
    fn hypothesis_status(&self) -> Vec<&'static str> {
        self.result
            .hypotheses
            .iter()
            .map(|h| h.status.name())
            .collect()
    }

    /// (M, 2) array of each hypothesis's focal lengths (f1, f2) in px, NaN
    /// where none was estimated.
    #[getter]
    fn hypothesis_focals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let h = &self.result.hypotheses;
        Array2::from_shape_fn((h.len(), 2), |(i, j)| match h[i].focals {
            Some((f1, f2)) => [f1, f2][j],
            None => f64::NAN,
        })
        .into_pyarray(py)
    }

    /// The principal point used (px).
    #[getter]
    fn principal_point(&self) -> (f64, f64) {
        (self.principal_point[0], self.principal_point[1])
    }

    /// The focal prior used (px).
    #[getter]
    fn focal_prior(&self) -> f64 {
        self.focal_prior
    }

    /// The image size (width, height).
    #[getter]
    fn image_size(&self) -> (u32, u32) {
        self.image_size
    }

    /// The parameters used, as a dict of the ``segment`` keywords.
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.params)
    }

    fn __len__(&self) -> usize {
        self.result.labels.len()
    }

    fn __repr__(&self) -> String {
        let r = &self.result;
        let sizes: Vec<String> = r.clusters.iter().map(|c| c.size.to_string()).collect();
        let mut s = format!(
            "Segmentation(matches={}, motions={} [sizes {}], outliers={}, f_peak={}, \
             hypotheses kept {} of {} ({} refined), {:.3} s",
            r.labels.len(),
            r.clusters.len(),
            sizes.join(", "),
            r.outliers(),
            r.f_peak()
                .map_or("None".to_string(), |f| format!("{f:.1} px")),
            r.counts.kept,
            r.counts.generated,
            r.counts.refined,
            r.timings.total,
        );
        if let Some(reason) = &r.degenerate {
            let _ = write!(s, ", degenerate: {reason}");
        }
        s.push(')');
        s
    }
}
