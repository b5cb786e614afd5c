//! Gauss–Newton polish of a root of ten polynomial equations in three
//! unknowns (the five-point constraint system, src/essential_system.rs).

/// A system of ten polynomial equations in three unknowns that can be
/// evaluated with its Jacobian (the constraint systems of the minimal
/// solvers).
pub(crate) trait Equations {
    /// For each equation at `p`: its value, its gradient, and `Σ |term|`
    /// (the scale against which the value's rounding error is judged).
    fn evaluate(&self, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10];
}

/// Relative residual of an evaluated system:
/// `‖(e_k(p))_k‖ / Σ_k Σ |terms of e_k(p)|` (0 at an exact root, of order
/// `ε` at a root computed in floating point).
fn relative_residual(values: &[(f64, [f64; 3], f64); 10]) -> f64 {
    let (mut r2, mut scale) = (0.0, 0.0);
    for (v, _, m) in values {
        r2 += v * v;
        scale += m;
    }
    if scale > 0.0 {
        r2.sqrt() / scale
    } else {
        0.0
    }
}

/// Up to `steps` Gauss–Newton steps on the overdetermined system
/// `equations(p) = 0` from `p`, each kept only if it lowers the relative
/// residual `‖(e_k(p))_k‖ / Σ_k Σ |terms of e_k(p)|`. Returns the polished
/// point and its residual.
pub(crate) fn polish_root(
    equations: &impl Equations,
    mut p: [f64; 3],
    steps: usize,
) -> ([f64; 3], f64) {
    let mut values = equations.evaluate(p);
    let mut residual = relative_residual(&values);
    for _ in 0..steps {
        let mut jac = nalgebra::SMatrix::<f64, 10, 3>::zeros();
        let mut r = nalgebra::SVector::<f64, 10>::zeros();
        for (k, (v, g, _)) in values.iter().enumerate() {
            r[k] = -v;
            for j in 0..3 {
                jac[(k, j)] = g[j];
            }
        }
        // Normal equations: the 3 × 3 Gram matrix of a Jacobian that is
        // well conditioned at a simple root.
        let Some(delta) = (jac.transpose() * jac).lu().solve(&(jac.transpose() * r)) else {
            break;
        };
        if !delta.iter().all(|v| v.is_finite()) {
            break;
        }
        let next = [p[0] + delta[0], p[1] + delta[1], p[2] + delta[2]];
        let next_values = equations.evaluate(next);
        let next_residual = relative_residual(&next_values);
        if next_residual.partial_cmp(&residual) != Some(std::cmp::Ordering::Less) {
            break;
        }
        p = next;
        values = next_values;
        residual = next_residual;
    }
    (p, residual)
}
