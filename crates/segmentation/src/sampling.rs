//! Minimal samples of Algorithm 1 step 1, reproducible per seed.
//!
//! Hypothesis `j` draws its sample from its own ChaCha8 stream `j` under a
//! key expanded from the seed, so the samples — and with them the labels —
//! are the same for any number of threads and do not depend on anything but
//! the seed, the index and the number of points. Localized sampling
//! ([`Sampling::Localized`]) draws from the same streams; its neighbourhoods
//! are computed once per scene ([`MinimalSampler::new`]).

use crate::{CoInlierKernel, Sampling};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rstar::primitives::GeomWithData;
use rstar::RTree;

/// SplitMix64's output function (Steele, Lea, Flood 2014): a bijective mix
/// of 64 bits.
///
/// ```
/// assert_eq!(segmentation::splitmix64(0), 0xe220a8397b1dcdaf);
/// ```
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The RNG of hypothesis `index` (Algorithm 1 step 1): a ChaCha8 key of four
/// successive SplitMix64 outputs starting from `seed`, and stream number
/// `index`.
///
/// ```
/// use rand::Rng;
/// let mut a = segmentation::hypothesis_rng(12345, 7);
/// let mut b = segmentation::hypothesis_rng(12345, 7);
/// let mut c = segmentation::hypothesis_rng(12345, 8);
/// let (x, y, z): (u64, u64, u64) = (a.gen(), b.gen(), c.gen());
/// assert_eq!(x, y);
/// assert_ne!(x, z);
/// ```
pub fn hypothesis_rng(seed: u64, index: usize) -> ChaCha8Rng {
    let mut state = seed;
    let mut key = [0u8; 32];
    for chunk in key.chunks_exact_mut(8) {
        state = splitmix64(state);
        chunk.copy_from_slice(&state.to_le_bytes());
    }
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(index as u64);
    rng
}

/// The minimal sample of hypothesis `index`: `mss_size` distinct indices
/// drawn uniformly from `0..n` (Algorithm 1 step 1). Needs `mss_size ≤ n`.
pub fn minimal_sample(seed: u64, index: usize, n: usize, mss_size: usize) -> Vec<usize> {
    let mut rng = hypothesis_rng(seed, index);
    rand::seq::index::sample(&mut rng, n, mss_size).into_vec()
}

/// The neighbourhood of localized sampling for `n` matches and samples of
/// `sample_size`: `k = min(n − 1, max(3 · sample_size, ⌈n / 20⌉))` nearest
/// matches. A twentieth of the scene keeps a sample inside a motion that
/// holds a few percent of the matches; at least three samples' worth
/// keeps the samples of a small scene apart. It holds `sample_size − 1`
/// matches or more whenever `n ≥ sample_size`.
///
/// ```
/// assert_eq!(segmentation::neighbourhood_size(3000, 5), 150);
/// assert_eq!(segmentation::neighbourhood_size(200, 8), 24);
/// assert_eq!(segmentation::neighbourhood_size(10, 8), 9);
/// ```
pub fn neighbourhood_size(n: usize, sample_size: usize) -> usize {
    n.saturating_sub(1)
        .min((3 * sample_size).max(n.div_ceil(20)))
}

/// The minimal samples of one scene (Algorithm 1 step 1), uniform or
/// localized ([`Sampling`]). Built once per scene; sample `j` depends only
/// on the seed, `j` and the points, never on the thread that draws it.
#[derive(Debug, Clone)]
pub struct MinimalSampler {
    n: usize,
    /// The `k` nearest other matches (image 1) of each match, nearest
    /// first, ties by index, flattened; empty for uniform sampling.
    neighbours: Vec<u32>,
    k: usize,
    /// [`Sampling::Guided`]: the even samples uniform (or guided, after
    /// the first batch), the odd ones localized.
    mixed: bool,
}

impl MinimalSampler {
    /// The sampler of `points1` (image 1) for samples of `sample_size`:
    /// for [`Sampling::Localized`] and [`Sampling::Guided`] the
    /// [`neighbourhood_size`] nearest
    /// neighbours of every match, found in an R*-tree (`rstar`).
    pub fn new(points1: &[[f64; 2]], sampling: Sampling, sample_size: usize) -> Self {
        let n = points1.len();
        if sampling == Sampling::Uniform {
            return Self {
                n,
                neighbours: Vec::new(),
                k: 0,
                mixed: false,
            };
        }
        let k = neighbourhood_size(n, sample_size);
        let tree = RTree::bulk_load(
            points1
                .iter()
                .enumerate()
                .map(|(i, &p)| GeomWithData::new(p, i as u32))
                .collect(),
        );
        let neighbours = (0..n)
            .into_par_iter()
            .flat_map_iter(|i| nearest(&tree, points1[i], i, k))
            .collect();
        Self {
            n,
            neighbours,
            k,
            mixed: sampling == Sampling::Guided,
        }
    }

