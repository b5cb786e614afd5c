use super::*;
use crate::reference;

/// A small deterministic generator (xorshift) for the tests of this module.
struct Xorshift(u64);

impl Xorshift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn uniform(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Values that stress the quantisation: 1, the Eq. 38 minimum, values on
/// and next to the quantisation grid, tiny and subnormal values.
fn awkward_value(rng: &mut Xorshift) -> f64 {
    let k = (rng.next() % (u64::from(Level::MAX) + 1)) as f64;
    match rng.next() % 8 {
        0 => 1.0,
        1 => (-5.0f64).exp(),
        2 => k / LEVELS,
        3 => (k / LEVELS) * (1.0 + f64::EPSILON),
        4 => (k / LEVELS) * (1.0 - f64::EPSILON),
        5 => 1e-300 * rng.uniform(),
        6 => f64::from_bits(1 + rng.next() % 1000),
        _ => rng.uniform(),
    }
}

fn random_matrix(rng: &mut Xorshift, n: usize, m: usize, density: f64) -> PreferenceMatrix {
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|_| {
            (0..m)
                .map(|_| {
                    if rng.uniform() < density {
                        awkward_value(rng)
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect();
    PreferenceMatrix::from_rows(&rows).unwrap()
}

/// Test case `case`: N in `n.0..n.0 + n.1`, M in `m.0..m.0 + m.1`, the
/// density cycling through `densities`.
fn random_case(
    rng: &mut Xorshift,
    case: usize,
    n: (usize, u64),
    m: (usize, u64),
    densities: [f64; 3],
) -> PreferenceMatrix {
    let n = n.0 + (rng.next() % n.1) as usize;
    let m = m.0 + (rng.next() % m.1) as usize;
    random_matrix(rng, n, m, densities[case % 3])
}

/// The states of `p` for the portable kernels and, where the CPU has
/// them, the AVX2 ones.
fn kernel_states(p: &PreferenceMatrix) -> Vec<ContinuousState<'_>> {
    [false, avx2_available()]
        .into_iter()
        .map(|avx2| ContinuousState {
            avx2,
            ..ContinuousState::new(p)
        })
        .collect()
}

/// Merges `removed` into `kept` as the agglomeration does (marked
/// inactive first), leaving the merged cluster's candidates in `fresh`.
fn absorb(
    state: &mut ContinuousState,
    (kept, removed): (usize, usize),
    active: &mut [bool],
    fresh: &mut Vec<(u32, Candidate)>,
) {
    active[removed] = false;
    fresh.clear();
    let merge = Merge {
        kept,
        removed,
        distance: 0.0,
    };
    state.merge(&merge, active, fresh);
}

#[test]
fn quantisation_rounds_up_and_keeps_zero() {
    let mut rng = Xorshift(99);
    assert_eq!(quantise(0.0), 0);
    assert_eq!(quantise(1.0), Level::MAX);
    assert_eq!(quantise(f64::from_bits(1)), 1);
    for _ in 0..100_000 {
        let v = awkward_value(&mut rng);
        let q = quantise(v);
        assert!(f64::from(q) >= v * LEVELS, "q({v}) = {q}");
        assert!(
            f64::from(q) <= v * LEVELS * (1.0 + 1e-12) + 1.0,
            "q({v}) = {q} too large"
        );
    }
}

/// Every candidate the kernels produce, initial or after a merge, is at
/// most the exact distance (a certified lower bound), for both kernel
/// versions.
#[test]
fn bounds_never_exceed_distances() {
    let mut rng = Xorshift(12345);
    for case in 0..60 {
        let p = random_case(&mut rng, case, (2, 40), (1, 300), [0.05, 0.3, 1.0]);
        let n = p.n_points();
        for mut state in kernel_states(&p) {
            let mut pairs = Vec::new();
            state.initial_distances(0..n, &mut pairs);
            for &(i, k, c) in &pairs {
                let d = state.exact_distance(i as usize, k as usize);
                assert!(
                    !c.exact && c.d <= d,
                    "case {case}: ({i}, {k}) bound {} > {d}",
                    c.d
                );
            }
            // Every pair with d < 1 has a candidate.
            let expected = (0..n)
                .flat_map(|i| (i + 1..n).map(move |k| (i, k)))
                .filter(|&(i, k)| state.exact_distance(i, k) < 1.0)
                .count();
            assert!(pairs.len() >= expected);
            let (mut active, mut fresh) = (vec![true; n], Vec::new());
            for removed in (1..n).rev().step_by(3) {
                let kept = (rng.next() as usize) % removed;
                if !active[kept] || !active[removed] {
                    continue;
                }
                absorb(&mut state, (kept, removed), &mut active, &mut fresh);
                for &(k, c) in &fresh {
                    let d = state.exact_distance(kept, k as usize);
                    assert!(
                        c.d <= d,
                        "case {case}: merged ({kept}, {k}) bound {} > {d}",
                        c.d
                    );
                }
            }
        }
    }
}

/// The initial kernel (blocks of rows) and the sweep (one cluster) give
/// a singleton pair the same bound, bit for bit: a refill recomputes
/// dropped initial pairs with the sweep and compares them to the floor.
#[test]
fn initial_bounds_equal_the_sweeps_bit_for_bit() {
    let mut rng = Xorshift(31);
    for case in 0..12 {
        let p = random_case(&mut rng, case, (20, 60), (50, 400), [0.1, 0.5, 0.95]);
        let n = p.n_points();
        for mut state in kernel_states(&p) {
            let avx2 = state.avx2;
            let mut initial = Vec::new();
            state.initial_distances(0..n, &mut initial);
            let active = vec![true; n];
            for i in 0..n {
                let mut swept = Vec::new();
                state.candidates(i, &active, &mut swept);
                let later: Vec<(u32, u64)> = swept
                    .iter()
                    .filter(|&&(k, _)| k as usize > i)
                    .map(|&(k, c)| (k, c.d.to_bits()))
                    .collect();
                let rows: Vec<(u32, u64)> = initial
                    .iter()
                    .filter(|&&(r, _, _)| r as usize == i)
                    .map(|&(_, k, c)| (k, c.d.to_bits()))
                    .collect();
                assert_eq!(rows, later, "case {case}, row {i}, avx2 {avx2}");
            }
        }
    }
}

#[test]
fn portable_kernels_give_the_reference_result() {
    let mut rng = Xorshift(7);
    for case in 0..30 {
        let (n, m) = (
            2 + (rng.next() % 80) as usize,
            1 + (rng.next() % 200) as usize,
        );
        let p = random_matrix(&mut rng, n, m, [0.1, 0.4, 0.9][case % 3]);
        let mut state = ContinuousState::new(&p);
        state.avx2 = false;
        let merges = agglomerate(state, RUN_CAPACITY);
        assert_eq!(
            labels_from_merges(n, merges, SizeRule::MinSize, 0),
            reference::t_linkage(&p, 0),
            "case {case}"
        );
    }
}

/// Consuming the matrix (rows merged in place, absorbed rows freed)
/// leaves every surviving row at exactly its length (its merges are
/// checked in `bounded_runs_give_the_reference_result`).
#[test]
fn owned_rows_stay_at_their_length() {
    let mut rng = Xorshift(44);
    for case in 0..30 {
        let p = random_case(&mut rng, case, (2, 70), (1, 150), [0.05, 0.4, 0.9]);
        let n = p.n_points();
        let mut state = ContinuousState::owning(p);
        let mut active = vec![true; n];
        let mut fresh = Vec::new();
        for removed in (1..n).rev() {
            absorb(&mut state, (0, removed), &mut active, &mut fresh);
            assert_eq!(state.index[0].len(), state.value[0].len());
            assert!(matches!(state.index[0], Cow::Owned(ref v) if v.capacity() == v.len()));
            assert!(state.index[removed].is_empty());
        }
    }
}

/// After merges and in-place compactions (those the rule triggers, and
/// one every 40 merges), the bound matrix holds exactly the quantised
/// exact vector of every active cluster in its slot, and nothing in
/// the other slots.
#[test]
fn compaction_keeps_every_live_column() {
    let mut rng = Xorshift(8);
    let (n, m) = (300, 120);
    let p = random_matrix(&mut rng, n, m, 0.5);
    let mut state = ContinuousState::owning(p);
    let mut active = vec![true; n];
    let mut fresh = Vec::new();
    let mut widths = vec![state.width];
    for removed in (1..n).rev().filter(|r| r % 5 != 0) {
        let kept = (rng.next() as usize) % removed;
        if !active[kept] {
            continue;
        }
        absorb(&mut state, (kept, removed), &mut active, &mut fresh);
        if widths.len() % 40 == 0 && state.width - state.live_slots >= LANES {
            state.compact();
        }
        widths.push(state.width);
    }
    assert!(
        widths.windows(2).filter(|w| w[1] < w[0]).count() >= 3,
        "{widths:?}"
    );
    assert_eq!(state.bounds.len(), m * state.width);
    for (slot, &c) in state.cluster_of_slot.iter().enumerate() {
        let mut expected = vec![0 as Level; m];
        if c != DEAD {
            let c = c as usize;
            assert!(active[c] && state.slot_of_cluster[c] as usize == slot);
            for (&j, &v) in state.index[c].iter().zip(state.value[c].iter()) {
                expected[j as usize] = quantise(v);
            }
        }
        let column: Vec<Level> = (0..m)
            .map(|j| state.bounds[j * state.width + slot])
            .collect();
        assert_eq!(column, expected, "slot {slot}");
    }
}

/// Runs bounded to very few entries (refilled all the time) give the
/// reference merges: the bound changes the memory, not the result.
#[test]
fn bounded_runs_give_the_reference_result() {
    let mut rng = Xorshift(21);
    for case in 0..40 {
        let p = random_case(&mut rng, case, (2, 70), (1, 150), [0.05, 0.3, 0.8]);
        let n = p.n_points();
        let expected = reference::t_linkage(&p, 0);
        for capacity in [1, 2, 3, 7, RUN_CAPACITY] {
            // Borrowing the matrix, and consuming it (rows merged in place).
            for state in [ContinuousState::new(&p), ContinuousState::owning(p.clone())] {
                let merges = agglomerate(state, capacity);
                assert_eq!(
                    labels_from_merges(n, merges, SizeRule::MinSize, 0),
                    expected,
                    "case {case}, capacity {capacity}"
                );
            }
        }
    }
}

/// At a realistic size the bounded heap gives the merges of the
/// unbounded one (every pair kept: the implementation before the bound).
#[test]
fn bounded_runs_equal_the_unbounded_heap_at_large_n() {
    let mut rng = Xorshift(5);
    let p = random_matrix(&mut rng, 900, 250, 0.2);
    let unbounded = agglomerate(ContinuousState::new(&p), usize::MAX);
    assert!(unbounded.len() > 800);
    for capacity in [RUN_CAPACITY, 4] {
        assert_eq!(
            agglomerate(ContinuousState::new(&p), capacity),
            unbounded,
            "capacity {capacity}"
        );
    }
}

#[test]
fn exact_dot_is_the_ordered_sum() {
    let mut rng = Xorshift(3);
    let p = random_matrix(&mut rng, 2, 500, 0.5);
    let (pi, pv) = p.row_support(0);
    let (qi, qv) = p.row_support(1);
    assert_eq!(
        exact_dot(pi, pv, qi, qv).to_bits(),
        crate::ordered_dot(&p.row(0), &p.row(1)).to_bits()
    );
}
