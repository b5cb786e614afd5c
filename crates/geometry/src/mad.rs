//! Medians and median absolute deviations: the robust scale of the IRLS
//! step (Eq. 34, `σ = 1.4826 · MAD`). The public forms select on `f64`;
//! the IRLS loop selects on order-preserving integer keys in a reusable
//! buffer (same results, faster selection).

/// Median absolute deviation `median(|v − median(v)|)` (the MAD of Eq. 34,
/// without the 1.4826 factor). The median of an even count is the mean of
/// the two middle values. NaN for an empty slice. `scratch` is overwritten.
///
/// ```
/// let mut scratch = Vec::new();
/// let mad = geometry::median_absolute_deviation(&[1.0, 2.0, 3.0, 4.0, 100.0], &mut scratch);
/// assert_eq!(mad, 1.0);
/// ```
pub fn median_absolute_deviation(values: &[f64], scratch: &mut Vec<f64>) -> f64 {
    scratch.clear();
    scratch.extend_from_slice(values);
    let center = median_in_place(scratch);
    for v in scratch.iter_mut() {
        *v = (*v - center).abs();
    }
    median_in_place(scratch)
}

/// Median of `values` (reordered in place): the middle value, or the mean of
/// the two middle values for an even count; NaN when empty.
pub fn median_in_place(values: &mut [f64]) -> f64 {
    let n = values.len();
    if n == 0 {
        return f64::NAN;
    }
    let (lower, &mut middle, _) = values.select_nth_unstable_by(n / 2, f64::total_cmp);
    if n % 2 == 1 {
        middle
    } else {
        let below = lower.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        0.5 * (below + middle)
    }
}

/// Order-preserving map from `f64` (IEEE total order, as `f64::total_cmp`)
/// to `u64`, so that medians are selected with integer comparisons.
#[inline(always)]
fn order_key(v: f64) -> u64 {
    // Negative: all bits flipped; otherwise the sign bit set. Without a
    // branch: the arithmetic shift spreads the sign over the word.
    let bits = v.to_bits();
    bits ^ (((bits as i64 >> 63) as u64) | (1 << 63))
}

/// Inverse of [`order_key`].
#[inline(always)]
fn from_order_key(key: u64) -> f64 {
    f64::from_bits(if key >> 63 == 1 {
        key & !(1 << 63)
    } else {
        !key
    })
}

/// Median of the values behind `keys` (reordered), with the conventions of
/// [`median_in_place`].
fn median_of_keys(keys: &mut [u64]) -> f64 {
    let n = keys.len();
    if n == 0 {
        return f64::NAN;
    }
    let (lower, middle, _) = keys.select_nth_unstable(n / 2);
    let middle = from_order_key(*middle);
    if n % 2 == 1 {
        middle
    } else {
        let below = lower.iter().copied().max().map_or(f64::NAN, from_order_key);
        0.5 * (below + middle)
    }
}

/// [`median_absolute_deviation`] with integer-key selection and a
/// reusable key buffer.
pub(crate) fn mad_by_keys(values: &[f64], keys: &mut Vec<u64>) -> f64 {
    keys.clear();
    keys.extend(values.iter().map(|&v| order_key(v)));
    let center = median_of_keys(keys);
    keys.clear();
    keys.extend(values.iter().map(|&v| order_key((v - center).abs())));
    median_of_keys(keys)
}

/// The MAD of `values` when it is below `limit`, `None` when it is certainly
/// `>= limit`: after the median `m`, counting the deviations `|v − m| <
/// limit` decides the case without the second selection when fewer than
/// half of them are below the limit.
pub(crate) fn mad_below(values: &[f64], keys: &mut Vec<u64>, limit: f64) -> Option<f64> {
    let n = values.len();
    keys.clear();
    keys.extend(values.iter().map(|&v| order_key(v)));
    let center = median_of_keys(keys);
    let below = values
        .iter()
        .map(|&v| usize::from((v - center).abs() < limit))
        .sum::<usize>();
    // The lower middle deviation (rank (n − 1) / 2) is >= limit, so the
    // median of the deviations (of both middles when n is even) is too.
    if n > 0 && below <= (n - 1) / 2 {
        return None;
    }
    keys.clear();
    keys.extend(values.iter().map(|&v| order_key((v - center).abs())));
    let mad = median_of_keys(keys);
    if mad >= limit {
        None
    } else {
        Some(mad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_matches_sorting() {
        let data = [5.0, -1.0, 3.5, 2.0, 8.0, 0.0, 3.5, -7.25];
        for len in 1..=data.len() {
            let mut sorted = data[..len].to_vec();
            sorted.sort_by(f64::total_cmp);
            let expected = if len % 2 == 1 {
                sorted[len / 2]
            } else {
                0.5 * (sorted[len / 2 - 1] + sorted[len / 2])
            };
            let mut v = data[..len].to_vec();
            assert_eq!(median_in_place(&mut v), expected, "len {len}");
        }
        assert!(median_in_place(&mut []).is_nan());
    }

    #[test]
    fn key_medians_equal_the_float_medians() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 20.0
        };
        let (mut keys, mut scratch) = (Vec::new(), Vec::new());
        for n in 1..60 {
            let mut values: Vec<f64> = (0..n).map(|_| next()).collect();
            if n % 7 == 0 {
                values[0] = -0.0;
                values[n / 2] = f64::INFINITY;
            }
            for v in &values {
                assert_eq!(from_order_key(order_key(*v)).to_bits(), v.to_bits());
            }
            let expected = median_absolute_deviation(&values, &mut scratch);
            assert_eq!(mad_by_keys(&values, &mut keys), expected, "n {n}");
            for limit in [0.0, expected * 0.999, expected, expected * 1.001, 100.0] {
                match mad_below(&values, &mut keys, limit) {
                    Some(mad) => assert!(mad == expected && mad < limit, "n {n}"),
                    None => assert!(expected >= limit, "n {n}, limit {limit}"),
                }
            }
        }
    }

    #[test]
    fn mad_of_a_known_sample() {
        let mut scratch = Vec::new();
        // median 2.5; deviations 1.5, 0.5, 0.5, 1.5 -> MAD 1.0
        assert_eq!(
            median_absolute_deviation(&[1.0, 2.0, 3.0, 4.0], &mut scratch),
            1.0
        );
    }
}
