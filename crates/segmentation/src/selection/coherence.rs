//! Whether a group's matches map neighbours to neighbours along their
//! epipolar lines: a rigid object's surface moves as a whole, so two
//! matches close in image 1 lie at close positions along their epipolar
//! lines in image 2, while gross outliers that happen to fit one F (a
//! mismatch pairs a keypoint with an unrelated one, whose position along
//! the line owes nothing to its neighbours') do not. The position across
//! the line is what the F fit already constrains, so only the position
//! along it is tested. The principle is the motion smoothness of matching
//! (a true match's neighbours match near its own: Schmid & Mohr's
//! semi-local constraints, IEEE TPAMI 1997; Bian et al., "GMS: Grid-based
//! Motion Statistics", CVPR 2017), restricted to the one coordinate an F
//! leaves free.
//!
//! The statistic is a rank sum (a contrario, as the NFA of
//! [`super::nfa`]): for each of n matches i, with j its nearest match in
//! image 1 among the group's, the distance along i's epipolar line in image 2
//! between x₂ᵢ and x₂ⱼ is ranked among those to the group's other matches
//! (rank 0 the closest of the n − 1). Under the hypothesis that positions
//! along the lines are independent of image-1 neighbourhoods each rank is
//! uniform on {0, …, n − 2}, and the chance of a rank sum as small as the
//! group's is the tail of the sum of n such uniforms (treating the n
//! matches as independent), computed exactly.

use geometry::Correspondences;
use nalgebra::{Matrix3, Vector3};

/// At most this many of a group's matches are tested: an even stride
/// through the group (the cost is quadratic in their number; the tail's
/// smallest value, (1/99)¹⁰⁰, stays a normal `f64`).
pub const MAX_TESTED: usize = 100;

/// `ln P(R ≤ r)`: the chance that matches whose positions along the
/// epipolar lines of `f` ignore their image-1 neighbours have a rank sum R
/// as small as `members`' r (module documentation). 0 (chance explains it)
/// with fewer than 3 matches tested.
pub fn ln_incoherence(points: &Correspondences, members: &[usize], f: &Matrix3<f64>) -> f64 {
    let step = members.len().div_ceil(MAX_TESTED).max(1);
    let tested: Vec<usize> = members.iter().copied().step_by(step).collect();
    let n = tested.len();
    if n < 3 {
        return 0.0;
    }
    let rank_sum: usize = (0..n).map(|i| neighbour_rank(points, &tested, i, f)).sum();
    ln_uniform_sum_cdf(n, n - 1, rank_sum)
}

/// `ln P(U₁ + … + Uₙ ≤ s)` for n independent uniforms on {0, …, m − 1}:
/// the distribution of the partial sums, truncated at s, convolved n times
/// with the uniform by a running sum.
fn ln_uniform_sum_cdf(n: usize, m: usize, s: usize) -> f64 {
    let mut mass = vec![0.0; s + 1];
    mass[0] = 1.0;
    for _ in 0..n {
        let mut next = vec![0.0; s + 1];
        let mut window = 0.0;
        for t in 0..=s {
            window += mass[t];
            if t >= m {
                window -= mass[t - m];
            }
            next[t] = window / m as f64;
        }
        mass = next;
    }
    mass.iter().sum::<f64>().min(1.0).ln()
}

/// The rank of `tested[i]`'s image-1 nearest neighbour among `tested`'s
/// distances to it along its epipolar line in image 2 (0 the closest of the
/// n − 1 others); the last, n − 2, when that line is undefined (x₁ at the
/// epipole).
fn neighbour_rank(points: &Correspondences, tested: &[usize], i: usize, f: &Matrix3<f64>) -> usize {
    let worst = tested.len() - 2;
    let (x1, x2) = (points.point1(tested[i]), points.point2(tested[i]));
    let Some(along) = line_direction(f, x1) else {
        return worst;
    };
    let squared = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
    let distance_along = |m: usize| {
        let q = points.point2(m);
        ((q[0] - x2[0]) * along[0] + (q[1] - x2[1]) * along[1]).abs()
    };
    let Some(nearest) = (0..tested.len()).filter(|&o| o != i).min_by(|&a, &b| {
        squared(points.point1(tested[a]), x1)
            .total_cmp(&squared(points.point1(tested[b]), x1))
            .then(a.cmp(&b))
    }) else {
        return worst;
    };
    let to_nearest = distance_along(tested[nearest]);
    (0..tested.len())
        .filter(|&o| o != i && o != nearest && distance_along(tested[o]) < to_nearest)
        .count()
}

