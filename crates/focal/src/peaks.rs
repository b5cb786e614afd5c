//! `scipy.signal.find_peaks` with `prominence` and `distance`, as the KDE
//! focal consensus of Eq. 37 (docs/method.md step 6) uses it.

use serde::{Deserialize, Serialize};

/// The peaks of a 1-D signal and their scipy properties.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Peaks {
    /// Peak indices, increasing (the middle of a plateau, rounded down).
    pub indices: Vec<usize>,
    /// Prominence of each peak.
    pub prominences: Vec<f64>,
    /// Left base of each peak (index of the minimum its prominence refers to).
    pub left_bases: Vec<usize>,
    /// Right base of each peak.
    pub right_bases: Vec<usize>,
}

/// Peaks of `x` with the semantics of `scipy.signal.find_peaks(x,
/// prominence=min_prominence, distance=min_distance)`:
///
/// 1. local maxima: samples (or flat plateaus) strictly higher than both
///    neighbours, never at the ends; a plateau's peak is its middle index
///    (rounded down);
/// 2. `min_distance`: peaks are visited from the highest down, each
///    removing the not-yet-removed peaks closer than `min_distance` samples
///    on either side (equal heights: the later index is visited first; scipy
///    leaves this order to numpy's unstable argsort);
/// 3. prominence of each remaining peak: from the peak, walk left while
///    `x[i] <= x[peak]` and take the minimum reached (the left base; on ties
///    the one nearest the peak), likewise to the right; prominence =
///    `x[peak] - max(left_min, right_min)`; peaks with prominence
///    `< min_prominence` are dropped.
///
/// The prominences and bases are reported for the kept peaks whether or not
/// `min_prominence` is given. NaN samples never form peaks.
///
/// ```
/// let p = focal::find_peaks(&[0.0, 5.0, 0.0, 4.0, 0.0, 6.0, 0.0, 1.0, 0.0], None, Some(3));
/// assert_eq!(p.indices, vec![1, 5]);
/// ```
pub fn find_peaks(x: &[f64], min_prominence: Option<f64>, min_distance: Option<usize>) -> Peaks {
    let mut peaks = local_maxima(x);
    if let Some(distance) = min_distance {
        peaks = select_by_distance(x, &peaks, distance.max(1));
    }
    let mut out = Peaks::default();
    for &peak in &peaks {
        let (prominence, left, right) = prominence_of(x, peak);
        if let Some(min) = min_prominence {
            if prominence.is_nan() || prominence < min {
                continue;
            }
        }
        out.indices.push(peak);
        out.prominences.push(prominence);
        out.left_bases.push(left);
        out.right_bases.push(right);
    }
    out
}

/// scipy's `_local_maxima_1d`: midpoints of the strict local maxima,
/// plateaus included, ends excluded.
fn local_maxima(x: &[f64]) -> Vec<usize> {
    let n = x.len();
    let mut peaks = Vec::new();
    if n < 3 {
        return peaks;
    }
    let i_max = n - 1;
    let mut i = 1;
    while i < i_max {
        if x[i - 1] < x[i] {
            let mut ahead = i + 1;
            while ahead < i_max && x[ahead] == x[i] {
                ahead += 1;
            }
            if x[ahead] < x[i] {
                let left = i;
                let right = ahead - 1;
                peaks.push((left + right) / 2);
                i = ahead;
            }
        }
        i += 1;
    }
    peaks
}

/// scipy's `_select_by_peak_distance`, with a stable order of equal heights.
fn select_by_distance(x: &[f64], peaks: &[usize], distance: usize) -> Vec<usize> {
    let m = peaks.len();
    let mut keep = vec![true; m];
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| x[peaks[a]].total_cmp(&x[peaks[b]]));
    for &j in order.iter().rev() {
        if !keep[j] {
            continue;
        }
        let mut k = j;
        while k > 0 && peaks[j] - peaks[k - 1] < distance {
            keep[k - 1] = false;
            k -= 1;
        }
        let mut k = j + 1;
        while k < m && peaks[k] - peaks[j] < distance {
            keep[k] = false;
            k += 1;
        }
    }
    peaks
        .iter()
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(&p, _)| p)
        .collect()
}

