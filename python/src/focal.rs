//! `sctl.focals_from_fundamental` (the robust Kocur–Kyselica–Kukelova solver
//! with the reference's multi-start rule) and `sctl.bougnoux`, over one F
//! or a stack (docs/method.md step 4).

use crate::convert::{array1, matrices, pair, points_array, to_json, value_error};
use crate::params::from_object;
use focal::{robust_focals_multi_start, FocalEstimate, FocalFailure, OnFailure};
use nalgebra::Matrix3;
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use segmentation::{Params, WeightSets};
use serde_json::Map;

/// The solver's options as `focals_from_fundamental` takes them.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SolverOptions {
    focal_prior: f64,
    weight_sets: WeightSets,
    max_iters: usize,
    on_failure: OnFailure,
}

/// The options from the keyword values, checked as the pipeline checks
/// them (`Params::validate`), each error naming its key.
fn solver_options(
    focal_prior: &Bound<'_, PyAny>,
    weight_sets: &Bound<'_, PyAny>,
    max_iters: &Bound<'_, PyAny>,
    on_failure: &Bound<'_, PyAny>,
) -> PyResult<SolverOptions> {
    let mut object = Map::new();
    for (key, value) in [
        ("focal_prior", focal_prior),
        ("weight_sets", weight_sets),
        ("max_iters", max_iters),
        ("on_failure", on_failure),
    ] {
        object.insert(key.to_string(), to_json(value, key)?);
    }
    let options: SolverOptions = from_object(object)?;
    if !(options.focal_prior.is_finite() && options.focal_prior > 0.0) {
        return Err(value_error(format!(
            "invalid parameter `focal_prior`: must be a finite number > 0, got {}",
            options.focal_prior
        )));
    }
    Params::default()
        .with(|q| {
            q.focal.weight_sets = options.weight_sets.clone();
            q.focal.max_iters = options.max_iters;
        })
        .validate()
        .map_err(|e| value_error(e.to_string()))?;
    Ok(options)
}

/// A short name of a solver failure, as `status` reports it.
fn failure_name(failure: &FocalFailure) -> &'static str {
    match failure {
        FocalFailure::InvalidMatrix => "invalid-matrix",
        FocalFailure::InvalidParameter { .. } => "invalid-parameter",
        FocalFailure::NoRealFocal => "no-real-focal",
        FocalFailure::Singular => "singular",
        FocalFailure::NoRealSolution { .. } => "no-real-solution",
        FocalFailure::NonFinite { .. } => "non-finite",
        FocalFailure::NoConvergence { .. } => "no-convergence",
        FocalFailure::NoWeightSets => "no-weight-sets",
    }
}

/// One answer as (estimate, iterations, status): NaN focals for a failure.
fn answer(result: Result<FocalEstimate, FocalFailure>) -> (FocalEstimate, usize, &'static str) {
    match result {
        Ok(e) => (e, e.iterations, if e.from_prior { "prior" } else { "ok" }),
        Err(failure) => (
            FocalEstimate {
                f1: f64::NAN,
                f2: f64::NAN,
                pp1: [f64::NAN; 2],
                pp2: [f64::NAN; 2],
                iterations: failure.iterations(),
                from_prior: false,
            },
            failure.iterations(),
            failure_name(&failure),
        ),
    }
}

