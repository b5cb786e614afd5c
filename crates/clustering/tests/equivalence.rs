//! The min-heap T-Linkage / J-Linkage against the plain O(N³) reference:
//! identical labels, cluster counts and merge sequences (pairs and
//! distances, bit for bit) on random matrices with deliberate ties.

use clustering::{
    j_linkage, reference, t_linkage, BinaryPreferenceMatrix, Clustering, PreferenceMatrix,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Sizes of the random cases: mostly small (the reference is O(N³)), a few
/// up to N = 300, M = 500.
fn case_size(rng: &mut impl Rng, case: usize) -> (usize, usize) {
    match case % 20 {
        0 => (rng.gen_range(150..=300), rng.gen_range(100..=500)),
        1..=3 => (rng.gen_range(40..150), rng.gen_range(1..=500)),
        _ => (rng.gen_range(2..40), rng.gen_range(1..=120)),
    }
}

/// How the non-zero values are drawn: continuous (few exact ties), from a
/// small set (many equal distances), or all ones (binary-valued).
#[derive(Clone, Copy, Debug)]
enum Values {
    Continuous,
    Quantised,
    Ones,
}

/// A random N × M boolean support with density `density`, grouped so that
/// clusters exist: each point belongs to one of a few groups and prefers its
/// group's hypotheses more often; then some rows and columns are duplicated.
fn random_support(rng: &mut impl Rng, n: usize, m: usize, density: f64) -> Vec<Vec<bool>> {
    let groups = rng.gen_range(1..=5);
    let hypothesis_group: Vec<usize> = (0..m).map(|_| rng.gen_range(0..groups)).collect();
    let mut rows: Vec<Vec<bool>> = (0..n)
        .map(|_| {
            let g = rng.gen_range(0..groups);
            (0..m)
                .map(|j| {
                    let p = if hypothesis_group[j] == g {
                        (density * 2.0).min(1.0)
                    } else {
                        density * 0.5
                    };
                    rng.gen_bool(p)
                })
                .collect()
        })
        .collect();
    duplicate_rows_and_columns(rng, &mut rows);
    rows
}

/// Deliberate ties: copies some rows onto others, some columns onto others.
fn duplicate_rows_and_columns<T: Clone>(rng: &mut impl Rng, rows: &mut [Vec<T>]) {
    let n = rows.len();
    let m = rows.first().map_or(0, Vec::len);
    for _ in 0..rng.gen_range(0..=n / 3 + 1) {
        let (from, to) = (rng.gen_range(0..n), rng.gen_range(0..n));
        rows[to] = rows[from].clone();
    }
    if m > 1 {
        for _ in 0..rng.gen_range(0..=m / 4 + 1) {
            let (from, to) = (rng.gen_range(0..m), rng.gen_range(0..m));
            for row in rows.iter_mut() {
                row[to] = row[from].clone();
            }
        }
    }
}

fn random_preferences(
    rng: &mut impl Rng,
    n: usize,
    m: usize,
    density: f64,
    values: Values,
) -> PreferenceMatrix {
    let support = random_support(rng, n, m, density);
    let levels = [1.0, 0.5, 0.25, (-5.0f64).exp()];
    let mut rows: Vec<Vec<f64>> = support
        .iter()
        .map(|row| {
            row.iter()
                .map(|&s| match (s, values) {
                    (false, _) => 0.0,
                    (true, Values::Continuous) => (-rng.gen_range(0.0..5.0f64)).exp(),
                    (true, Values::Quantised) => levels[rng.gen_range(0..levels.len())],
                    (true, Values::Ones) => 1.0,
                })
                .collect()
        })
        .collect();
    duplicate_rows_and_columns(rng, &mut rows);
    PreferenceMatrix::from_rows(&rows).unwrap()
}

fn assert_identical(fast: &Clustering, slow: &Clustering, what: &str) {
    assert_eq!(fast.merges.len(), slow.merges.len(), "{what}: merge count");
    for (step, (a, b)) in fast.merges.iter().zip(&slow.merges).enumerate() {
        assert_eq!(
            (a.kept, a.removed, a.distance.to_bits()),
            (b.kept, b.removed, b.distance.to_bits()),
            "{what}: merge {step}"
        );
    }
    assert_eq!(fast, slow, "{what}");
}

#[test]
fn t_linkage_equals_reference_on_random_matrices() {
    let mut rng = ChaCha8Rng::seed_from_u64(20240601);
    let mut merges = 0;
    let mut tied_merges = 0;
    for case in 0..240 {
        let (n, m) = case_size(&mut rng, case);
        let density = [0.01, 0.05, 0.2, 0.5, 1.0][case % 5] * rng.gen_range(0.5..=1.0);
        let values = [Values::Continuous, Values::Quantised, Values::Ones][case % 3];
        let p = random_preferences(&mut rng, n, m, density, values);
        let min_size = [0, 1, 2, 8][case % 4];
        let fast = t_linkage(&p, min_size);
        let slow = reference::t_linkage(&p, min_size);
        let what = format!("case {case}: N={n} M={m} density={density:.3} {values:?}");
        assert_identical(&fast, &slow, &what);
        merges += fast.merges.len();
        tied_merges += fast
            .merges
            .windows(2)
            .filter(|w| w[0].distance == w[1].distance)
            .count();
    }
    // The cases must exercise the agglomeration, including equal distances.
    assert!(merges > 5_000, "only {merges} merges");
    assert!(
        tied_merges > 500,
        "only {tied_merges} consecutive equal distances"
    );
}

#[test]
fn j_linkage_equals_reference_on_random_matrices() {
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let mut merges = 0;
    for case in 0..220 {
        let (n, m) = case_size(&mut rng, case);
        let density = [0.01, 0.05, 0.2, 0.5, 1.0][case % 5] * rng.gen_range(0.5..=1.0);
        let rows = random_support(&mut rng, n, m, density);
        let b = BinaryPreferenceMatrix::from_rows(&rows).unwrap();
        let min_size = [0, 3, 8][case % 3];
        let fast = j_linkage(&b, min_size);
        let slow = reference::j_linkage(&b, min_size);
        assert_identical(
            &fast,
            &slow,
            &format!("case {case}: N={n} M={m} density={density:.3}"),
        );
        merges += fast.merges.len();
    }
    assert!(merges > 3_000, "only {merges} merges");
}

#[test]
fn result_does_not_depend_on_thread_count() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let p = random_preferences(&mut rng, 257, 300, 0.3, Values::Quantised);
    let b = BinaryPreferenceMatrix::from_rows(&random_support(&mut rng, 257, 300, 0.3)).unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| (t_linkage(&p, 8), j_linkage(&b, 8)))
    };
    let one = run(1);
    assert!(!one.0.merges.is_empty() && !one.1.merges.is_empty());
    assert_eq!(one, run(3));
    assert_eq!(one, run(8));
}
