//! The per-hypothesis local test (Eq. 36) and the scene-level KDE focal
//! consensus with its band filter (Eq. 37), docs/method.md steps 5 and 6.

use serde::{Deserialize, Serialize};

use crate::peaks::find_peaks;

/// The local test of Eq. 36: `f1 > 0`, `f2 > 0` and
/// `|f1 - f2| / f_avg < tau_diff` with `f_avg = (f1 + f2) / 2`.
/// NaN anywhere gives `false`.
///
/// ```
/// assert!(focal::passes_local_test(1000.0, 1040.0, 0.05));
/// assert!(!focal::passes_local_test(1000.0, 1100.0, 0.05));
/// assert!(!focal::passes_local_test(-1000.0, -1000.0, 0.05));
/// ```
pub fn passes_local_test(f1: f64, f2: f64, tau_diff: f64) -> bool {
    if !(f1 > 0.0 && f2 > 0.0) {
        return false;
    }
    let f_avg = 0.5 * (f1 + f2);
    (f1 - f2).abs() / f_avg < tau_diff
}

/// The band of Eq. 37: `|f_avg - f_peak| / f_peak <= tau_range`. False when
/// `f_peak <= 0` or any argument is NaN.
pub fn within_band(f_avg: f64, f_peak: f64, tau_range: f64) -> bool {
    f_peak > 0.0 && (f_avg - f_peak).abs() / f_peak <= tau_range
}

/// Indices `i` of `f_avgs` with [`within_band`]`(f_avgs[i], f_peak,
/// tau_range)`, in increasing order (the hypotheses the band keeps,
/// Eq. 37).
pub fn band_indices(f_avgs: &[f64], f_peak: f64, tau_range: f64) -> Vec<usize> {
    f_avgs
        .iter()
        .enumerate()
        .filter(|(_, &v)| within_band(v, f_peak, tau_range))
        .map(|(i, _)| i)
        .collect()
}

/// Parameters of [`focal_consensus`] (docs/method.md step 6).
///
/// Defaults (serde and [`Default`]): 512 grid points between the 1st and
/// 99th percentiles, peaks with prominence `>= 0.05 * max density` and at
/// least 10 grid cells apart.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ConsensusParams {
    /// Number of KDE grid points. Default 512.
    pub grid_points: usize,
    /// Lower end of the grid, a percentile of the values (0..=100). Default 1.
    pub low_percentile: f64,
    /// Upper end of the grid, a percentile of the values (0..=100). Default 99.
    pub high_percentile: f64,
    /// Minimum peak prominence as a fraction of the maximum density.
    /// Default 0.05.
    pub rel_prominence: f64,
    /// Minimum distance between peaks, grid cells. Default 10.
    pub min_peak_distance: usize,
}

impl Default for ConsensusParams {
    fn default() -> Self {
        Self {
            grid_points: 512,
            low_percentile: 1.0,
            high_percentile: 99.0,
            rel_prominence: 0.05,
            min_peak_distance: 10,
        }
    }
}

/// The result of [`focal_consensus`]: the KDE on its grid, the peaks and
/// the consensus focal length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FocalConsensus {
    /// The grid, `linspace(P_low, P_high, grid_points)`.
    pub grid: Vec<f64>,
    /// The Gaussian KDE at each grid point (Eq. 37).
    pub density: Vec<f64>,
    /// The bandwidth h.
    pub bandwidth: f64,
    /// Grid indices of the peaks kept (scipy `find_peaks` semantics), in
    /// increasing order.
    pub peaks: Vec<usize>,
    /// The grid value of the highest peak, or the median of the values when
    /// there is no peak.
    pub f_peak: f64,
    /// True when `f_peak` is the median (no peak was found).
    pub from_median: bool,
    /// Number of finite values used.
    pub n: usize,
}

