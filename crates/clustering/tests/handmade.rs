//! Hand-made cases with known answers, builders and input checking.

use clustering::{
    cluster, j_linkage, preference, reference, t_linkage, tanimoto_distance_dense,
    BinaryPreferenceMatrix, ClusteringError, ClusteringParams, Linkage, PreferenceBuilder,
    PreferenceMatrix, Preferences,
};

/// Block-diagonal matrix: `sizes[b]` points preferring only the hypotheses
/// of block b (`width` per block), with values varying by point.
fn blocks(sizes: &[usize], width: usize) -> Vec<Vec<f64>> {
    let m = sizes.len() * width;
    let mut rows = Vec::new();
    for (b, &size) in sizes.iter().enumerate() {
        for p in 0..size {
            rows.push(
                (0..m)
                    .map(|j| {
                        if j / width == b {
                            1.0 - 0.1 * ((p + j) % 5) as f64
                        } else {
                            0.0
                        }
                    })
                    .collect(),
            );
        }
    }
    rows
}

/// Interleaves the rows of the blocks: point i goes to block `i % k`.
fn interleave(rows: Vec<Vec<f64>>, sizes: &[usize]) -> (Vec<Vec<f64>>, Vec<usize>) {
    let mut by_block: Vec<Vec<Vec<f64>>> = Vec::new();
    let mut it = rows.into_iter();
    for &s in sizes {
        by_block.push(it.by_ref().take(s).collect());
    }
    let (mut out, mut truth) = (Vec::new(), Vec::new());
    let mut round = 0;
    while out.len() < sizes.iter().sum() {
        for (b, block) in by_block.iter().enumerate() {
            if let Some(row) = block.get(round) {
                out.push(row.clone());
                truth.push(b);
            }
        }
        round += 1;
    }
    (out, truth)
}

#[test]
fn two_disjoint_blocks_give_two_clusters() {
    let (rows, truth) = interleave(blocks(&[10, 12], 6), &[10, 12]);
    let p = PreferenceMatrix::from_rows(&rows).unwrap();
    let c = t_linkage(&p, 8);
    assert_eq!((c.clusters_before_filter, c.clusters_after_filter), (2, 2));
    // Block 0 contains point 0, so it is cluster 0.
    let expected: Vec<i32> = truth.iter().map(|&b| b as i32).collect();
    assert_eq!(c.labels, expected);
    assert_eq!(c.merges.len(), 20);
    assert!(c
        .merges
        .iter()
        .all(|m| m.kept < m.removed && m.distance < 1.0));
    // Same with J-Linkage on the supports.
    let b = BinaryPreferenceMatrix::from_rows(
        &rows
            .iter()
            .map(|r| r.iter().map(|&v| v > 0.0).collect())
            .collect::<Vec<_>>(),
    )
    .unwrap();
    assert_eq!(j_linkage(&b, 8).labels, expected);
}

#[test]
fn small_blocks_are_outliers_and_ids_are_compacted() {
    // Blocks of 9, 3 and 8 points: the middle one is below the filter.
    let p = PreferenceMatrix::from_rows(&blocks(&[9, 3, 8], 4)).unwrap();
    let c = t_linkage(&p, 8);
    let mut expected = vec![0; 9];
    expected.extend([-1; 3]);
    expected.extend([1; 8]);
    assert_eq!(c.labels, expected);
    assert_eq!((c.clusters_before_filter, c.clusters_after_filter), (3, 2));
    // Without the filter every cluster keeps an id, in ascending order of
    // its smallest point index.
    let c = t_linkage(&p, 0);
    assert_eq!(&c.labels[8..13], &[0, 1, 1, 1, 2]);
    assert_eq!(c.clusters_after_filter, 3);
}

