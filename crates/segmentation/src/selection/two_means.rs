//! A group of matches in two by where they lie, or by how they move:
//! 2-means (Lloyd's algorithm, Lloyd 1982) over the matches' points `(x₁,
//! y₁, x₂, y₂)` or over their displacements `(x₂ − x₁, y₂ − y₁)`, candidate
//! splits of [`super::split`] for two objects one cluster holds.
//!
//! Written out rather than taken from a clustering crate: two centres, a
//! deterministic start and at most [`LLOYD_ROUNDS`] rounds over at most a
//! thousand matches are some thirty lines, and a crate of k-means would
//! bring a random start to seed and its own matrix types.

use geometry::Correspondences;

/// Rounds of Lloyd's algorithm at most; it stops earlier when no match
/// changes side.
pub const LLOYD_ROUNDS: usize = 20;

/// A match as a point of R⁴.
type Point = [f64; 4];

/// `group` (indices into `points`) in two by 2-means over `(x₁, y₁, x₂,
/// y₂)`: the centres start at the match farthest from the group's centroid
/// and the match farthest from that one (a farthest-first start, Gonzalez
/// 1985; ties to the lower index), each match goes to the nearer centre
/// (the first on a tie) and each centre moves to its side's mean, until no
/// match changes side or [`LLOYD_ROUNDS`] rounds. The sides keep the
/// group's order; None when one has fewer than `min` matches.
pub fn two_means(points: &Correspondences, group: &[usize], min: usize) -> Option<[Vec<usize>; 2]> {
    two_means_over(group, min, |i| {
        let (a, b) = (points.point1(i), points.point2(i));
        [a[0], a[1], b[0], b[1]]
    })
}

/// `group` in two by 2-means over the matches' displacements `(x₂ − x₁,
/// y₂ − y₁)`, as [`two_means`] over their points: two objects side by
/// side, which 2-means over the points may cut across, differ in how they
/// move.
pub fn two_means_by_displacement(
    points: &Correspondences,
    group: &[usize],
    min: usize,
) -> Option<[Vec<usize>; 2]> {
    two_means_over(group, min, |i| {
        let (a, b) = (points.point1(i), points.point2(i));
        [b[0] - a[0], b[1] - a[1], 0.0, 0.0]
    })
}

/// 2-means of `group` over the points `at` gives (the start, rounds and
/// ties of [`two_means`]).
fn two_means_over(
    group: &[usize],
    min: usize,
    at: impl Fn(usize) -> Point,
) -> Option<[Vec<usize>; 2]> {
    if group.len() < 2 * min.max(1) {
        return None;
    }
    let farthest = |from: Point| {
        let distance = |&i: &usize| squared_distance(at(i), from);
        *group
            .iter()
            .max_by(|a, b| distance(a).total_cmp(&distance(b)).then(b.cmp(a)))
            .expect("a group of at least two matches")
    };
    let first = farthest(mean(group.iter().map(|&i| at(i))));
    let mut centres = [at(first), at(farthest(at(first)))];
    let mut sides: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
    for _ in 0..LLOYD_ROUNDS {
        let (a, b): (Vec<usize>, Vec<usize>) = group.iter().partition(|&&i| {
            squared_distance(at(i), centres[0]) <= squared_distance(at(i), centres[1])
        });
        let settled = sides[0] == a;
        sides = [a, b];
        if settled || sides.iter().any(Vec::is_empty) {
            break;
        }
        centres = sides
            .each_ref()
            .map(|side| mean(side.iter().map(|&i| at(i))));
    }
    sides.iter().all(|side| side.len() >= min).then_some(sides)
}

fn squared_distance(a: Point, b: Point) -> f64 {
    (0..4).map(|k| (a[k] - b[k]) * (a[k] - b[k])).sum()
}

