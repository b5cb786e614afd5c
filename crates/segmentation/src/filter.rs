//! Steps 5–6 of Algorithm 1: the local test (Eq. 36), the KDE focal
//! consensus and its band (Eq. 37), and the plausibility of the consensus.

use crate::{FocalVerdict, Hypothesis, HypothesisStatus, LocalTest, Params};
use focal::{ConsensusParams, FocalConsensus};

/// The plausible scene focals relative to the focal prior `max(W, H)`:
/// f_peak outside `[0.3, 3] × prior` is implausible (a horizontal field of
/// view above 118° or below 19° for the usual prior). Such consensus values
/// come from motions whose focal F cannot measure (results/README.md,
/// `sctl gt-focals`), not from the camera.
pub const PLAUSIBLE_FOCAL_RANGE: [f64; 2] = [0.3, 3.0];

/// The verdict on a focal consensus for a scene of focal prior `prior`.
pub fn focal_verdict(consensus: Option<&FocalConsensus>, prior: f64) -> FocalVerdict {
    let [low, high] = PLAUSIBLE_FOCAL_RANGE;
    match consensus {
        None => FocalVerdict::NoConsensus,
        Some(c) if c.f_peak >= low * prior && c.f_peak <= high * prior => FocalVerdict::Plausible,
        Some(_) => FocalVerdict::Implausible,
    }
}

/// What the focal filter decided besides each hypothesis's status.
#[derive(Debug, Clone, PartialEq)]
pub struct FilterOutcome {
    /// The KDE consensus of the local-test survivors, when there was any.
    pub consensus: Option<FocalConsensus>,
    /// True when nothing passed or nothing fell in the band, so every
    /// refined hypothesis was kept.
    pub fallback: bool,
    /// Hypotheses that passed the local test (Eq. 36).
    pub local_ok: usize,
    /// Whether the consensus is plausible ([`focal_verdict`]); the filter
    /// applies the band either way (the thesis), the verdict is reported.
    pub verdict: FocalVerdict,
}

/// `f_avg = (f1 + f2) / 2` (Eq. 36).
fn f_avg((f1, f2): (f64, f64)) -> f64 {
    0.5 * (f1 + f2)
}