#[test]
fn all_zero_row_stays_a_singleton_outlier() {
    let mut rows = blocks(&[8], 5);
    rows.insert(3, vec![0.0; 5]);
    let p = PreferenceMatrix::from_rows(&rows).unwrap();
    let c = t_linkage(&p, 8);
    assert_eq!(c.labels[3], -1);
    assert!(c
        .labels
        .iter()
        .enumerate()
        .all(|(i, &l)| (i == 3) == (l == -1)));
    assert!(c.merges.iter().all(|m| m.kept != 3 && m.removed != 3));
    assert_eq!((c.clusters_before_filter, c.clusters_after_filter), (2, 1));
    assert_eq!(tanimoto_distance_dense(&rows[3], &rows[3]), 1.0);
}

#[test]
fn identical_rows_merge_first() {
    let rows = vec![
        vec![1.0, 0.5, 0.2, 0.0],
        vec![0.9, 0.6, 0.0, 0.1],
        vec![0.3, 0.0, 1.0, 0.7],
        vec![0.9, 0.6, 0.0, 0.1], // = row 1
        vec![0.3, 0.0, 1.0, 0.7], // = row 2
    ];
    let p = PreferenceMatrix::from_rows(&rows).unwrap();
    let c = t_linkage(&p, 0);
    // Two pairs at distance 0; ties broken by the smaller (i, j).
    assert_eq!(
        (c.merges[0].kept, c.merges[0].removed, c.merges[0].distance),
        (1, 3, 0.0)
    );
    assert_eq!(
        (c.merges[1].kept, c.merges[1].removed, c.merges[1].distance),
        (2, 4, 0.0)
    );
    assert!(c.merges[2].distance > 0.0);
    assert_eq!(c, reference::t_linkage(&p, 0));
}

#[test]
fn merged_vector_is_the_elementwise_minimum() {
    // 0 and 1 merge first; their minimum (1, 1, 0, 0) shares nothing with
    // point 2, although point 1 alone did (hypothesis 2): 2 stays apart.
    // Point 3 then joins at the distance of Eq. 39 to the merged vector.
    let rows = vec![
        vec![1.0, 1.0, 0.0, 0.0],
        vec![1.0, 1.0, 0.5, 0.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.5, 0.25, 0.0, 0.0],
    ];
    let p = PreferenceMatrix::from_rows(&rows).unwrap();
    let c = t_linkage(&p, 0);
    assert!(tanimoto_distance_dense(&rows[1], &rows[2]) < 1.0);
    assert_eq!((c.merges[0].kept, c.merges[0].removed), (0, 1));
    assert_eq!(
        c.merges[0].distance,
        tanimoto_distance_dense(&rows[0], &rows[1])
    );
    let merged = [1.0, 1.0, 0.0, 0.0];
    assert_eq!((c.merges[1].kept, c.merges[1].removed), (0, 3));
    assert_eq!(
        c.merges[1].distance,
        tanimoto_distance_dense(&merged, &rows[3])
    );
    assert_eq!(c.merges.len(), 2);
    assert_eq!(c.labels, vec![0, 0, 1, 0]);
}

#[test]
fn degenerate_sizes_do_not_panic() {
    // N = 0.
    let empty = PreferenceMatrix::from_rows(&[]).unwrap();
    let c = t_linkage(&empty, 8);
    assert!(c.labels.is_empty() && c.merges.is_empty());
    assert_eq!(c.clusters_before_filter, 0);
    // N = 1.
    let one = PreferenceMatrix::from_rows(&[vec![1.0, 0.5]]).unwrap();
    assert_eq!(t_linkage(&one, 8).labels, vec![-1]);
    assert_eq!(t_linkage(&one, 1).labels, vec![0]);
    // M = 0: nothing is preferred, every point is a singleton.
    let none = PreferenceMatrix::from_residuals(5, 0, 1.0, |_, _| 0.0).unwrap();
    let c = t_linkage(&none, 0);
    assert_eq!(c.labels, vec![0, 1, 2, 3, 4]);
    assert_eq!(c.clusters_before_filter, 5);
    assert_eq!(t_linkage(&none, 8).labels, vec![-1; 5]);
    let b = BinaryPreferenceMatrix::from_residuals(3, 0, 1.0, |_, _| 0.0).unwrap();
    assert_eq!(j_linkage(&b, 0).labels, vec![0, 1, 2]);
    assert_eq!(reference::t_linkage(&none, 0), t_linkage(&none, 0));
}

