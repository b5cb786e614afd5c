use super::*;

#[test]
fn tukey_weight_shape() {
    assert_eq!(tukey_weight(0.0), 1.0);
    assert_eq!(tukey_weight(1.0), 0.0);
    assert_eq!(tukey_weight(-1.5), 0.0);
    assert!((tukey_weight(0.5) - 0.5625).abs() < 1e-15);
    assert_eq!(tukey_weight(0.3), tukey_weight(-0.3));
}

#[test]
fn params_validation_names_the_field() {
    let bad = IrlsParams {
        thr_px: -1.0,
        ..IrlsParams::default()
    };
    assert!(matches!(
        bad.validate(),
        Err(GeometryError::InvalidParameter { name: "thr_px", .. })
    ));
    let bad = IrlsParams {
        max_iters: 0,
        ..IrlsParams::default()
    };
    assert!(matches!(
        bad.validate(),
        Err(GeometryError::InvalidParameter {
            name: "max_iters",
            ..
        })
    ));
    let bad = IrlsParams {
        tukey_c: f64::NAN,
        ..IrlsParams::default()
    };
    assert!(bad.validate().is_err());
    assert!(IrlsParams::default().validate().is_ok());
}

#[test]
fn checked_initial_rejects_nan_and_zero() {
    let mut f = Matrix3::identity();
    f[(2, 1)] = f64::NAN;
    assert_eq!(
        checked_initial(&f),
        Err(GeometryError::NonFiniteMatrix { row: 2, col: 1 })
    );
    assert_eq!(
        checked_initial(&Matrix3::zeros()),
        Err(GeometryError::ZeroMatrix)
    );
}