/// The unit direction of the epipolar line `F x̃₁` in image 2, or None
/// when it is undefined.
fn line_direction(f: &Matrix3<f64>, x1: [f64; 2]) -> Option<[f64; 2]> {
    let l = f * Vector3::new(x1[0], x1[1], 1.0);
    let g = l.x.hypot(l.y);
    (g.is_finite() && g > 0.0).then(|| [-l.y / g, l.x / g])
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_rank_sum_tail_equals_enumeration() {
        // n = 3 uniforms on {0, 1, 2, 3}: count the 64 triples.
        for s in 0..=9 {
            let count = (0..64).filter(|t| t % 4 + t / 4 % 4 + t / 16 <= s).count();
            let exact = (count as f64 / 64.0).ln();
            assert!((ln_uniform_sum_cdf(3, 4, s) - exact).abs() < 1e-12, "s {s}");
        }
    }

    /// Matches of a surface (a plane with a gentle relief) turning and
    /// moving in front of a camera of focal 500, principal-point-centred,
    /// and their F.
    fn rigid_surface(
        rng: &mut ChaCha8Rng,
        count: usize,
    ) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, Matrix3<f64>) {
        let focal = 500.0;
        let r = Rotation3::new(Vector3::new(0.05, -0.1, 0.02));
        let t = Vector3::new(0.6, 0.1, 0.2);
        let (mut p1, mut p2) = (Vec::new(), Vec::new());
        while p1.len() < count {
            let (u, v) = (rng.gen_range(-150.0..150.0), rng.gen_range(-120.0..120.0));
            let depth = 6.0 + 0.002 * u + 0.3 * (v / 40.0_f64).sin();
            let x1 = Vector3::new(u / focal * depth, v / focal * depth, depth);
            let x2 = r * x1 + t;
            p1.push([u, v]);
            p2.push([focal * x2.x / x2.z, focal * x2.y / x2.z]);
        }
        let k_inv = Matrix3::new(1.0 / focal, 0.0, 0.0, 0.0, 1.0 / focal, 0.0, 0.0, 0.0, 1.0);
        let f = k_inv.transpose() * t.cross_matrix() * r.matrix() * k_inv;
        (p1, p2, f)
    }

    #[test]
    fn a_rigid_surface_is_coherent_and_its_matches_slid_along_their_lines_are_not() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let (p1, p2, f) = rigid_surface(&mut rng, 60);
        let all: Vec<usize> = (0..p1.len()).collect();
        let rigid = Correspondences::new(&p1, &p2).unwrap();
        let ln_rigid = ln_incoherence(&rigid, &all, &f);
        assert!(ln_rigid < -50.0, "{ln_rigid}");
        // Each x₂ moved to a random place on its own epipolar line (around
        // the line's point nearest the principal point): the same F fits
        // every match exactly, the neighbourhoods are gone.
        let slid: Vec<[f64; 2]> = p1
            .iter()
            .map(|a| {
                let l = f * Vector3::new(a[0], a[1], 1.0);
                let g2 = l.x * l.x + l.y * l.y;
                let foot = [-l.z * l.x / g2, -l.z * l.y / g2];
                let along = line_direction(&f, *a).unwrap();
                let shift = rng.gen_range(-150.0..150.0);
                [foot[0] + shift * along[0], foot[1] + shift * along[1]]
            })
            .collect();
        let mismatched = Correspondences::new(&p1, &slid).unwrap();
        for (i, x2) in slid.iter().enumerate() {
            let l = f * Vector3::new(p1[i][0], p1[i][1], 1.0);
            let off = (l.x * x2[0] + l.y * x2[1] + l.z) / l.x.hypot(l.y);
            assert!(off.abs() < 1e-9, "match {i} off its line by {off}");
        }
        let ln_slid = ln_incoherence(&mismatched, &all, &f);
        assert!(ln_slid > (0.01f64).ln(), "{ln_slid}");
    }
}