#[test]
fn preferences_follow_eq_38() {
    let tau = 2.0;
    let residuals = [[0.0, 1.0, 10.0, 10.5], [4.0, f64::INFINITY, 0.5, 9.99]];
    let p = PreferenceMatrix::from_residuals(2, 4, tau, |i, j| residuals[i][j]).unwrap();
    for (i, row) in residuals.iter().enumerate() {
        for (j, &r) in row.iter().enumerate() {
            let expected = if r <= 5.0 * tau {
                (-r / tau).exp()
            } else {
                0.0
            };
            assert_eq!(p.get(i, j), expected, "({i}, {j})");
            assert_eq!(preference(r, tau), expected);
        }
    }
    assert_eq!(p.get(0, 2), (-5.0f64).exp()); // r = 5τ exactly is kept
    assert_eq!(p.get(0, 3), 0.0);
    assert_eq!(p.density(), 6.0 / 8.0);
}

#[test]
fn column_builder_matches_closure_builder() {
    let (n, m, tau) = (7, 11, 1.5);
    let r = |i: usize, j: usize| ((i * 31 + j * 17) % 23) as f64 * 0.4;
    for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
        let mut builder = PreferenceBuilder::new(linkage, n, tau).unwrap();
        for j in 0..m {
            let column: Vec<f64> = (0..n).map(|i| r(i, j)).collect();
            builder.push_residuals(&column).unwrap();
        }
        assert_eq!(builder.n_hypotheses(), m);
        let built = builder.finish();
        assert_eq!(
            built,
            Preferences::from_residuals(linkage, n, m, tau, r).unwrap()
        );
        assert_eq!(built.linkage(), linkage);
        assert_eq!((built.n_points(), built.n_hypotheses()), (n, m));
    }
    let Preferences::Binary(b) =
        Preferences::from_residuals(Linkage::JLinkage, n, m, tau, r).unwrap()
    else {
        panic!("J-Linkage builds binary preferences")
    };
    for i in 0..n {
        for j in 0..m {
            assert_eq!(b.get(i, j), r(i, j) <= tau);
        }
    }
}

