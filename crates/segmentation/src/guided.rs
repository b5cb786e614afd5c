//! Guided sampling from the hypotheses drawn so far (`sampling = "guided"`):
//! the Multi-GS idea (Chin, Yu & Suter, "Accelerated hypothesis generation
//! for multistructure data via preference analysis", TPAMI 2012) with
//! co-inlier counts in place of its top-h rank lists.
//!
//! Two matches of one structure lie within `thr_px` of the same good
//! hypotheses; a match of another structure, or an outlier, shares few of
//! them. So after a batch of hypotheses, a sample whose first match is
//! drawn uniformly takes each next match with probability proportional to
//! the product, over the matches already drawn, of the number of
//! hypotheses that hold both (Chin et al.'s conditional sampling rule, a
//! product of kernel values, with their intersection kernel of top-h
//! hypothesis lists replaced by that count).

use rand::Rng;

/// Which hypotheses hold each match: one bit per hypothesis and match,
/// match-major (`words` 64-bit words a match), and the co-inlier counts of
/// the hypotheses counted so far.
#[derive(Debug, Clone)]
pub struct CoInliers {
    words: usize,
    bits: Vec<u64>,
    hypotheses: usize,
    /// How many of the hypotheses `kernel` counts.
    counted: usize,
    kernel: CoInlierKernel,
}

impl CoInliers {
    /// Room for `capacity` hypotheses over `n` matches (more grow it),
    /// none added.
    pub fn new(n: usize, capacity: usize) -> Self {
        let words = capacity.div_ceil(64).max(1);
        Self {
            words,
            bits: vec![0; n * words],
            hypotheses: 0,
            counted: 0,
            kernel: CoInlierKernel {
                n,
                counts: vec![0.0; n * n],
            },
        }
    }

    /// Adds the next hypothesis, holding the matches `consensus` (indices
    /// below `n`; others are ignored). Past the capacity, the rows grow.
    pub fn add(&mut self, consensus: &[usize]) {
        let h = self.hypotheses;
        if h >= 64 * self.words {
            self.grow();
        }
        let (word, bit) = (h / 64, 1u64 << (h % 64));
        let n = self.kernel.n;
        for &i in consensus.iter().filter(|&&i| i < n) {
            self.bits[i * self.words + word] |= bit;
        }
        self.hypotheses += 1;
    }

    /// Doubles the words of every match's row, keeping its bits.
    fn grow(&mut self) {
        let (n, old) = (self.kernel.n, self.words);
        let new = 2 * old;
        let mut bits = vec![0; n * new];
        for (row, old_row) in bits.chunks_exact_mut(new).zip(self.bits.chunks_exact(old)) {
            row[..old].copy_from_slice(old_row);
        }
        self.bits = bits;
        self.words = new;
    }

    /// Adds a hypothesis that holds nothing (a sample without a fit), so
    /// that hypothesis indices stay aligned.
    pub fn skip(&mut self) {
        self.add(&[]);
    }

    /// The hypotheses added so far.
    pub fn len(&self) -> usize {
        self.hypotheses
    }

    /// Whether no hypothesis has been added.
    pub fn is_empty(&self) -> bool {
        self.hypotheses == 0
    }

    /// The co-inlier counts `K(i, j) = |{h : i and j in h}|` of every pair
    /// over the hypotheses added so far (`K(i, i) = 0`). Only the
    /// hypotheses added since the last call are counted: each call costs
    /// N² times the words they span.
    pub fn kernel(&mut self) -> &CoInlierKernel {
        let (n, w) = (self.kernel.n, self.words);
        let (from, to) = (self.counted, self.hypotheses);
        if n == 0 {
            self.counted = to;
            return &self.kernel;
        }
        // One word at a time, its new hypotheses' bits gathered into one
        // column: each match's row adds the shared bits of every match
        // (contiguous, so it vectorises), and a match none of the new
        // hypotheses holds adds nothing. The counts are integers, exact
        // in f64 in any order.
        let mut column = vec![0u64; n];
        for word in from / 64..to.div_ceil(64) {
            let lo = from.max(64 * word) - 64 * word;
            let hi = to.min(64 * (word + 1)) - 64 * word;
            let high = if hi == 64 { u64::MAX } else { (1u64 << hi) - 1 };
            let mask = high & !((1u64 << lo) - 1);
            for (c, row) in column.iter_mut().zip(self.bits.chunks_exact(w)) {
                *c = row[word] & mask;
            }
            for (i, counts) in self.kernel.counts.chunks_exact_mut(n).enumerate() {
                let bi = column[i];
                if bi == 0 {
                    continue;
                }
                for (k, &bj) in counts.iter_mut().zip(&column) {
                    *k += f64::from((bi & bj).count_ones());
                }
                counts[i] = 0.0;
            }
        }
        self.counted = to;
        &self.kernel
    }
}

/// The co-inlier counts of [`CoInliers::kernel`], row-major `n × n`.
#[derive(Debug, Clone)]
pub struct CoInlierKernel {
    n: usize,
    counts: Vec<f64>,
}

impl CoInlierKernel {
    /// The count of matches `i` and `j`.
    pub fn count(&self, i: usize, j: usize) -> f64 {
        self.counts[i * self.n + j]
    }

    /// A guided sample of `size ≤ n` distinct matches from `rng`: the first
    /// uniformly, each next one with probability proportional to the
    /// product of its counts with those drawn (uniformly among the others
    /// when every product is 0).
    pub fn sample<R: Rng>(&self, rng: &mut R, size: usize) -> Vec<usize> {
        let n = self.n;
        let size = size.min(n);
        let mut sample = Vec::with_capacity(size);
        if size == 0 {
            return sample;
        }
        let first = rng.gen_range(0..n);
        sample.push(first);
        let mut weights = self.counts[first * n..(first + 1) * n].to_vec();
        while sample.len() < size {
            for &s in &sample {
                weights[s] = 0.0;
            }
            let next = draw(rng, &weights).unwrap_or_else(|| uniform_other(rng, n, &sample));
            sample.push(next);
            for (w, &k) in weights
                .iter_mut()
                .zip(&self.counts[next * n..(next + 1) * n])
            {
                *w *= k;
            }
        }
        sample
    }
}

