//! Agreement with PoseLib on ../shared/fixtures/focal/poselib_focals.csv
//! (docs/method.md step 4): Bougnoux's closed form and the robust iterative
//! solver.

mod support;

use std::collections::BTreeMap;

use focal::{
    bougnoux_per_image, relative_kruppa_residual, robust_focals, RobustFocalParams,
    KRUPPA_TOLERANCE,
};
use support::load;

#[test]
fn bougnoux_matches_poselib() {
    let rows = load();
    assert_eq!(rows.len(), 140);
    let mut compared = 0;
    let mut worst = 0.0_f64;
    for row in &rows {
        let got = bougnoux_per_image(&row.f, [0.0, 0.0], [0.0, 0.0]);
        for (i, (result, &want)) in got.iter().zip(row.bougnoux.iter()).enumerate() {
            match *result {
                Ok(v) => {
                    assert!(
                        want.is_finite(),
                        "row {} image {}: got {v}, PoseLib has no focal",
                        row.id,
                        i + 1
                    );
                    let rel = (v - want).abs() / want;
                    assert!(rel <= 1e-8, "row {} image {}: {v} vs {want}", row.id, i + 1);
                    worst = worst.max(rel);
                    compared += 1;
                }
                Err(e) => assert!(
                    !want.is_finite(),
                    "row {} image {}: {e}, PoseLib gives {want}",
                    row.id,
                    i + 1
                ),
            }
        }
    }
    println!(
        "Bougnoux vs PoseLib: {compared} focal values, largest relative difference {worst:.2e}"
    );
    assert!(compared >= 150, "only {compared} focal values compared");
}

#[test]
fn robust_solver_agrees_with_poselib_on_feasible_rows() {
    let rows = load();
    let mut per_kind: BTreeMap<String, (usize, usize, usize)> = BTreeMap::new();
    let (mut total, mut agree, mut same_iters) = (0, 0, 0);
    let mut report = String::new();
    for row in rows.iter().filter(|r| r.status == "feasible") {
        let params = RobustFocalParams {
            f_prior: row.f_prior,
            weights: row.weights,
            max_iters: row.max_iters,
        };
        let got = robust_focals(&row.f, &params);
        let ok = match &got {
            Ok(e) => {
                let within = |a: f64, b: f64| (a.abs() - b.abs()).abs() <= 0.01 * b.abs();
                within(e.f1, row.iter_f[0]) && within(e.f2, row.iter_f[1])
            }
            Err(_) => false,
        };
        let iters_equal = matches!(&got, Ok(e) if e.iterations == row.iterations);
        let entry = per_kind.entry(row.kind.clone()).or_default();
        entry.0 += 1;
        entry.1 += ok as usize;
        entry.2 += iters_equal as usize;
        total += 1;
        agree += ok as usize;
        same_iters += iters_equal as usize;
        if !ok {
            report.push_str(&format!(
                "  row {} ({}): ours {:?}, PoseLib ({}, {}) in {} iterations\n",
                row.id,
                row.kind,
                got.map(|e| (e.f1, e.f2, e.iterations)),
                row.iter_f[0],
                row.iter_f[1],
                row.iterations
            ));
        }
    }
    println!("robust solver vs PoseLib, feasible rows: {agree}/{total} within 1 %, {same_iters} with the same iteration count");
    for (kind, (n, a, it)) in &per_kind {
        println!(
            "  {kind:>14}: {a}/{n} within 1 % ({:.1} %), {it} same iterations",
            100.0 * *a as f64 / *n as f64
        );
    }
    print!("{report}");
    assert!(total >= 50, "only {total} feasible rows");
    assert!(
        agree as f64 >= 0.9 * total as f64,
        "overall agreement {agree}/{total} < 90 %"
    );
    for (kind, (n, a, _)) in &per_kind {
        assert!(
            *a as f64 >= 0.8 * *n as f64,
            "kind {kind}: agreement {a}/{n} < 80 %"
        );
    }
}

#[test]
fn every_success_satisfies_the_kruppa_constraints() {
    let rows = load();
    let mut successes = 0;
    for row in &rows {
        let params = RobustFocalParams {
            f_prior: row.f_prior,
            weights: row.weights,
            max_iters: row.max_iters,
        };
        if let Ok(e) = robust_focals(&row.f, &params) {
            successes += 1;
            let r = relative_kruppa_residual(&row.f, &e, row.f_prior).unwrap();
            assert!(
                r <= KRUPPA_TOLERANCE,
                "row {}: relative residual {r:e}",
                row.id
            );
            assert!(e.f1.is_finite() && e.f2.is_finite() && !e.from_prior);
        }
    }
    assert!(successes >= 60, "only {successes} successes");
}
