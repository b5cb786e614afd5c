use super::*;

#[test]
fn canonical_scale_has_unit_norm_and_positive_largest_entry() {
    let f = Matrix3::new(1.0, -7.0, 2.0, 0.0, 3.0, 0.0, 0.0, 0.0, 1.0);
    let g = canonical_scale(f);
    assert!((g.norm() - 1.0).abs() < 1e-15);
    assert!(g[(0, 1)] > 0.0);
    assert!((g + f / f.norm()).norm() < 1e-15);
}

#[test]
fn smallest_eigenvector_rejects_a_two_dimensional_null_space() {
    let mut a = [[0.0; 9]; 9];
    for (k, row) in a.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    a[3][3] = 0.0;
    let v = smallest_eigenvector(&a).unwrap();
    assert!((v[3].abs() - 1.0).abs() < 1e-12);
    a[5][5] = 1e-15;
    assert!(matches!(
        smallest_eigenvector(&a),
        Err(GeometryError::Degenerate(_))
    ));
}
