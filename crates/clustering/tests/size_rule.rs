//! The rules that keep clusters (docs/method.md step 9): the relative
//! minimum, the default being the former behaviour bit for bit; and the
//! memory bound.

use clustering::{
    cluster, cluster_with_rule, reference, t_linkage, ClusteringError, ClusteringParams, Linkage,
    PreferenceMatrix, Preferences, SizeRule,
};

#[test]
fn every_rule_keeps_min_cluster_size_as_a_floor() {
    assert_eq!(SizeRule::MinSize.min_size(154, 8), 8);
    assert_eq!(SizeRule::MinSize.min_size(154, 60), 60);
    assert_eq!(SizeRule::RelativeMin(0.01).min_size(5000, 8), 50);
    assert_eq!(SizeRule::RelativeMin(0.001).min_size(5000, 8), 8);
    assert_eq!(SizeRule::RelativeMin(f64::NAN).min_size(5000, 8), 8);
    assert_eq!(SizeRule::RelativeMin(-1.0).min_size(5000, 8), 8);
}

#[test]
fn rules_serialise_in_kebab_case() {
    for (text, rule) in [
        (r#""min-size""#, SizeRule::MinSize),
        (r#"{"relative-min":0.01}"#, SizeRule::RelativeMin(0.01)),
    ] {
        assert_eq!(serde_json::from_str::<SizeRule>(text).unwrap(), rule);
        assert_eq!(serde_json::to_string(&rule).unwrap(), text);
    }
    assert!(serde_json::from_str::<SizeRule>(r#""min_size""#).is_err());
    assert!(serde_json::from_str::<SizeRule>(r#""largest-gap""#).is_err());
    let p: ClusteringParams =
        serde_json::from_str(r#"{"size_rule": "min-size", "max_memory_bytes": 1000}"#).unwrap();
    assert_eq!(p.size_rule, SizeRule::MinSize);
    assert_eq!(p.max_memory_bytes, Some(1000));
    assert_eq!(p.min_cluster_size, 8);
}

/// Disjoint blocks of identical rows: block b's points prefer hypotheses
/// `2b, 2b + 1` only, so the clusters are exactly the blocks.
fn blocks(sizes: &[usize]) -> PreferenceMatrix {
    let m = 2 * sizes.len();
    let rows: Vec<Vec<f64>> = sizes
        .iter()
        .enumerate()
        .flat_map(|(b, &size)| {
            let row: Vec<f64> = (0..m).map(|j| if j / 2 == b { 0.9 } else { 0.0 }).collect();
            std::iter::repeat(row).take(size)
        })
        .collect();
    PreferenceMatrix::from_rows(&rows).unwrap()
}

#[test]
fn relative_min_drops_the_fragments_of_a_clustering() {
    let p = blocks(&[40, 30, 3, 2]);
    let prefs = Preferences::Continuous(p.clone());
    // A relative minimum of 10 % of N = 75 keeps clusters of >= 8 points.
    let gap = cluster_with_rule(&prefs, SizeRule::RelativeMin(0.1), 1);
    let expected: Vec<i32> = [(0, 40), (1, 30), (-1, 5)]
        .iter()
        .flat_map(|&(label, count)| std::iter::repeat(label).take(count))
        .collect();
    assert_eq!(gap.labels, expected);
    assert_eq!(
        (gap.clusters_before_filter, gap.clusters_after_filter),
        (4, 2)
    );
    // The same merges as without the rule; only the labels differ.
    let all = t_linkage(&p, 1);
    assert_eq!(gap.merges, all.merges);
    assert_eq!(all.clusters_after_filter, 4);
}

#[test]
fn the_default_rule_is_the_former_filter() {
    let sizes = [30, 12, 9, 8, 7, 3, 1];
    let p = blocks(&sizes);
    let prefs = Preferences::Continuous(p.clone());
    let params = ClusteringParams::default();
    assert_eq!(params.size_rule, SizeRule::MinSize);
    let c = params.cluster(&prefs);
    assert_eq!(c, t_linkage(&p, 8));
    assert_eq!(c, reference::t_linkage(&p, 8));
    assert_eq!(c, cluster(&prefs, 8));
    assert_eq!(c.clusters_after_filter, 4);
    assert_eq!(params.try_cluster(&prefs).unwrap(), c);
    assert_eq!(params.try_cluster_owned(prefs.clone()).unwrap(), c);
    let relative = ClusteringParams {
        size_rule: SizeRule::RelativeMin(0.2),
        ..params
    };
    assert_eq!(
        relative.try_cluster_owned(prefs.clone()).unwrap(),
        relative.try_cluster(&prefs).unwrap()
    );
}

#[test]
fn invalid_relative_min_is_a_typed_error() {
    let params = ClusteringParams {
        size_rule: SizeRule::RelativeMin(1.5),
        ..Default::default()
    };
    assert_eq!(
        params.validate(),
        Err(ClusteringError::InvalidRelativeMin(1.5))
    );
    let prefs = Preferences::Continuous(blocks(&[3]));
    assert_eq!(
        params.try_cluster(&prefs),
        Err(ClusteringError::InvalidRelativeMin(1.5))
    );
}

#[test]
fn memory_bound_refuses_at_once_and_names_the_memory() {
    let params = ClusteringParams {
        max_memory_bytes: Some(200_000_000),
        ..Default::default()
    };
    let fits = params.check_memory(5000, 3000, 0.2).unwrap();
    assert!(fits <= 200_000_000);
    let err = params.check_memory(20_000, 3000, 0.2).unwrap_err();
    let ClusteringError::MemoryBound {
        n_points,
        n_hypotheses,
        required,
        limit,
    } = err
    else {
        panic!("expected MemoryBound, got {err:?}")
    };
    assert_eq!((n_points, n_hypotheses, limit), (20_000, 3000, 200_000_000));
    assert!(required > limit);
    let message = err.to_string();
    assert!(
        message.contains(&format!("{} MB", required.div_ceil(1_000_000)))
            && message.contains("20000 points")
            && message.contains("max_memory_bytes = 200 MB"),
        "{message}"
    );
    // No bound: the estimate, never an error.
    assert!(ClusteringParams::default()
        .check_memory(20_000, 3000, 0.2)
        .is_ok());
    // J-Linkage's estimate does not depend on the density.
    let j = ClusteringParams {
        linkage: Linkage::JLinkage,
        ..params
    };
    assert_eq!(
        j.check_memory(5000, 3000, 0.1),
        j.check_memory(5000, 3000, 0.9)
    );
    // try_cluster checks the matrix it is given.
    let tiny = ClusteringParams {
        max_memory_bytes: Some(10),
        ..Default::default()
    };
    let prefs = Preferences::Continuous(blocks(&[3, 2]));
    assert!(matches!(
        tiny.try_cluster(&prefs),
        Err(ClusteringError::MemoryBound { n_points: 5, .. })
    ));
    assert!(matches!(
        tiny.try_cluster_owned(prefs),
        Err(ClusteringError::MemoryBound { n_points: 5, .. })
    ));
}