    /// The neighbourhood of match `i` (empty for uniform sampling).
    pub fn neighbourhood(&self, i: usize) -> &[u32] {
        if self.neighbours.is_empty() {
            &[]
        } else {
            &self.neighbours[i * self.k..(i + 1) * self.k]
        }
    }

    /// The sample of hypothesis `index` as [`sample`](Self::sample) draws
    /// it, except that with a `guide` the even (uniform) turns of guided
    /// sampling are guided ([`CoInlierKernel::sample`], from stream `index`
    /// of [`hypothesis_rng`]).
    pub fn sample_guided(
        &self,
        guide: Option<&CoInlierKernel>,
        seed: u64,
        index: usize,
        size: usize,
    ) -> Vec<usize> {
        match guide {
            Some(kernel) if self.mixed && index % 2 == 0 => {
                kernel.sample(&mut hypothesis_rng(seed, index), size)
            }
            _ => self.sample(seed, index, size),
        }
    }

    /// The sample of hypothesis `index`: `size` distinct matches. Uniform
    /// (and the even indices of guided sampling): [`minimal_sample`].
    /// Localized (and the odd indices of guided): from stream `index` of
    /// [`hypothesis_rng`], the first match uniformly, then `size − 1`
    /// distinct matches uniformly among its neighbourhood (all other
    /// matches when the neighbourhood is too small). At most `n` matches.
    pub fn sample(&self, seed: u64, index: usize, size: usize) -> Vec<usize> {
        let size = size.min(self.n);
        let uniform_turn = self.mixed && index % 2 == 0;
        if self.neighbours.is_empty() || size == 0 || uniform_turn {
            return minimal_sample(seed, index, self.n, size);
        }
        let mut rng = hypothesis_rng(seed, index);
        let first = rng.gen_range(0..self.n);
        let mut sample = Vec::with_capacity(size);
        sample.push(first);
        let hood = self.neighbourhood(first);
        if hood.len() + 1 >= size {
            let picks = rand::seq::index::sample(&mut rng, hood.len(), size - 1);
            sample.extend(picks.into_iter().map(|t| hood[t] as usize));
        } else {
            // Wider: every other match.
            let picks = rand::seq::index::sample(&mut rng, self.n - 1, size - 1);
            sample.extend(picks.into_iter().map(|t| t + usize::from(t >= first)));
        }
        sample
    }
}

