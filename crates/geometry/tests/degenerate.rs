//! Property tests: bad or degenerate input gives an error value, never a
//! panic and never a silent answer.

mod common;

use geometry::{
    eight_point_normalized, eight_point_plain, eight_point_weighted, eight_point_weighted_plain,
    refine_irls_tukey, Correspondences, GeometryError, IrlsParams,
};
use nalgebra::Matrix3;
use proptest::prelude::*;

type Estimator = fn(&Correspondences) -> Result<Matrix3<f64>, GeometryError>;

fn unit_weighted(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    eight_point_weighted(points, &vec![1.0; points.len()])
}

fn varied_weighted_plain(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    let w: Vec<f64> = (0..points.len()).map(|i| 0.5 + (i % 3) as f64).collect();
    eight_point_weighted_plain(points, &w)
}

const VARIANTS: [(&str, Estimator); 4] = [
    ("plain", eight_point_plain),
    ("normalized", eight_point_normalized),
    ("weighted", unit_weighted),
    ("weighted plain", varied_weighted_plain),
];

fn pixel() -> impl Strategy<Value = [f64; 2]> {
    [-400.0..400.0f64, -300.0..300.0f64]
}

fn is_degenerate(r: &Result<Matrix3<f64>, GeometryError>) -> bool {
    matches!(r, Err(GeometryError::Degenerate(_)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn nan_or_infinite_coordinates_are_rejected_with_their_position(
        pts in prop::collection::vec((pixel(), pixel()), 8..20),
        index in 0usize..20,
        field in 0usize..4,
        bad in prop::sample::select(vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY]),
    ) {
        let index = index % pts.len();
        let (mut p1, mut p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        match field {
            0 => p1[index][0] = bad,
            1 => p1[index][1] = bad,
            2 => p2[index][0] = bad,
            _ => p2[index][1] = bad,
        }
        let names = ["x1", "y1", "x2", "y2"];
        prop_assert_eq!(
            Correspondences::new(&p1, &p2),
            Err(GeometryError::NonFinite { field: names[field], index })
        );
    }

    #[test]
    fn fewer_than_eight_points_is_an_error(pts in prop::collection::vec((pixel(), pixel()), 0..8)) {
        let (p1, p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let c = Correspondences::new(&p1, &p2).unwrap();
        for (name, estimate) in VARIANTS {
            prop_assert_eq!(
                estimate(&c),
                Err(GeometryError::TooFewPoints { got: p1.len(), needed: 8 }),
                "{}", name
            );
        }
        let sample: Vec<usize> = (0..p1.len()).collect();
        let refined = refine_irls_tukey(&c, &sample, None, &IrlsParams::default());
        let too_few = matches!(refined, Err(GeometryError::TooFewPoints { .. }));
        prop_assert!(too_few, "{:?}", refined);
    }

    #[test]
    fn eight_copies_of_one_match_are_degenerate(a in pixel(), b in pixel(), copies in 8usize..30) {
        let c = Correspondences::new(&vec![a; copies], &vec![b; copies]).unwrap();
        for (name, estimate) in VARIANTS {
            prop_assert!(is_degenerate(&estimate(&c)), "{}: {:?}", name, estimate(&c));
        }
        let sample: Vec<usize> = (0..8).collect();
        prop_assert!(refine_irls_tukey(&c, &sample, None, &IrlsParams::default()).is_err());
    }

    #[test]
    fn four_distinct_matches_repeated_are_degenerate(
        pts in prop::collection::vec((pixel(), pixel()), 4),
        repeats in 2usize..5,
    ) {
        let (q1, q2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let p1: Vec<_> = (0..4 * repeats).map(|i| q1[i % 4]).collect();
        let p2: Vec<_> = (0..4 * repeats).map(|i| q2[i % 4]).collect();
        let c = Correspondences::new(&p1, &p2).unwrap();
        for (name, estimate) in VARIANTS {
            prop_assert!(is_degenerate(&estimate(&c)), "{}: {:?}", name, estimate(&c));
        }
    }

    #[test]
    fn seven_distinct_matches_are_degenerate(pts in prop::collection::vec((pixel(), pixel()), 7)) {
        // Seven matches leave a two-dimensional null space (the 7-point case).
        let (mut p1, mut p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        p1.push(p1[3]);
        p2.push(p2[3]);
        let c = Correspondences::new(&p1, &p2).unwrap();
        for (name, estimate) in VARIANTS {
            prop_assert!(is_degenerate(&estimate(&c)), "{}: {:?}", name, estimate(&c));
        }
    }

    #[test]
    fn collinear_points_in_one_image_are_degenerate(
        origin in pixel(),
        angle in 0.0..std::f64::consts::PI,
        along in prop::collection::vec(-300.0..300.0f64, 8..40),
        others in prop::collection::vec(pixel(), 40),
        image in 0usize..3,
    ) {
        let line: Vec<[f64; 2]> = along
            .iter()
            .map(|s| [origin[0] + s * angle.cos(), origin[1] + s * angle.sin()])
            .collect();
        let other = &others[..line.len()];
        // image 0: collinear in image 1; 1: in image 2; 2: in both.
        let (p1, p2) = match image {
            0 => (line.clone(), other.to_vec()),
            1 => (other.to_vec(), line.clone()),
            _ => (line.clone(), line.iter().map(|p| [0.5 * p[0] + 20.0, 0.5 * p[1] - 7.0]).collect()),
        };
        let c = Correspondences::new(&p1, &p2).unwrap();
        for (name, estimate) in VARIANTS {
            prop_assert!(is_degenerate(&estimate(&c)), "{}: {:?}", name, estimate(&c));
        }
    }

    #[test]
    fn general_position_points_are_accepted(pts in prop::collection::vec((pixel(), pixel()), 8..30)) {
        // Random matches (no geometry) still give a unique least-squares F
        // unless the draw is nearly degenerate; the control for the tests above.
        let (p1, p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let c = Correspondences::new(&p1, &p2).unwrap();
        for (name, estimate) in VARIANTS {
            match estimate(&c) {
                Ok(f) => prop_assert!((f.norm() - 1.0).abs() < 1e-12 && f.determinant().abs() < 1e-12),
                Err(GeometryError::Degenerate(_)) => {}
                Err(e) => prop_assert!(false, "{}: unexpected error {:?}", name, e),
            }
        }
    }
}

#[test]
fn a_duplicated_sample_is_degenerate_for_irls() {
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(1);
    let scene = common::random_scene(&mut rng, 40, 0, 0.5);
    let sample = [0, 1, 2, 3, 0, 1, 2, 3];
    assert!(matches!(
        refine_irls_tukey(&scene.points, &sample, None, &IrlsParams::default()),
        Err(GeometryError::Degenerate(_))
    ));
}
