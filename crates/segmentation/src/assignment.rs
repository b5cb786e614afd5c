//! Label bookkeeping after the clustering: the matches of each cluster and
//! labels renumbered by first appearance, as the clustering numbers them
//! (the merge of [`crate::merge_explained`] and the subset's extension,
//! [`crate::extend_labels`], use both).

/// The matches of each label `0..clusters`, increasing.
pub(crate) fn members(labels: &[i32], clusters: usize) -> Vec<Vec<usize>> {
    let mut members = vec![Vec::new(); clusters];
    for (i, &label) in labels.iter().enumerate() {
        if let Some(m) = usize::try_from(label).ok().and_then(|l| members.get_mut(l)) {
            m.push(i);
        }
    }
    members
}

/// Labels `0..clusters` with fewer than `min_size` matches become −1; the
/// others are renumbered by first appearance.
pub(crate) fn drop_small_and_renumber(
    labels: &[i32],
    clusters: usize,
    min_size: usize,
) -> Vec<i32> {
    let mut sizes = vec![0usize; clusters];
    for &l in labels.iter().filter(|&&l| l >= 0) {
        sizes[l as usize] += 1;
    }
    let mut renumbered = vec![-1_i32; clusters];
    let mut next = 0;
    labels
        .iter()
        .map(|&l| {
            let Ok(l) = usize::try_from(l) else { return -1 };
            if sizes[l] < min_size {
                return -1;
            }
            if renumbered[l] < 0 {
                renumbered[l] = next;
                next += 1;
            }
            renumbered[l]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_clusters_drop_and_labels_follow_first_appearance() {
        let labels = [2, 2, 0, -1, 1, 2, 0, 0, 1];
        assert_eq!(
            drop_small_and_renumber(&labels, 3, 3),
            [0, 0, 1, -1, -1, 0, 1, 1, -1]
        );
        assert_eq!(
            drop_small_and_renumber(&labels, 3, 1),
            [0, 0, 1, -1, 2, 0, 1, 1, 2]
        );
        assert_eq!(drop_small_and_renumber(&labels, 3, 4), [-1; 9]);
    }

    #[test]
    fn members_ignore_outliers_and_unknown_labels() {
        assert_eq!(members(&[1, -1, 0, 7, 1], 2), vec![vec![2], vec![0, 4]]);
    }
}