/// An index drawn with probability proportional to `weights` (None when
/// they sum to 0 or are not finite).
fn draw<R: Rng>(rng: &mut R, weights: &[f64]) -> Option<usize> {
    let total: f64 = weights.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let target = rng.gen::<f64>() * total;
    let mut acc = 0.0;
    let mut last = None;
    for (i, &w) in weights.iter().enumerate() {
        if w > 0.0 {
            acc += w;
            last = Some(i);
            if target < acc {
                return Some(i);
            }
        }
    }
    last
}

/// A match of `0..n` not in `taken`, uniformly (needs `taken.len() < n`).
fn uniform_other<R: Rng>(rng: &mut R, n: usize, taken: &[usize]) -> usize {
    let mut k = rng.gen_range(0..n - taken.len());
    for i in 0..n {
        if !taken.contains(&i) {
            if k == 0 {
                return i;
            }
            k -= 1;
        }
    }
    unreachable!("fewer than n matches taken")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{hypothesis_rng, splitmix64};

    /// Random consensus sets over `n` matches.
    fn random_sets(n: usize, count: usize, salt: u64) -> Vec<Vec<usize>> {
        (0..count as u64)
            .map(|h| {
                (0..n)
                    .filter(|&i| splitmix64(h ^ (i as u64) << 20 ^ salt) % 3 == 0)
                    .collect()
            })
            .collect()
    }

    #[test]
    fn the_kernel_counts_the_hypotheses_two_matches_share() {
        let (n, count) = (37, 150);
        let sets = random_sets(n, count, 5);
        let mut co = CoInliers::new(n, count);
        // Counted in uneven steps, across word boundaries: the same counts.
        let mut added = 0;
        for step in [1, 40, 30, 63, 2, 14] {
            sets[added..added + step].iter().for_each(|s| co.add(s));
            added += step;
            co.kernel();
        }
        assert_eq!(added, count);
        let kernel = co.kernel();
        for i in 0..n {
            for j in 0..n {
                let naive = if i == j {
                    0
                } else {
                    sets.iter()
                        .filter(|s| s.contains(&i) && s.contains(&j))
                        .count()
                };
                assert_eq!(kernel.count(i, j), naive as f64, "{i} {j}");
            }
        }
    }

    #[test]
    fn no_match_gives_an_empty_kernel() {
        let mut co = CoInliers::new(0, 10);
        co.add(&[0, 3]);
        co.skip();
        assert_eq!(co.len(), 2);
        co.kernel();
        let mut one = CoInliers::new(1, 10);
        one.add(&[0]);
        assert_eq!(one.kernel().count(0, 0), 0.0);
    }

    #[test]
    fn past_the_capacity_the_rows_grow_and_keep_counting() {
        // Room for 10, 150 added (two growths), counted before and after.
        let (n, count) = (37, 150);
        let sets = random_sets(n, count, 9);
        let mut grown = CoInliers::new(n, 10);
        let mut sized = CoInliers::new(n, count);
        for (h, s) in sets.iter().enumerate() {
            grown.add(s);
            sized.add(s);
            if h == 70 {
                grown.kernel();
            }
        }
        grown.skip();
        assert_eq!(grown.len(), count + 1);
        let (a, b) = (grown.kernel().clone(), sized.kernel());
        assert_eq!(a.counts, b.counts);
        // The hypotheses past the first 64 are in the counts.
        let mut first = CoInliers::new(n, 64);
        sets[..64].iter().for_each(|s| first.add(s));
        assert_ne!(a.counts, first.kernel().counts);
    }

    #[test]
    fn guided_samples_stay_in_the_structure_of_their_first_match() {
        // Two structures (matches 0–19 and 20–39) that no hypothesis
        // shares, and 10 matches (40–49) that no hypothesis holds.
        let n = 50;
        let mut co = CoInliers::new(n, 40);
        for h in 0..40 {
            let set: Vec<usize> = if h % 2 == 0 {
                (0..20).collect()
            } else {
                (20..40).collect()
            };
            co.add(&set);
        }
        let kernel = co.kernel();
        for j in 0..200 {
            let s = kernel.sample(&mut hypothesis_rng(3, j), 5);
            assert_eq!(s, kernel.sample(&mut hypothesis_rng(3, j), 5));
            let mut d = s.clone();
            d.sort_unstable();
            d.dedup();
            assert_eq!(d.len(), 5, "{s:?}");
            assert!(s.iter().all(|&i| i < n));
            if s[0] < 40 {
                let block = s[0] / 20;
                assert!(s.iter().all(|&i| i / 20 == block), "{s:?}");
            }
        }
    }

    #[test]
    fn without_shared_hypotheses_the_sample_is_uniform_and_distinct() {
        let mut co = CoInliers::new(6, 10);
        let kernel = co.kernel();
        let mut seen = [false; 6];
        for j in 0..100 {
            let s = kernel.sample(&mut hypothesis_rng(1, j), 6);
            let mut d = s.clone();
            d.sort_unstable();
            assert_eq!(d, (0..6).collect::<Vec<_>>());
            seen[s[1]] = true;
        }
        assert!(seen.iter().all(|&b| b));
        assert_eq!(kernel.sample(&mut hypothesis_rng(1, 0), 9).len(), 6);
    }
}
