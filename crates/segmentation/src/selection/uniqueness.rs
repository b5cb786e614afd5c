//! The uniqueness of keypoints: a keypoint of one image corresponds to at
//! most one point of the other (the uniqueness constraint of stereo
//! matching, Marr & Poggio, "Cooperative computation of stereo disparity",
//! Science 1976). A matcher without a cross-check matches several
//! keypoints of image 1 to one of image 2, and mismatches made by pairing
//! the scene's keypoints (HOPE-F's outliers) reuse the keypoints of true
//! matches; once a detected motion explains one match of a keypoint, the
//! others that it does not explain are mismatches and stop counting as
//! evidence for the motions detected after it ([`super::nfa::detect`]).
//! Matches whose keypoints are all distinct are untouched.

use geometry::Correspondences;
use std::collections::HashMap;

/// Two points are one keypoint when their coordinates are equal after
/// rounding to this step, px (the same keypoint written twice, whatever
/// the file's precision).
pub const KEYPOINT_STEP_PX: f64 = 0.01;

/// The matches of each keypoint, in each image.
#[derive(Debug, Clone)]
pub struct Keypoints {
    /// Per image: per match, its keypoint.
    of: [Vec<usize>; 2],
    /// Per image: the matches sorted by keypoint.
    order: [Vec<usize>; 2],
    /// Per image: keypoint k's matches are `order[start[k]..start[k + 1]]`.
    start: [Vec<usize>; 2],
}

impl Keypoints {
    /// The keypoints of `points` in both images.
    pub fn new(points: &Correspondences) -> Self {
        let image1 = Side::new((0..points.len()).map(|m| points.point1(m)));
        let image2 = Side::new((0..points.len()).map(|m| points.point2(m)));
        Self {
            of: [image1.of, image2.of],
            order: [image1.order, image2.order],
            start: [image1.start, image2.start],
        }
    }

    /// The other matches that share match `m`'s keypoint in image 1 or in
    /// image 2 (a match sharing both is listed twice).
    pub fn sharing(&self, m: usize) -> impl Iterator<Item = usize> + '_ {
        (0..2).flat_map(move |side| {
            let k = self.of[side][m];
            let range = self.start[side][k]..self.start[side][k + 1];
            self.order[side][range]
                .iter()
                .copied()
                .filter(move |&j| j != m)
        })
    }
}

/// One image's keypoints.
struct Side {
    of: Vec<usize>,
    order: Vec<usize>,
    start: Vec<usize>,
}

impl Side {
    /// Keypoints numbered by first appearance.
    fn new(points: impl Iterator<Item = [f64; 2]>) -> Self {
        let mut index: HashMap<(i64, i64), usize> = HashMap::new();
        let of: Vec<usize> = points
            .map(|p| {
                let key = p.map(|v| (v / KEYPOINT_STEP_PX).round() as i64);
                let next = index.len();
                *index.entry((key[0], key[1])).or_insert(next)
            })
            .collect();
        let mut start = vec![0; index.len() + 1];
        for &k in &of {
            start[k + 1] += 1;
        }
        for k in 0..index.len() {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut order = vec![0; of.len()];
        for (m, &k) in of.iter().enumerate() {
            order[fill[k]] = m;
            fill[k] += 1;
        }
        Self { of, order, start }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sharing_lists_the_matches_of_the_same_keypoint_in_either_image() {
        let p1 = [
            [10.0, 20.0],
            [10.0, 20.0],
            [30.0, 40.0],
            [50.0, 60.0],
            [10.001, 20.0],
        ];
        let p2 = [[1.0, 2.0], [3.0, 4.0], [3.0, 4.0], [7.0, 8.0], [9.0, 9.0]];
        let points = Correspondences::new(&p1, &p2).unwrap();
        let keys = Keypoints::new(&points);
        let mut sharing: Vec<Vec<usize>> = (0..5)
            .map(|m| keys.sharing(m).collect::<Vec<_>>())
            .collect();
        sharing.iter_mut().for_each(|s| s.sort_unstable());
        // Brute force: equal coordinates to the step.
        let same = |a: [f64; 2], b: [f64; 2]| {
            (0..2).all(|i| (a[i] / KEYPOINT_STEP_PX).round() == (b[i] / KEYPOINT_STEP_PX).round())
        };
        for m in 0..5 {
            let mut expected: Vec<usize> = (0..5)
                .filter(|&j| j != m)
                .flat_map(|j| {
                    let n = usize::from(same(p1[m], p1[j])) + usize::from(same(p2[m], p2[j]));
                    std::iter::repeat(j).take(n)
                })
                .collect();
            expected.sort_unstable();
            assert_eq!(sharing[m], expected, "match {m}");
        }
        // 0 and 1 share image 1 (and 4 within the step), 1 and 2 image 2;
        // 3 shares nothing.
        assert_eq!(sharing[0], [1, 4]);
        assert_eq!(sharing[1], [0, 2, 4]);
        assert!(sharing[3].is_empty());
    }
}
