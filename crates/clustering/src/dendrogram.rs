//! The two sides of each final cluster's last merge, read back from the
//! agglomeration's merges: where a cluster may be split in two.

use crate::Clustering;

/// The two sides (point indices, increasing within each side's order of
/// merging) of a cluster's last merge whose sides both held at least `min`
/// points.
pub type Sides = [Vec<usize>; 2];

/// For each cluster `0..clusters_after_filter` of `clustering`, the two
/// sides of the last merge that made it from two clusters of at least
/// `min` points each (None when no merge did). Merges with a smaller side
/// (a few points joining a large cluster) are passed over: the sides are
/// those of the last merge of two sizeable clusters, on the larger side's
/// line of descent.
pub fn last_sides(clustering: &Clustering, min: usize) -> Vec<Option<Sides>> {
    let n = clustering.labels.len();
    let mut members: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
    let mut last: Vec<Option<Sides>> = vec![None; n];
    for m in &clustering.merges {
        let removed = std::mem::take(&mut members[m.removed]);
        let removed_last = last[m.removed].take();
        if members[m.kept].len() >= min && removed.len() >= min {
            last[m.kept] = Some([members[m.kept].clone(), removed.clone()]);
        } else if removed.len() > members[m.kept].len() {
            last[m.kept] = removed_last;
        }
        members[m.kept].extend(removed);
    }
    // A cluster's id is its smallest point index: the first point of each
    // label.
    let clusters = clustering.clusters_after_filter;
    let mut out = vec![None; clusters];
    let mut seen = vec![false; clusters];
    for (i, &l) in clustering.labels.iter().enumerate() {
        if let Ok(l) = usize::try_from(l) {
            if l < clusters && !seen[l] {
                seen[l] = true;
                out[l] = last[i].take();
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Merge;

    fn merge(kept: usize, removed: usize) -> Merge {
        Merge {
            kept,
            removed,
            distance: 0.5,
        }
    }

    #[test]
    fn the_last_merge_of_two_sizeable_clusters_is_found_past_later_small_ones() {
        // Points 0-2 and 3-5 grow into clusters {0,1,2} and {3,4,5}, which
        // merge; point 6 joins after; points 7, 8 form a cluster of two.
        let merges = vec![
            merge(0, 1),
            merge(0, 2),
            merge(3, 4),
            merge(3, 5),
            merge(0, 3),
            merge(0, 6),
            merge(7, 8),
        ];
        let clustering = Clustering {
            labels: vec![0, 0, 0, 0, 0, 0, 0, 1, 1],
            clusters_before_filter: 2,
            clusters_after_filter: 2,
            merges,
        };
        let sides = last_sides(&clustering, 3);
        assert_eq!(sides[0], Some([vec![0, 1, 2], vec![3, 4, 5]]));
        assert_eq!(sides[1], None);
        // With min 4 no merge qualifies.
        assert_eq!(last_sides(&clustering, 4), vec![None, None]);
    }

    #[test]
    fn a_small_cluster_absorbing_a_larger_one_takes_its_sides() {
        // {1,2} and {3,4} merge (sides of 2), then point 0 absorbs them.
        let merges = vec![merge(1, 2), merge(3, 4), merge(1, 3), merge(0, 1)];
        let clustering = Clustering {
            labels: vec![0; 5],
            clusters_before_filter: 1,
            clusters_after_filter: 1,
            merges,
        };
        assert_eq!(
            last_sides(&clustering, 2),
            vec![Some([vec![1, 2], vec![3, 4]])]
        );
    }
}