/// The scene-level focal consensus of docs/method.md step 6 (Eq. 37) on the
/// `f_avg` values that passed the local test:
///
/// - Gaussian KDE `p(f) = 1/(n h) sum_i phi((f - f_i) / h)` with
///   `phi(z) = exp(-z^2/2) / sqrt(2 pi)` and the bandwidth
///   `h = 1.06 * std * n^(-1/5)` (std with ddof 0; `h = 1` when `n = 1` or
///   `std = 0`; at least `1e-9`);
/// - evaluated on `grid_points` points evenly spaced between the
///   `low_percentile` and `high_percentile` percentiles of the values
///   (numpy's linear interpolation);
/// - peaks found with [`find_peaks`] (prominence `>= rel_prominence * max
///   density`, distance `>= min_peak_distance`; none when the maximum density
///   is not positive);
/// - `f_peak` = the grid value of the highest peak (the first on ties), or
///   the median of the values when no peak survives.
///
/// Non-finite values are ignored. Returns `None` when no finite value is
/// left.
///
/// ```
/// use focal::{focal_consensus, band_indices, ConsensusParams};
/// let values: Vec<f64> = (0..200).map(|i| 1000.0 + ((i * 37) % 101) as f64 - 50.0).collect();
/// let c = focal_consensus(&values, &ConsensusParams::default()).unwrap();
/// assert_eq!(c.grid.len(), 512);
/// assert!((c.f_peak - 1000.0).abs() < 60.0);
/// let kept = band_indices(&values, c.f_peak, 0.25);
/// assert_eq!(kept.len(), values.len());
/// assert!(focal_consensus(&[], &ConsensusParams::default()).is_none());
/// ```
pub fn focal_consensus(values: &[f64], params: &ConsensusParams) -> Option<FocalConsensus> {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if sorted.is_empty() {
        return None;
    }
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let bandwidth = kde_bandwidth(&sorted);
    let lo = percentile_sorted(&sorted, params.low_percentile);
    let hi = percentile_sorted(&sorted, params.high_percentile);
    let grid = linspace(lo, hi, params.grid_points);
    let density = gaussian_kde(&sorted, &grid, bandwidth);
    let max_density = density.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let peaks = if max_density > 0.0 {
        find_peaks(
            &density,
            Some(params.rel_prominence * max_density),
            Some(params.min_peak_distance),
        )
        .indices
    } else {
        Vec::new()
    };
    let highest = peaks
        .iter()
        .copied()
        .fold(None, |best: Option<usize>, i| match best {
            Some(b) if density[b] >= density[i] => Some(b),
            _ => Some(i),
        });
    let (f_peak, from_median) = match highest {
        Some(i) => (grid[i], false),
        None => (median_sorted(&sorted), true),
    };
    Some(FocalConsensus {
        grid,
        density,
        bandwidth,
        peaks,
        f_peak,
        from_median,
        n,
    })
}

/// The KDE bandwidth of Eq. 37: `h = 1.06 * std * n^(-1/5)` with the
/// population standard deviation (ddof 0); `h = 1` when `n <= 1` or
/// `std = 0`; never below `1e-9`.
pub fn kde_bandwidth(values: &[f64]) -> f64 {
    let n = values.len();
    if n <= 1 {
        return 1.0;
    }
    let nf = n as f64;
    let mean = values.iter().sum::<f64>() / nf;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / nf;
    let std = var.sqrt();
    if std.is_nan() || std <= 0.0 {
        return 1.0;
    }
    (1.06 * std * nf.powf(-0.2)).max(1e-9)
}

/// The Gaussian KDE of Eq. 37 at each grid point:
/// `p(g) = 1/(n h) sum_i exp(-((g - v_i)/h)^2 / 2) / sqrt(2 pi)`.
/// Zero everywhere for an empty sample.
pub fn gaussian_kde(values: &[f64], grid: &[f64], bandwidth: f64) -> Vec<f64> {
    if values.is_empty() {
        return vec![0.0; grid.len()];
    }
    let norm = 1.0 / ((2.0 * std::f64::consts::PI).sqrt() * bandwidth * values.len() as f64);
    let inv_h = 1.0 / bandwidth;
    grid.iter()
        .map(|&g| {
            values
                .iter()
                .map(|&v| {
                    let z = (g - v) * inv_h;
                    (-0.5 * z * z).exp()
                })
                .sum::<f64>()
                * norm
        })
        .collect()
}

/// `num` evenly spaced values from `start` to `stop` inclusive, as
/// `numpy.linspace` computes them (`start + i * step`, the last set to
/// `stop`).
pub fn linspace(start: f64, stop: f64, num: usize) -> Vec<f64> {
    match num {
        0 => Vec::new(),
        1 => vec![start],
        _ => {
            let div = (num - 1) as f64;
            let step = (stop - start) / div;
            let mut out: Vec<f64> = (0..num)
                .map(|i| {
                    if step == 0.0 {
                        start + (i as f64 / div) * (stop - start)
                    } else {
                        start + i as f64 * step
                    }
                })
                .collect();
            out[num - 1] = stop;
            out
        }
    }
}

/// The `q`-th percentile (0..=100) of ascending-sorted values with numpy's
/// default "linear" method: virtual index `(n - 1) q / 100`, linear
/// interpolation between its neighbours. NaN for an empty slice.
pub fn percentile_sorted(sorted: &[f64], q: f64) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    let quantile = q / 100.0;
    // numpy: n * q + (alpha + q * (1 - alpha - beta)) - 1 with
    // alpha = beta = 1, i.e. n * q + (1 - q) - 1.
    let virtual_index = n as f64 * quantile + (1.0 - quantile) - 1.0;
    if virtual_index.is_nan() || virtual_index < 0.0 {
        return sorted[0];
    }
    if virtual_index >= (n - 1) as f64 {
        return sorted[n - 1];
    }
    let below = virtual_index.floor();
    let gamma = virtual_index - below;
    let i = below as usize;
    lerp(sorted[i], sorted[i + 1], gamma)
}

/// numpy's `_lerp`: `a + (b - a) t`, computed from `b` when `t >= 0.5`.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    let diff = b - a;
    if t >= 0.5 {
        b - diff * (1.0 - t)
    } else {
        a + diff * t
    }
}