/// The focal filter of steps 5–6 over the refined hypotheses (`refined[k]`
/// indexes `hypotheses`), whose focals are set: sets every refined
/// hypothesis's status.
///
/// - Local test (Eq. 36): `|f1 − f2| / f_avg < τ_diff`; with
///   [`LocalTest::ReferenceCode`] a failing hypothesis with `f_avg > 0`
///   stays in the pool, only its focals are left out of the KDE.
/// - Consensus (Eq. 37): f_peak, the highest KDE peak of the passing
///   `f_avg`; the pool's hypotheses with `|f_avg − f_peak| ≤ τ_range f_peak`
///   are kept.
/// - When nothing is kept, every refined hypothesis is (the fallback).
/// - The verdict on f_peak against [`PLAUSIBLE_FOCAL_RANGE`] times
///   `focal_prior` is reported, and changes nothing.
pub fn focal_filter(
    hypotheses: &mut [Hypothesis],
    refined: &[usize],
    params: &Params,
    focal_prior: f64,
) -> FilterOutcome {
    let reference = params.reference_code.local_test == LocalTest::ReferenceCode;
    let mut local_ok = Vec::new();
    let mut pool = Vec::new();
    for &j in refined {
        let h = &mut hypotheses[j];
        let Some(focals) = h.focals else {
            h.status = HypothesisStatus::FocalFailed;
            continue;
        };
        let passes = focal::passes_local_test(focals.0, focals.1, params.focal.tau_diff);
        if passes {
            local_ok.push(j);
        }
        if passes || (reference && f_avg(focals) > 0.0) {
            pool.push(j);
        } else {
            h.status = HypothesisStatus::LocalTestFailed;
        }
    }
    let values: Vec<f64> = local_ok
        .iter()
        .filter_map(|&j| hypotheses[j].focals.map(f_avg))
        .collect();
    let consensus = focal::focal_consensus(&values, &ConsensusParams::default());
    let verdict = focal_verdict(consensus.as_ref(), focal_prior);
    let mut kept = 0;
    if let Some(c) = consensus.as_ref() {
        for &j in &pool {
            let Some(focals) = hypotheses[j].focals else {
                continue;
            };
            let inside = focal::within_band(f_avg(focals), c.f_peak, params.focal.tau_range);
            kept += usize::from(inside);
            hypotheses[j].status = if inside {
                HypothesisStatus::Kept
            } else {
                HypothesisStatus::OutsideBand
            };
        }
    }
    let fallback = kept == 0;
    if fallback {
        for &j in refined {
            hypotheses[j].status = HypothesisStatus::Kept;
        }
    }
    FilterOutcome {
        consensus,
        fallback,
        local_ok: local_ok.len(),
        verdict,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use HypothesisStatus::*;

    fn hyp(focals: Option<(f64, f64)>) -> Hypothesis {
        Hypothesis {
            status: Kept,
            focals,
        }
    }

    #[test]
    fn focal_filter_variants() {
        // 0: no focal; 1..=4 agree near 1000; 5 far away; 6 fails |f1-f2|
        // only; 7 negative.
        let mut hs = vec![
            hyp(None),
            hyp(Some((1000.0, 1010.0))),
            hyp(Some((990.0, 1000.0))),
            hyp(Some((1005.0, 1000.0))),
            hyp(Some((995.0, 1000.0))),
            hyp(Some((2000.0, 2010.0))),
            hyp(Some((900.0, 1100.0))),
            hyp(Some((-1000.0, -1000.0))),
        ];
        let refined: Vec<usize> = (0..hs.len()).collect();
        let params = Params::default().with(|q| {
            q.focal.tau_diff = 0.05;
            q.focal.tau_range = 0.2;
        });
        let mut a = hs.clone();
        let out = focal_filter(&mut a, &refined, &params, 1000.0);
        assert!(!out.fallback);
        assert_eq!(out.local_ok, 5);
        let f_peak = out.consensus.unwrap().f_peak;
        assert!((f_peak - 1000.0).abs() < 100.0, "{f_peak}");
        let status: Vec<HypothesisStatus> = a.iter().map(|h| h.status).collect();
        assert_eq!(
            status,
            [
                FocalFailed,
                Kept,
                Kept,
                Kept,
                Kept,
                OutsideBand,
                LocalTestFailed,
                LocalTestFailed
            ]
        );
        // Reference code: 6 stays in the pool and the band keeps it (f_avg 1000).
        let reference = params
            .clone()
            .with(|q| q.reference_code.local_test = LocalTest::ReferenceCode);
        let out = focal_filter(&mut hs, &refined, &reference, 1000.0);
        assert_eq!(out.local_ok, 5);
        assert_eq!(hs[6].status, Kept);
        assert_eq!(hs[7].status, LocalTestFailed);
        assert_eq!(hs[0].status, FocalFailed);
        // Nothing passes: everything refined is kept.
        let mut none = vec![hyp(None), hyp(Some((500.0, 1500.0)))];
        let out = focal_filter(&mut none, &[0, 1], &params, 1000.0);
        assert!(out.consensus.is_none() && out.fallback && out.local_ok == 0);
        assert_eq!(out.verdict, FocalVerdict::NoConsensus);
        assert!(none.iter().all(|h| h.status == Kept));
    }

    #[test]
    fn an_implausible_consensus_filters_all_the_same() {
        // A consensus at 10 px for a prior of 1000 px: outside [300, 3000].
        let focals = [(10.0, 10.1), (10.1, 10.0), (10.0, 10.0), (900.0, 905.0)];
        let fresh = || -> Vec<Hypothesis> { focals.iter().map(|&f| hyp(Some(f))).collect() };
        let refined = [0, 1, 2, 3];
        let filter = Params::default();
        let mut hs = fresh();
        let out = focal_filter(&mut hs, &refined, &filter, 1000.0);
        assert_eq!(out.verdict, FocalVerdict::Implausible);
        assert!(!out.fallback);
        assert_eq!(hs[3].status, OutsideBand);
        assert!(hs[..3].iter().all(|h| h.status == Kept));
        // The same consensus is plausible for a prior of 30 px.
        let out = focal_filter(&mut fresh(), &refined, &filter, 30.0);
        assert_eq!(out.verdict, FocalVerdict::Plausible);
    }

    #[test]
    fn verdict_bounds_are_inclusive() {
        let at = |f_peak: f64| FocalConsensus {
            f_peak,
            ..focal::focal_consensus(&[100.0, 101.0, 99.0], &ConsensusParams::default()).unwrap()
        };
        assert_eq!(
            focal_verdict(Some(&at(300.0)), 1000.0),
            FocalVerdict::Plausible
        );
        assert_eq!(
            focal_verdict(Some(&at(3000.0)), 1000.0),
            FocalVerdict::Plausible
        );
        assert_eq!(
            focal_verdict(Some(&at(299.0)), 1000.0),
            FocalVerdict::Implausible
        );
        assert_eq!(
            focal_verdict(Some(&at(3001.0)), 1000.0),
            FocalVerdict::Implausible
        );
        assert_eq!(focal_verdict(None, 1000.0), FocalVerdict::NoConsensus);
    }
}
