//! The Wilcoxon test against scipy: `shared/fixtures/stats/wilcoxon.json`.

use super::test_fixtures::load_fixture;
use super::{wilcoxon, Alternative, Mode, ModeUsed, WilcoxonError};
use serde::Deserialize;

#[derive(Deserialize)]
struct WilcoxonCase {
    x: Vec<f64>,
    y: Vec<f64>,
    p_exact: Option<f64>,
    p_approx: Option<f64>,
    p_auto: Option<f64>,
    stat_exact: Option<f64>,
    stat_approx: Option<f64>,
    stat_auto: Option<f64>,
    has_ties_or_zeros: bool,
}

fn assert_relative(what: &str, case: usize, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-6 * want.abs(),
        "case {case}: {what} = {got:e}, scipy {want:e}"
    );
}

fn check_mode(
    case: usize,
    c: &WilcoxonCase,
    mode: Mode,
    p: Option<f64>,
    stat: Option<f64>,
) -> usize {
    let (Some(p), Some(stat)) = (p, stat) else {
        return 0;
    };
    let r = wilcoxon(&c.x, &c.y, Alternative::Greater, mode)
        .unwrap_or_else(|e| panic!("case {case} {mode:?}: {e}"));
    assert_relative(
        &format!("{mode:?} p-value ({:?})", r.mode_used),
        case,
        r.p_value,
        p,
    );
    assert_eq!(r.statistic, stat, "case {case} {mode:?}: statistic");
    1
}

#[test]
fn every_wilcoxon_p_value_agrees_with_scipy() {
    let cases: Vec<WilcoxonCase> = load_fixture("wilcoxon.json");
    let mut checked = 0;
    let mut used = std::collections::BTreeSet::new();
    for (i, c) in cases.iter().enumerate() {
        checked += check_mode(i, c, Mode::Auto, c.p_auto, c.stat_auto);
        checked += check_mode(i, c, Mode::Exact, c.p_exact, c.stat_exact);
        checked += check_mode(i, c, Mode::Approx, c.p_approx, c.stat_approx);
        let auto = wilcoxon(&c.x, &c.y, Alternative::Greater, Mode::Auto).unwrap();
        used.insert(format!("{}", auto.mode_used));
        // The branch Auto chose is the documented one.
        let expected = if c.x.len() > 50 {
            ModeUsed::Approx
        } else if !c.has_ties_or_zeros {
            ModeUsed::Exact
        } else if c.x.len() <= 13 {
            ModeUsed::Permutation
        } else {
            ModeUsed::Approx
        };
        assert_eq!(auto.mode_used, expected, "case {i}");
    }
    assert!(
        checked >= 2 * cases.len(),
        "only {checked} p-values checked"
    );
    // The fixture exercises all three branches of Auto.
    assert_eq!(used.len(), 3, "branches used: {used:?}");
}

#[test]
fn wilcoxon_alternatives_are_mirror_images() {
    // Swapping the samples turns Greater into Less; the two-sided p is twice
    // the smaller one-sided p (exact and permutation branches).
    let x = [0.3, 0.12, 0.25, 0.4, 0.18, 0.22, 0.35, 0.09, 0.5];
    let y = [0.2, 0.1, 0.28, 0.15, 0.12, 0.21, 0.3, 0.02, 0.5];
    for mode in [Mode::Auto, Mode::Exact, Mode::Approx] {
        let g = wilcoxon(&x, &y, Alternative::Greater, mode).unwrap();
        let l = wilcoxon(&y, &x, Alternative::Less, mode).unwrap();
        assert!((g.p_value - l.p_value).abs() < 1e-15, "{mode:?}");
        let t = wilcoxon(&x, &y, Alternative::TwoSided, mode).unwrap();
        let less = wilcoxon(&x, &y, Alternative::Less, mode).unwrap();
        let want = (2.0 * g.p_value.min(less.p_value)).min(1.0);
        assert!(
            (t.p_value - want).abs() < 1e-15,
            "{mode:?}: {} vs {want}",
            t.p_value
        );
        assert_eq!(
            t.statistic,
            g.statistic
                .min((g.n * (g.n + 1)) as f64 / 2.0 - g.statistic)
        );
    }
}

#[test]
fn wilcoxon_bad_input_is_a_typed_error() {
    let g = Alternative::Greater;
    assert_eq!(
        wilcoxon(&[1.0, 2.0], &[1.0], g, Mode::Auto),
        Err(WilcoxonError::LengthMismatch { x: 2, y: 1 })
    );
    assert_eq!(wilcoxon(&[], &[], g, Mode::Auto), Err(WilcoxonError::Empty));
    assert_eq!(
        wilcoxon(&[1.0, 2.0], &[1.0, 2.0], g, Mode::Exact),
        Err(WilcoxonError::AllZero { pairs: 2 })
    );
    assert_eq!(
        wilcoxon(&[1.0, 2.0], &[0.0, f64::NAN], g, Mode::Approx),
        Err(WilcoxonError::NonFinite {
            sample: "y",
            index: 1
        })
    );
    let err = wilcoxon(&[f64::INFINITY], &[0.0], g, Mode::Approx).unwrap_err();
    assert_eq!(err.to_string(), "x[0] is not a finite number");
    let big: Vec<f64> = (1..=1001).map(f64::from).collect();
    assert_eq!(
        wilcoxon(&big, &vec![0.0; big.len()], g, Mode::Exact),
        Err(WilcoxonError::ExactTooLarge { n: 1001, max: 1000 })
    );
}

#[test]
fn wilcoxon_every_alternative_and_mode_on_tied_data_agrees_with_scipy() {
    // Differences 0.25 -0.25 0.5 0.5 0 0.25 1 1.5 -0.25 0.125: a zero and
    // ties, N = 10, so Auto enumerates the sign flips. Oracle values from
    // scipy.stats.wilcoxon(x, y, alternative=..., method=...).
    let x = [0.5, 0.25, 0.75, 1.0, 0.5, 0.25, 1.5, 2.0, 0.0, 0.125];
    let y = [0.25, 0.5, 0.25, 0.5, 0.5, 0.0, 0.5, 0.5, 0.25, 0.0];
    let (greater, less, two) = (
        Alternative::Greater,
        Alternative::Less,
        Alternative::TwoSided,
    );
    let (auto, exact, approx) = (Mode::Auto, Mode::Exact, Mode::Approx);
    let oracle = [
        (greater, auto, 38.0, 0.03515625),
        (greater, exact, 38.0, 0.037109375),
        (greater, approx, 38.0, 0.03185093770301228),
        (less, auto, 38.0, 0.9765625),
        (less, exact, 38.0, 0.97265625),
        (less, approx, 38.0, 0.9681490622969877),
        (two, auto, 7.0, 0.0703125),
        (two, exact, 7.0, 0.07421875),
        (two, approx, 7.0, 0.06370187540602457),
    ];
    for (alternative, mode, statistic, p) in oracle {
        let r = wilcoxon(&x, &y, alternative, mode).unwrap();
        assert_eq!(r.statistic, statistic, "{alternative:?} {mode:?}");
        assert!(
            (r.p_value - p).abs() <= 1e-9 * p,
            "{alternative:?} {mode:?}: {} vs scipy {p}",
            r.p_value
        );
        assert_eq!((r.n, r.n_zero), (9, 1));
    }
}
