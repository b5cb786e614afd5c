//! Prototype (not adopted): the spatial coherence of a group, a contrario. A motion is
//! an object: many of its matches' nearest matches in (x₁, y₁, x₂, y₂) are
//! its own. A group of k matches drawn at random among N has each
//! neighbour in it with probability (k − 1)/(N − 1).

use super::binomial::ln_binomial_tail;
use geometry::Correspondences;
use rstar::primitives::GeomWithData;
use rstar::RTree;

/// Neighbours per match.
pub const K: usize = 8;

/// Every match in an R*-tree over (x₁, y₁, x₂, y₂).
pub struct Space {
    tree: RTree<GeomWithData<[f64; 4], u32>>,
    coords: Vec<[f64; 4]>,
}

impl Space {
    pub fn new(points: &Correspondences) -> Self {
        let coords: Vec<[f64; 4]> = (0..points.len())
            .map(|m| {
                let (p, q) = (points.point1(m), points.point2(m));
                [p[0], p[1], q[0], q[1]]
            })
            .collect();
        let tree = RTree::bulk_load(
            coords
                .iter()
                .enumerate()
                .map(|(m, &c)| GeomWithData::new(c, m as u32))
                .collect(),
        );
        Self { tree, coords }
    }

    /// `ln(tests · P(Bin(k K, (k − 1)/(N − 1)) ≥ X))`, X the neighbours of
    /// the group's matches that are in the group.
    pub fn ln_nfa(&self, group: &[usize], ln_tests: f64) -> f64 {
        let n = self.coords.len();
        let k = group.len();
        if k < 2 || n < 3 {
            return f64::INFINITY;
        }
        let mut member = vec![false; n];
        group.iter().for_each(|&m| member[m] = true);
        let within: usize = group
            .iter()
            .map(|&m| {
                crate::sampling::nearest(&self.tree, self.coords[m], m, K)
                    .iter()
                    .filter(|&&j| member[j as usize])
                    .count()
            })
            .sum();
        let p = (k - 1) as f64 / (n - 1) as f64;
        ln_tests + ln_binomial_tail((k * K) as u64, within as u64, p)
    }
}
