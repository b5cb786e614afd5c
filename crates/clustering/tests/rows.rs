//! Preferences built one point at a time equal those built entry by entry
//! and one hypothesis at a time, at any thread count, with the same errors.

use clustering::{ClusteringError, Linkage, PreferenceBuilder, Preferences};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Residuals that stress Eq. 38: zeros, the 5τ cut-off exactly, τ exactly,
/// infinities and ordinary values.
fn residuals(rng: &mut ChaCha8Rng, n: usize, m: usize, tau: f64) -> Vec<Vec<f64>> {
    (0..n)
        .map(|_| {
            (0..m)
                .map(|_| match rng.gen_range(0..6) {
                    0 => 0.0,
                    1 => 5.0 * tau,
                    2 => tau,
                    3 => f64::INFINITY,
                    _ => rng.gen_range(0.0..8.0 * tau),
                })
                .collect()
        })
        .collect()
}

fn by_rows(linkage: Linkage, r: &[Vec<f64>], m: usize, tau: f64, threads: usize) -> Preferences {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        Preferences::from_residual_rows(linkage, r.len(), m, tau, |i, out| {
            out.copy_from_slice(&r[i])
        })
        .unwrap()
    })
}

#[test]
fn rows_equal_entries_and_columns_at_any_thread_count() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for (n, m) in [(1, 1), (5, 0), (0, 4), (63, 70), (300, 129)] {
        let tau = 2.5;
        let r = residuals(&mut rng, n, m, tau);
        for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
            let entries = Preferences::from_residuals(linkage, n, m, tau, |i, j| r[i][j]).unwrap();
            let mut builder = PreferenceBuilder::new(linkage, n, tau).unwrap();
            for j in 0..m {
                let column: Vec<f64> = r.iter().map(|row| row[j]).collect();
                builder.push_residuals(&column).unwrap();
            }
            assert_eq!(builder.finish(), entries, "{linkage:?} {n}x{m}");
            for threads in [1, 3] {
                assert_eq!(
                    by_rows(linkage, &r, m, tau, threads),
                    entries,
                    "{linkage:?} {n}x{m}, {threads} threads"
                );
            }
        }
    }
}

#[test]
fn rows_are_stored_at_exactly_their_size() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let r = residuals(&mut rng, 40, 500, 1.0);
    let Preferences::Continuous(p) =
        Preferences::from_residual_rows(Linkage::TLinkage, 40, 500, 1.0, |i, out| {
            out.copy_from_slice(&r[i])
        })
        .unwrap()
    else {
        panic!("T-Linkage builds continuous preferences")
    };
    assert!(p.nonzeros() > 0);
    for (i, row) in r.iter().enumerate() {
        let (index, value) = p.row_support(i);
        let expected = row.iter().filter(|&&x| x <= 5.0).count();
        assert_eq!((index.len(), value.len()), (expected, expected));
    }
    assert_eq!(p.spare_capacity(), 0);
}

#[test]
fn rows_report_the_first_bad_residual_and_a_bad_tau() {
    let bad = |i: usize, out: &mut [f64]| {
        out.fill(0.0);
        if i == 70 {
            out[3] = -1.0;
        }
        if i == 200 {
            out[0] = f64::NAN;
        }
    };
    for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
        assert_eq!(
            Preferences::from_residual_rows(linkage, 300, 5, 1.0, bad),
            Err(ClusteringError::InvalidResidual {
                point: 70,
                hypothesis: 3,
                value: -1.0
            }),
            "{linkage:?}"
        );
    }
    assert_eq!(
        Preferences::from_residual_rows(Linkage::JLinkage, 3, 2, 0.0, |_, out| out.fill(0.0)),
        Err(ClusteringError::InvalidTau(0.0))
    );
}