/// scipy's `_peak_prominences` for one peak without a window:
/// `(prominence, left_base, right_base)`.
fn prominence_of(x: &[f64], peak: usize) -> (f64, usize, usize) {
    let top = x[peak];
    let mut left_base = peak;
    let mut left_min = top;
    let mut i = peak as isize;
    while i >= 0 && x[i as usize] <= top {
        if x[i as usize] < left_min {
            left_min = x[i as usize];
            left_base = i as usize;
        }
        i -= 1;
    }
    let mut right_base = peak;
    let mut right_min = top;
    let mut i = peak;
    while i < x.len() && x[i] <= top {
        if x[i] < right_min {
            right_min = x[i];
            right_base = i;
        }
        i += 1;
    }
    (top - left_min.max(right_min), left_base, right_base)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn find_peaks_matches_scipy_on_hand_made_arrays() {
        // Expected values from scipy.signal.find_peaks (scipy 1.17.1), with
        // the keyword arguments noted; prominences/bases from the same call
        // with prominence=0 added where none was given. The arrays have no
        // equal peak heights: scipy orders ties by numpy's unstable argsort,
        // which depends on the platform's sort kernel.
        struct Case {
            x: Vec<f64>,
            prominence: Option<f64>,
            distance: Option<usize>,
            peaks: Vec<usize>,
            prominences: Vec<f64>,
            left: Vec<usize>,
            right: Vec<usize>,
        }
        let cases = vec![
            Case {
                x: vec![0., 1., 0., 2., 0., 3., 0.],
                prominence: None,
                distance: None,
                peaks: vec![1, 3, 5],
                prominences: vec![1., 2., 3.],
                left: vec![0, 2, 4],
                right: vec![2, 4, 6],
            },
            Case {
                x: vec![0., 1., 1., 1., 0., 2., 2., 0., 3., 3., 3., 3.],
                prominence: None,
                distance: None,
                peaks: vec![2, 5],
                prominences: vec![1., 2.],
                left: vec![0, 4],
                right: vec![4, 7],
            },
            Case {
                x: vec![2., 2., 1., 3., 3., 0., 1., 0.],
                prominence: None,
                distance: None,
                peaks: vec![3, 6],
                prominences: vec![2., 1.],
                left: vec![2, 5],
                right: vec![5, 7],
            },
            Case {
                x: vec![0., 5., 0., 4., 0., 6., 0., 1., 0.],
                prominence: None,
                distance: Some(3),
                peaks: vec![1, 5],
                prominences: vec![5., 6.],
                left: vec![0, 4],
                right: vec![2, 6],
            },
            Case {
                x: vec![0., 3., 1., 4., 2., 2.5, 0., 1., 0.5, 7., 6., 6.5, 0.],
                prominence: Some(1.0),
                distance: None,
                peaks: vec![1, 3, 9],
                prominences: vec![2., 4., 7.],
                left: vec![0, 0, 6],
                right: vec![2, 6, 12],
            },
            Case {
                x: vec![
                    0., 3., 1., 4., 2., 2.5, 0., 1., 0.5, 7., 6., 6.5, 0., 2., 1.9, 2.05, 0.,
                ],
                prominence: Some(0.6),
                distance: Some(3),
                peaks: vec![3, 9, 15],
                prominences: vec![4., 7., 2.05],
                left: vec![0, 6, 12],
                right: vec![6, 12, 16],
            },
        ];
        for c in cases {
            let p = find_peaks(&c.x, c.prominence, c.distance);
            assert_eq!(p.indices, c.peaks, "{:?}", c.x);
            assert_eq!(p.prominences, c.prominences, "{:?}", c.x);
            assert_eq!(p.left_bases, c.left, "{:?}", c.x);
            assert_eq!(p.right_bases, c.right, "{:?}", c.x);
        }
    }

    #[test]
    fn find_peaks_handles_degenerate_signals() {
        assert!(find_peaks(&[], Some(0.1), Some(10)).indices.is_empty());
        assert!(find_peaks(&[1.0], None, None).indices.is_empty());
        assert!(find_peaks(&[1.0, 2.0], None, None).indices.is_empty());
        assert!(find_peaks(&[3.0; 20], None, None).indices.is_empty());
        assert!(find_peaks(&[0.0, f64::NAN, 0.0], None, None)
            .indices
            .is_empty());
    }
}
