//! The KDE focal consensus (Eq. 37) on samples from a two-component
//! Gaussian mixture.

use focal::{band_indices, focal_consensus, kde_bandwidth, ConsensusParams};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

fn mixture(seed: u64, n: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let major = Normal::new(800.0, 40.0).unwrap();
    let minor = Normal::new(1300.0, 60.0).unwrap();
    (0..n)
        .map(|i| {
            if i % 10 < 7 {
                major.sample(&mut rng)
            } else {
                minor.sample(&mut rng)
            }
        })
        .collect()
}

#[test]
fn highest_peak_is_the_larger_mode() {
    // 70 % of the mass at N(800, 40), 30 % at N(1300, 60): the mixture's
    // larger mode is at 800 (the other component adds nothing measurable
    // there), and smoothing with the bandwidth keeps it there.
    for seed in [1, 2, 3] {
        let values = mixture(seed, 20_000);
        let c = focal_consensus(&values, &ConsensusParams::default()).unwrap();
        let cell = c.grid[1] - c.grid[0];
        assert_eq!(c.peaks.len(), 2, "seed {seed}: peaks {:?}", c.peaks);
        assert!(!c.from_median);
        assert!(
            (c.f_peak - 800.0).abs() <= cell,
            "seed {seed}: f_peak {} vs 800 (grid cell {cell})",
            c.f_peak
        );
        // The other peak is the minor mode.
        let other = c
            .peaks
            .iter()
            .map(|&i| c.grid[i])
            .find(|g| (g - c.f_peak).abs() > 100.0)
            .unwrap();
        assert!(
            (other - 1300.0).abs() <= 5.0 * cell,
            "seed {seed}: minor peak {other}"
        );
        // The band keeps the major component.
        let kept = band_indices(&values, c.f_peak, 0.25);
        assert!(kept
            .iter()
            .all(|&i| (values[i] - c.f_peak).abs() <= 0.25 * c.f_peak));
        assert_eq!(
            kept.len(),
            values
                .iter()
                .filter(|v| (*v - c.f_peak).abs() / c.f_peak <= 0.25)
                .count()
        );
    }
}

#[test]
fn bandwidth_equals_the_formula() {
    let values = mixture(4, 1234);
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    let want = 1.06 * std * n.powf(-1.0 / 5.0);
    let c = focal_consensus(&values, &ConsensusParams::default()).unwrap();
    assert!((c.bandwidth - want).abs() <= 1e-12 * want);
    assert!((c.bandwidth - kde_bandwidth(&values)).abs() <= 1e-12 * want);
    // The density is the formula at every grid point (naive reference).
    for k in [0, 100, 255, 400, 511] {
        let g = c.grid[k];
        let naive: f64 = values
            .iter()
            .map(|v| {
                (-0.5 * ((g - v) / want).powi(2)).exp()
                    / ((2.0 * std::f64::consts::PI).sqrt() * want)
            })
            .sum::<f64>()
            / n;
        assert!(
            (c.density[k] - naive).abs() <= 1e-10 * naive,
            "density[{k}]"
        );
    }
}

#[test]
fn consensus_parameters_have_the_documented_defaults() {
    let p: ConsensusParams = serde_json::from_str("{}").unwrap();
    assert_eq!(p, ConsensusParams::default());
    assert_eq!(
        (
            p.grid_points,
            p.low_percentile,
            p.high_percentile,
            p.rel_prominence,
            p.min_peak_distance
        ),
        (512, 1.0, 99.0, 0.05, 10)
    );
    assert!(serde_json::from_str::<ConsensusParams>(r#"{"grid": 10}"#).is_err());
}