/// The mean of a non-empty set of points.
fn mean(points: impl Iterator<Item = Point>) -> Point {
    let (mut sum, mut count) = ([0.0; 4], 0usize);
    for p in points {
        (0..4).for_each(|k| sum[k] += p[k]);
        count += 1;
    }
    sum.map(|s| s / count as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Matches on a grid in two boxes of image 1 (and the same in image 2,
    /// moved by 5 px), interleaved in index order.
    fn two_boxes(per_box: usize) -> (Correspondences, Vec<usize>, Vec<usize>) {
        let (mut p1, mut left, mut right) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..per_box {
            let (u, v) = ((k % 5) as f64 * 10.0, (k / 5) as f64 * 10.0);
            left.push(p1.len());
            p1.push([-300.0 + u, -100.0 + v]);
            right.push(p1.len());
            p1.push([100.0 + u, 50.0 + v]);
        }
        let p2: Vec<[f64; 2]> = p1.iter().map(|p| [p[0] + 5.0, p[1]]).collect();
        (Correspondences::new(&p1, &p2).unwrap(), left, right)
    }

    #[test]
    fn two_apart_boxes_are_the_two_sides() {
        let (points, left, right) = two_boxes(20);
        let group: Vec<usize> = (0..40).collect();
        let sides = two_means(&points, &group, 8).expect("two sides of 20");
        // The first centre is the match farthest from the centroid: a
        // corner of one box, whichever; the sides are the boxes.
        let mut found = sides.clone();
        found.sort();
        assert_eq!(found, [left, right]);
    }

    #[test]
    fn one_box_of_two_displacements_is_split_by_displacement_alone() {
        // One box of image 1, its matches moved by +5 px or −5 px in
        // alternation: over the points each side holds both kinds, over
        // the displacements the sides are the two kinds.
        let p1: Vec<[f64; 2]> = (0..40)
            .map(|k| [(k % 8) as f64 * 10.0, (k / 8) as f64 * 10.0])
            .collect();
        let shift = |k: usize| if k % 2 == 0 { 5.0 } else { -5.0 };
        let p2: Vec<[f64; 2]> = (0..40).map(|k| [p1[k][0] + shift(k), p1[k][1]]).collect();
        let points = Correspondences::new(&p1, &p2).unwrap();
        let group: Vec<usize> = (0..40).collect();
        let mut sides = two_means_by_displacement(&points, &group, 8).expect("two sides");
        sides.sort();
        let (even, odd): (Vec<usize>, Vec<usize>) = group.iter().partition(|&&k| k % 2 == 0);
        assert_eq!(sides, [even, odd]);
        let by_place = two_means(&points, &group, 8).expect("two sides");
        assert!(by_place
            .iter()
            .all(|side| side.iter().any(|k| k % 2 == 0) && side.iter().any(|k| k % 2 == 1)));
    }

    #[test]
    fn sides_below_the_minimum_or_a_small_group_give_none() {
        let (points, left, _) = two_boxes(20);
        // Three matches of the right box with the left box: a side of 3.
        let group: Vec<usize> = left.iter().copied().chain([1, 3, 5]).collect();
        assert_eq!(two_means(&points, &group, 8), None);
        assert_eq!(two_means(&points, &left[..15], 8), None);
        // Identical matches: one centre, one side.
        let same = Correspondences::new(&[[1.0, 2.0]; 20], &[[3.0, 4.0]; 20]).unwrap();
        let all: Vec<usize> = (0..20).collect();
        assert_eq!(two_means(&same, &all, 1), None);
    }

    #[test]
    fn the_sides_are_a_fixed_point_of_lloyd() {
        // Random matches: each lies on the side of the nearer of the two
        // sides' means (ties to the first), the fixed point Lloyd's
        // rounds stop at.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..20 {
            let mut point = || [rng.gen_range(-300.0..300.0), rng.gen_range(-200.0..200.0)];
            let (p1, p2): (Vec<[f64; 2]>, Vec<[f64; 2]>) =
                (0..60).map(|_| (point(), point())).unzip();
            let points = Correspondences::new(&p1, &p2).unwrap();
            let group: Vec<usize> = (0..60).collect();
            let sides = two_means(&points, &group, 1).expect("two sides");
            let at = |i: usize| [p1[i][0], p1[i][1], p2[i][0], p2[i][1]];
            let means = sides.each_ref().map(|s| mean(s.iter().map(|&i| at(i))));
            for (k, side) in sides.iter().enumerate() {
                for &i in side {
                    let nearer_first =
                        squared_distance(at(i), means[0]) <= squared_distance(at(i), means[1]);
                    assert_eq!(nearer_first, k == 0, "match {i}");
                }
            }
        }
    }
}
