//! Plain reference implementations of T-Linkage and J-Linkage, for tests and
//! benchmarks only.
//!
//! They follow the definition literally: dense preference vectors, the full
//! N × N distance matrix, and at every step an O(N²) scan for the active
//! pair with the smallest `(d, i, j)` — O(N³) in all, plus O(N² · M) for the
//! distances. [`crate::t_linkage`] and [`crate::j_linkage`] must return
//! exactly their labels and merges; use those in production.

use crate::distance::{jaccard_distance, tanimoto_distance_dense};
use crate::linkage::{Clustering, Merge};
use crate::{BinaryPreferenceMatrix, PreferenceMatrix};

/// Reference T-Linkage (Eq. 39–40): dense vectors, Tanimoto distances by
/// [`crate::tanimoto_distance_dense`], element-wise minimum merge, full scan
/// for the closest pair, stop at `d ≥ 1`; then the size filter.
///
/// ```
/// use clustering::{reference, t_linkage, PreferenceMatrix};
/// let p = PreferenceMatrix::from_rows(&[
///     vec![1.0, 0.5, 0.0],
///     vec![0.9, 0.5, 0.1],
///     vec![0.0, 0.0, 1.0],
/// ])
/// .unwrap();
/// assert_eq!(reference::t_linkage(&p, 0), t_linkage(&p, 0));
/// ```
pub fn t_linkage(preferences: &PreferenceMatrix, min_cluster_size: usize) -> Clustering {
    let rows = (0..preferences.n_points())
        .map(|i| preferences.row(i))
        .collect();
    naive_agglomerate(
        rows,
        |p: &Vec<f64>, q: &Vec<f64>| tanimoto_distance_dense(p, q),
        |p: &Vec<f64>, q: &Vec<f64>| p.iter().zip(q).map(|(a, b)| a.min(*b)).collect(),
        min_cluster_size,
    )
}

/// Reference J-Linkage: boolean vectors, Jaccard distance counted element by
/// element, intersection merge, full scan for the closest pair, stop at
/// `d ≥ 1`; then the size filter.
pub fn j_linkage(preferences: &BinaryPreferenceMatrix, min_cluster_size: usize) -> Clustering {
    let rows = (0..preferences.n_points())
        .map(|i| preferences.row(i))
        .collect();
    naive_agglomerate(
        rows,
        |p: &Vec<bool>, q: &Vec<bool>| {
            let intersection = p.iter().zip(q).filter(|(a, b)| **a && **b).count();
            let union = p.iter().zip(q).filter(|(a, b)| **a || **b).count();
            jaccard_distance(intersection as u64, union as u64)
        },
        |p: &Vec<bool>, q: &Vec<bool>| p.iter().zip(q).map(|(a, b)| *a && *b).collect(),
        min_cluster_size,
    )
}

/// The textbook agglomeration: a full distance matrix, an exhaustive scan
/// for the smallest `(d, i, j)` over active pairs, merge into the smaller
/// id, recompute its row, until the smallest distance is `≥ 1`.
fn naive_agglomerate<V>(
    mut vectors: Vec<V>,
    distance: impl Fn(&V, &V) -> f64,
    merge: impl Fn(&V, &V) -> V,
    min_cluster_size: usize,
) -> Clustering {
    let n = vectors.len();
    let mut dist = vec![1.0; n * n];
    for i in 0..n {
        for j in i + 1..n {
            dist[i * n + j] = distance(&vectors[i], &vectors[j]);
            dist[j * n + i] = dist[i * n + j];
        }
    }
    let mut active = vec![true; n];
    let mut labels: Vec<usize> = (0..n).collect();
    let mut merges = Vec::new();
    loop {
        let mut best: Option<(f64, usize, usize)> = None;
        for i in (0..n).filter(|&i| active[i]) {
            for j in (i + 1..n).filter(|&j| active[j]) {
                if best.map_or(true, |(d, _, _)| dist[i * n + j] < d) {
                    best = Some((dist[i * n + j], i, j));
                }
            }
        }
        let Some((d, a, b)) = best else { break };
        if d >= 1.0 {
            break;
        }
        vectors[a] = merge(&vectors[a], &vectors[b]);
        active[b] = false;
        for label in labels.iter_mut().filter(|l| **l == b) {
            *label = a;
        }
        merges.push(Merge {
            kept: a,
            removed: b,
            distance: d,
        });
        for k in (0..n).filter(|&k| active[k] && k != a) {
            dist[a * n + k] = distance(&vectors[a], &vectors[k]);
            dist[k * n + a] = dist[a * n + k];
        }
    }
    let survivors: Vec<usize> = (0..n).filter(|&c| active[c]).collect();
    let size = |c: usize| labels.iter().filter(|&&l| l == c).count();
    let kept: Vec<usize> = survivors
        .iter()
        .copied()
        .filter(|&c| size(c) >= min_cluster_size)
        .collect();
    Clustering {
        labels: labels
            .iter()
            .map(|l| kept.iter().position(|c| c == l).map_or(-1, |p| p as i32))
            .collect(),
        clusters_before_filter: survivors.len(),
        clusters_after_filter: kept.len(),
        merges,
    }
}