/// Focal lengths of both views from a fundamental matrix: the robust
/// iterative solver of Kocur, Kyselica and Kukelova (CVPR 2024), run once
/// per weight set, the answer with the fewest iterations kept (ties: the
/// smallest |f1 - f2|, then the earlier set), as in docs/method.md step 4.
///
/// Parameters
/// ----------
/// F : array_like, shape (3, 3) or (K, 3, 3)
///     Fundamental matrices in pixel coordinates with the principal points
///     at the origin (``x2' F x1 = 0``).
/// focal_prior : float
///     Prior focal length of both views (px), e.g. max(W, H).
/// weight_sets : "adelaidermf", "hopef" or list of [w_f1, w_pp1, w_f2, w_pp2]
///     The multi-start weight sets (4 or 6 of the reference code, or your own).
/// max_iters : int, default 100
///     Iteration cap of each solve.
/// on_failure : "report" or "prior", default "report"
///     "prior": a failed solve answers the prior (status "prior").
///
/// Returns
/// -------
/// dict
///     ``f1``, ``f2`` (px; NaN on failure), ``pp1``, ``pp2`` (principal
///     points relative to the origin, px), ``iterations`` and ``status``
///     ("ok", "prior" or the failure: "no-real-solution", "non-finite",
///     "no-convergence", "invalid-matrix"). For one F: scalars and (2,)
///     arrays; for a stack: arrays with a leading K axis and a list of
///     statuses.
///
/// The computation releases the GIL; a stack is solved in parallel.
#[pyfunction]
#[pyo3(
    signature = (F, *, focal_prior, weight_sets=None, max_iters=None, on_failure=None),
    text_signature = "(F, *, focal_prior, weight_sets='adelaidermf', max_iters=100, on_failure='report')"
)]
#[allow(non_snake_case)]
pub fn focals_from_fundamental<'py>(
    py: Python<'py>,
    F: &Bound<'py, PyAny>,
    focal_prior: &Bound<'py, PyAny>,
    weight_sets: Option<&Bound<'py, PyAny>>,
    max_iters: Option<&Bound<'py, PyAny>>,
    on_failure: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (stack, single) = matrices(F, "F")?;
    let adelaidermf = pyo3::types::PyString::new(py, "adelaidermf").into_any();
    let hundred = 100_i64.into_pyobject(py)?.into_any();
    let report = pyo3::types::PyString::new(py, "report").into_any();
    let options = solver_options(
        focal_prior,
        weight_sets.unwrap_or(&adelaidermf),
        max_iters.unwrap_or(&hundred),
        on_failure.unwrap_or(&report),
    )?;
    let sets = options.weight_sets.sets();
    let answers: Vec<_> = py.detach(|| {
        stack
            .par_iter()
            .map(|f| {
                answer(robust_focals_multi_start(
                    f,
                    options.focal_prior,
                    &sets,
                    options.max_iters,
                    options.on_failure,
                ))
            })
            .collect()
    });
    let dict = PyDict::new(py);
    if single {
        let (e, iterations, status) = answers[0];
        dict.set_item("f1", e.f1)?;
        dict.set_item("f2", e.f2)?;
        dict.set_item("pp1", array1(py, e.pp1.to_vec()))?;
        dict.set_item("pp2", array1(py, e.pp2.to_vec()))?;
        dict.set_item("iterations", iterations)?;
        dict.set_item("status", status)?;
    } else {
        let column = |g: fn(&FocalEstimate) -> f64| answers.iter().map(|a| g(&a.0)).collect();
        dict.set_item("f1", array1::<f64>(py, column(|e| e.f1)))?;
        dict.set_item("f2", array1::<f64>(py, column(|e| e.f2)))?;
        let pps = |g: fn(&FocalEstimate) -> [f64; 2]| {
            points_array(py, &answers.iter().map(|a| g(&a.0)).collect::<Vec<_>>())
        };
        dict.set_item("pp1", pps(|e| e.pp1))?;
        dict.set_item("pp2", pps(|e| e.pp2))?;
        let iterations: Vec<i64> = answers.iter().map(|a| a.1 as i64).collect();
        dict.set_item("iterations", array1(py, iterations))?;
        let status: Vec<&str> = answers.iter().map(|a| a.2).collect();
        dict.set_item("status", status)?;
    }
    Ok(dict)
}

/// Bougnoux's focal lengths of one F as `[f1, f2]`, NaN where the formula
/// has no real answer.
fn bougnoux_pair(f: &Matrix3<f64>, pp1: [f64; 2], pp2: [f64; 2]) -> [f64; 2] {
    focal::bougnoux_per_image(f, pp1, pp2).map(|r| r.unwrap_or(f64::NAN))
}

/// Bougnoux's closed-form focal lengths (Bougnoux 1998) of a fundamental
/// matrix or a stack of them.
///
/// Parameters
/// ----------
/// F : array_like, shape (3, 3) or (K, 3, 3)
///     Fundamental matrices, ``x2' F x1 = 0``, pixel coordinates.
/// pp1, pp2 : (float, float), default (0, 0)
///     Principal points of image 1 and image 2 in the coordinates of F.
///
/// Returns
/// -------
/// numpy.ndarray, shape (2,) or (K, 2)
///     (f1, f2) in px; NaN where f**2 <= 0 or the formula is singular.
#[pyfunction]
#[pyo3(
    signature = (F, pp1=None, pp2=None),
    text_signature = "(F, pp1=(0.0, 0.0), pp2=(0.0, 0.0))"
)]
#[allow(non_snake_case)]
pub fn bougnoux<'py>(
    py: Python<'py>,
    F: &Bound<'py, PyAny>,
    pp1: Option<&Bound<'py, PyAny>>,
    pp2: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (stack, single) = matrices(F, "F")?;
    let pp = |p: Option<&Bound<'py, PyAny>>, name| p.map_or(Ok([0.0; 2]), |p| pair(p, name));
    let (pp1, pp2) = (pp(pp1, "pp1")?, pp(pp2, "pp2")?);
    let answers: Vec<[f64; 2]> = stack.iter().map(|f| bougnoux_pair(f, pp1, pp2)).collect();
    Ok(if single {
        array1(py, answers[0].to_vec()).into_any()
    } else {
        Array2::from_shape_fn((answers.len(), 2), |(k, j)| answers[k][j])
            .into_pyarray(py)
            .into_any()
    })
}