/// The `k` nearest points of `tree` to `p` other than `self_index`, nearest
/// first and ties by index: every point as close as the `k`-th is fetched
/// before the sort, so the list equals a brute-force one. Points of any
/// dimension (image 1 here; (x₁, y₁, x₂, y₂) in the selection's vote).
pub(crate) fn nearest<P: rstar::Point<Scalar = f64>>(
    tree: &RTree<GeomWithData<P, u32>>,
    p: P,
    self_index: usize,
    k: usize,
) -> Vec<u32> {
    let mut found: Vec<(f64, u32)> = Vec::with_capacity(k + 1);
    for (entry, d2) in tree.nearest_neighbor_iter_with_distance_2(&p) {
        if entry.data as usize == self_index {
            continue;
        }
        if found.len() >= k && found.last().is_some_and(|&(last, _)| d2 > last) {
            break;
        }
        found.push((d2, entry.data));
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    found.into_iter().take(k).map(|(_, i)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_matches_the_reference_sequence() {
        // The first outputs of SplitMix64 seeded with 1234567 (Vigna's
        // splitmix64.c): each output is the mix of the state advanced once.
        let mut state: u64 = 1234567;
        let mut outputs = Vec::new();
        for _ in 0..3 {
            outputs.push(splitmix64(state));
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        }
        assert_eq!(
            outputs,
            [
                6457827717110365317,
                3203168211198807973,
                9817491932198370423
            ]
        );
    }

    #[test]
    fn samples_are_distinct_in_range_and_reproducible() {
        for j in 0..200 {
            let s = minimal_sample(1, j, 30, 8);
            assert_eq!(s.len(), 8);
            let mut d = s.clone();
            d.sort_unstable();
            d.dedup();
            assert_eq!(d.len(), 8);
            assert!(s.iter().all(|&i| i < 30));
            assert_eq!(s, minimal_sample(1, j, 30, 8));
        }
        assert_ne!(minimal_sample(1, 0, 1000, 8), minimal_sample(2, 0, 1000, 8));
        assert_ne!(minimal_sample(1, 0, 1000, 8), minimal_sample(1, 1, 1000, 8));
    }

    /// Points on a coarse grid (many equal distances and duplicates).
    fn grid_points(n: usize, salt: u64) -> Vec<[f64; 2]> {
        (0..n as u64)
            .map(|i| {
                let h = splitmix64(i ^ salt.rotate_left(17));
                [(h % 13) as f64, ((h >> 8) % 11) as f64]
            })
            .collect()
    }

    /// The `k` nearest other points by brute force, ties by index.
    fn brute_force(points: &[[f64; 2]], i: usize, k: usize) -> Vec<u32> {
        let d2 = |j: usize| {
            let (dx, dy) = (points[j][0] - points[i][0], points[j][1] - points[i][1]);
            dx * dx + dy * dy
        };
        let mut all: Vec<usize> = (0..points.len()).filter(|&j| j != i).collect();
        all.sort_by(|&a, &b| d2(a).total_cmp(&d2(b)).then(a.cmp(&b)));
        all.into_iter().take(k).map(|j| j as u32).collect()
    }

    #[test]
    fn uniform_sampler_is_minimal_sample() {
        let points = grid_points(50, 3);
        let sampler = MinimalSampler::new(&points, Sampling::Uniform, 8);
        for j in 0..100 {
            assert_eq!(sampler.sample(9, j, 8), minimal_sample(9, j, 50, 8));
        }
    }

    #[test]
    fn unguided_guided_sampling_alternates_uniform_and_localized() {
        let points = grid_points(200, 4);
        let uniform = MinimalSampler::new(&points, Sampling::Uniform, 5);
        let localized = MinimalSampler::new(&points, Sampling::Localized, 5);
        let mixed = MinimalSampler::new(&points, Sampling::Guided, 5);
        assert_eq!(mixed.neighbourhood(7), localized.neighbourhood(7));
        for j in 0..100 {
            let expected = if j % 2 == 0 { &uniform } else { &localized };
            assert_eq!(
                mixed.sample_guided(None, 3, j, 5),
                expected.sample(3, j, 5),
                "sample {j}"
            );
        }
    }

    #[test]
    fn guided_sampling_replaces_the_uniform_turns() {
        let points = grid_points(120, 6);
        let guided = MinimalSampler::new(&points, Sampling::Guided, 5);
        let mut co = crate::CoInliers::new(120, 30);
        for h in 0..30 {
            co.add(&(h..h + 40).collect::<Vec<_>>());
        }
        let kernel = co.kernel();
        for j in 0..60 {
            assert_eq!(guided.sample_guided(None, 3, j, 5), guided.sample(3, j, 5));
            let expected = if j % 2 == 0 {
                kernel.sample(&mut hypothesis_rng(3, j), 5)
            } else {
                guided.sample(3, j, 5)
            };
            assert_eq!(guided.sample_guided(Some(kernel), 3, j, 5), expected, "{j}");
        }
    }

    #[test]
    fn neighbourhoods_are_the_brute_force_nearest() {
        for (n, size) in [(9, 8), (60, 5), (400, 7)] {
            let points = grid_points(n, n as u64);
            let sampler = MinimalSampler::new(&points, Sampling::Localized, size);
            let k = neighbourhood_size(n, size);
            assert!(k + 1 >= size);
            for i in 0..n {
                assert_eq!(
                    sampler.neighbourhood(i),
                    brute_force(&points, i, k),
                    "{n} {i}"
                );
            }
        }
    }

    proptest::proptest! {
        #[test]
        fn localized_samples_are_distinct_and_local(
            n in 8usize..200, size in 5usize..9, seed in 0u64..1000, salt in 0u64..50,
        ) {
            let size = size.min(n);
            let points = grid_points(n, salt);
            let sampler = MinimalSampler::new(&points, Sampling::Localized, size);
            for j in 0..20 {
                let s = sampler.sample(seed, j, size);
                proptest::prop_assert_eq!(s.len(), size);
                let mut d = s.clone();
                d.sort_unstable();
                d.dedup();
                proptest::prop_assert_eq!(d.len(), size);
                let hood = sampler.neighbourhood(s[0]);
                proptest::prop_assert!(s[1..].iter().all(|&i| hood.contains(&(i as u32))));
                proptest::prop_assert_eq!(&s, &sampler.sample(seed, j, size));
            }
        }
    }

    #[test]
    fn a_too_small_neighbourhood_falls_back_to_every_match() {
        // Neighbourhoods of 15 (3 x 5) for samples of 30: every other match.
        let points = grid_points(40, 1);
        let sampler = MinimalSampler::new(&points, Sampling::Localized, 5);
        assert_eq!(sampler.neighbourhood(0).len(), 15);
        for j in 0..50 {
            let mut s = sampler.sample(2, j, 30);
            s.sort_unstable();
            s.dedup();
            assert_eq!(s.len(), 30);
            assert!(s.iter().all(|&i| i < 40));
        }
        // More than there are: all of them, no panic.
        assert_eq!(sampler.sample(2, 0, 60).len(), 40);
    }
}