/// The median of ascending-sorted values (mean of the two middle values for
/// an even count). NaN for an empty slice.
pub fn median_sorted(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn consensus_matches_numpy_scipy_reference() {
        // Reference: numpy.percentile / numpy.linspace / the reference
        // kde_1d and scipy.signal.find_peaks(prominence=0.05*max,
        // distance=10) on the same values (numpy 2.4.6, scipy 1.17.1).
        let mut v: Vec<f64> = (0..150)
            .map(|i| {
                let i = i as f64;
                1000.0 + 120.0 * (0.37 * i).sin() + 15.0 * (2.1 * i).cos()
            })
            .collect();
        v.extend((0..60).map(|j| 1400.0 + 20.0 * (1.7 * j as f64).sin()));
        let c = focal_consensus(&v, &ConsensusParams::default()).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
        assert!(close(c.grid[0], 869.3422010338137));
        assert!(close(c.grid[511], 1419.822380088058));
        assert!(close(c.bandwidth, 70.63789149153736));
        // Local maxima at 138 and 493; 493 lacks the prominence.
        assert_eq!(c.peaks, vec![138]);
        assert!(close(c.f_peak, 1018.0041671971908));
        assert!(!c.from_median);
        for (k, want) in [
            (0, 0.0014760104126232002),
            (100, 0.0022014169818043963),
            (138, 0.0022284871590041518),
            (255, 0.0013417896877760402),
            (511, 0.0015234120674863488),
        ] {
            assert!(close(c.density[k], want), "density[{k}] = {}", c.density[k]);
        }
        assert!(close(
            median_sorted(&{
                let mut s = v.clone();
                s.sort_by(f64::total_cmp);
                s
            }),
            1072.0404939046202
        ));
    }

    #[test]
    fn percentiles_follow_numpy_linear() {
        let s = [1.0, 2.0, 4.0, 8.0];
        // numpy.percentile([1,2,4,8], [0, 1, 50, 99, 100])
        assert_eq!(percentile_sorted(&s, 0.0), 1.0);
        assert!((percentile_sorted(&s, 1.0) - 1.03).abs() < 1e-12);
        assert_eq!(percentile_sorted(&s, 50.0), 3.0);
        assert!((percentile_sorted(&s, 99.0) - 7.88).abs() < 1e-12);
        assert_eq!(percentile_sorted(&s, 100.0), 8.0);
        assert!(percentile_sorted(&[], 50.0).is_nan());
    }

    #[test]
    fn linspace_matches_numpy() {
        assert_eq!(linspace(0.0, 1.0, 5), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(linspace(3.0, 3.0, 3), vec![3.0, 3.0, 3.0]);
        assert_eq!(linspace(2.0, 5.0, 1), vec![2.0]);
        assert!(linspace(2.0, 5.0, 0).is_empty());
    }

    #[test]
    fn single_value_and_constant_values_fall_back_to_the_median() {
        let c = focal_consensus(&[1234.0], &ConsensusParams::default()).unwrap();
        assert_eq!(c.bandwidth, 1.0);
        assert!(c.peaks.is_empty() && c.from_median);
        assert_eq!(c.f_peak, 1234.0);
        let c = focal_consensus(&[800.0; 7], &ConsensusParams::default()).unwrap();
        assert_eq!(c.bandwidth, 1.0);
        assert_eq!(c.f_peak, 800.0);
        assert!(c.from_median);
    }

    #[test]
    fn non_finite_values_are_ignored_and_empty_input_is_none() {
        assert!(focal_consensus(&[], &ConsensusParams::default()).is_none());
        assert!(focal_consensus(&[f64::NAN, f64::INFINITY], &ConsensusParams::default()).is_none());
        let a = focal_consensus(
            &[900.0, f64::NAN, 1000.0, 1100.0],
            &ConsensusParams::default(),
        )
        .unwrap();
        let b = focal_consensus(&[900.0, 1000.0, 1100.0], &ConsensusParams::default()).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.n, 3);
    }

    #[test]
    fn local_test_and_band() {
        assert!(passes_local_test(1000.0, 1000.0, 0.05));
        // |1000 - 1050| / 1025 = 0.0488 < 0.05; 1000 vs 1052: 0.0507.
        assert!(passes_local_test(1000.0, 1050.0, 0.05));
        assert!(!passes_local_test(1000.0, 1052.0, 0.05));
        assert!(!passes_local_test(0.0, 1000.0, 0.05));
        assert!(!passes_local_test(f64::NAN, 1000.0, 0.05));
        assert!(within_band(1250.0, 1000.0, 0.25));
        assert!(within_band(750.0, 1000.0, 0.25));
        assert!(!within_band(1250.1, 1000.0, 0.25));
        assert!(!within_band(f64::NAN, 1000.0, 0.25));
        assert!(!within_band(100.0, 0.0, 0.25));
        assert_eq!(
            band_indices(&[700.0, 1000.0, f64::NAN, 1200.0, 1300.0], 1000.0, 0.25),
            vec![1, 3]
        );
    }
}