#[test]
fn params_choose_the_linkage_and_the_filter() {
    let params = ClusteringParams::default();
    assert_eq!(params.linkage, Linkage::TLinkage);
    assert_eq!(params.min_cluster_size, 8);
    let params: ClusteringParams = serde_json::from_str(r#"{"min_cluster_size": 3}"#).unwrap();
    assert_eq!(params.linkage, Linkage::TLinkage);
    assert!(serde_json::from_str::<ClusteringParams>(r#"{"linkage": "x-linkage"}"#).is_err());
    // Points 0-3 fit hypotheses 0-1 exactly, 4-5 fit hypothesis 2.
    let r = |i: usize, j: usize| if (i < 4) == (j < 2) { 0.0 } else { 100.0 };
    for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
        let params = ClusteringParams {
            linkage,
            min_cluster_size: 3,
            ..Default::default()
        };
        let mut builder = params.preference_builder(6, 1.0).unwrap();
        for j in 0..3 {
            builder
                .push_residuals(&(0..6).map(|i| r(i, j)).collect::<Vec<_>>())
                .unwrap();
        }
        let prefs = builder.finish();
        let c = params.cluster(&prefs);
        assert_eq!(c.labels, vec![0, 0, 0, 0, -1, -1], "{linkage:?}");
        assert_eq!(c, cluster(&prefs, 3));
    }
}

#[test]
fn bad_input_gives_typed_errors() {
    assert_eq!(
        PreferenceMatrix::from_residuals(2, 2, 0.0, |_, _| 1.0),
        Err(ClusteringError::InvalidTau(0.0))
    );
    assert!(matches!(
        PreferenceMatrix::from_residuals(2, 2, f64::NAN, |_, _| 1.0),
        Err(ClusteringError::InvalidTau(_))
    ));
    assert!(matches!(
        PreferenceMatrix::from_residuals(3, 2, 1.0, |i, j| if (i, j) == (2, 1) {
            f64::NAN
        } else {
            0.0
        }),
        Err(ClusteringError::InvalidResidual {
            point: 2,
            hypothesis: 1,
            ..
        })
    ));
    assert_eq!(
        BinaryPreferenceMatrix::from_residuals(2, 3, 1.0, |i, j| if (i, j) == (1, 2) {
            -1.0
        } else {
            0.0
        }),
        Err(ClusteringError::InvalidResidual {
            point: 1,
            hypothesis: 2,
            value: -1.0
        })
    );
    assert_eq!(
        PreferenceMatrix::from_rows(&[vec![0.5, 0.5], vec![0.5]]),
        Err(ClusteringError::RaggedRow {
            point: 1,
            expected: 2,
            got: 1
        })
    );
    assert_eq!(
        PreferenceMatrix::from_rows(&[vec![0.5, 1.5]]),
        Err(ClusteringError::InvalidPreference {
            point: 0,
            hypothesis: 1,
            value: 1.5
        })
    );
    assert!(PreferenceMatrix::from_rows(&[vec![f64::NAN]]).is_err());
    assert!(PreferenceMatrix::from_rows(&[vec![f64::INFINITY]]).is_err());
    for linkage in [Linkage::TLinkage, Linkage::JLinkage] {
        let mut builder = PreferenceBuilder::new(linkage, 3, 1.0).unwrap();
        assert_eq!(
            builder.push_residuals(&[0.0, 1.0]),
            Err(ClusteringError::ColumnLength {
                hypothesis: 0,
                expected: 3,
                got: 2
            })
        );
        assert!(matches!(
            builder.push_residuals(&[0.0, f64::NAN, 1.0]),
            Err(ClusteringError::InvalidResidual {
                point: 1,
                hypothesis: 0,
                ..
            })
        ));
        // A rejected column leaves the builder unchanged.
        builder.push_residuals(&[0.0, 0.5, 1.0]).unwrap();
        assert_eq!(builder.n_hypotheses(), 1);
        assert_eq!(builder.finish().n_hypotheses(), 1);
        assert!(PreferenceBuilder::new(linkage, 3, -1.0).is_err());
    }
    // The error messages name the offending entry.
    let message = PreferenceMatrix::from_rows(&[vec![0.5, -0.5]])
        .unwrap_err()
        .to_string();
    assert!(message.contains("point 0, hypothesis 1"), "{message}");
}

#[test]
fn a_stop_check_ends_the_clustering_early_and_is_called_between_merges() {
    use std::cell::Cell;
    let sizes = [150, 170];
    let (rows, _) = interleave(blocks(&sizes, 6), &sizes);
    let p = PreferenceMatrix::from_rows(&rows).unwrap();
    let b = BinaryPreferenceMatrix::from_rows(
        &rows
            .iter()
            .map(|r| r.iter().map(|&v| v > 0.0).collect())
            .collect::<Vec<_>>(),
    )
    .unwrap();
    for (linkage, preferences) in [
        (Linkage::TLinkage, Preferences::Continuous(p)),
        (Linkage::JLinkage, Preferences::Binary(b)),
    ] {
        let params = ClusteringParams {
            linkage,
            ..Default::default()
        };
        let full = params.try_cluster_owned(preferences.clone()).unwrap();
        // Never stopped: the clustering of try_cluster_owned.
        let calls = Cell::new(0);
        let never = || {
            calls.set(calls.get() + 1);
            false
        };
        let same = params.try_cluster_owned_until(preferences.clone(), &never);
        assert_eq!(same.unwrap().unwrap().labels, full.labels);
        assert!(
            calls.get() >= 2,
            "{linkage:?}: stop called {} times",
            calls.get()
        );
        // Stopped at its second call: no clustering.
        let calls = Cell::new(0);
        let second = || {
            calls.set(calls.get() + 1);
            calls.get() >= 2
        };
        let stopped = params
            .try_cluster_owned_until(preferences, &second)
            .unwrap();
        assert!(stopped.is_none(), "{linkage:?}");
        assert_eq!(
            calls.get(),
            3,
            "{linkage:?}: checked once more after the loop"
        );
    }
}
