use super::*;
use nalgebra::{Matrix3, Rotation3, SMatrix, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `Q diag(λ) Qᵀ` for a fixed orthogonal Q (from a QR of a dense matrix).
fn spectral(lambda: [f64; 9]) -> [[f64; 9]; 9] {
    let g = SMatrix::<f64, 9, 9>::from_fn(|i, j| {
        ((i * 9 + j) as f64 * 0.7).sin() + if i == j { 2.0 } else { 0.0 }
    });
    let q = g.qr().q();
    let a = q
        * SMatrix::<f64, 9, 9>::from_diagonal(&SMatrix::<f64, 9, 1>::from(lambda))
        * q.transpose();
    let mut rows = [[0.0; 9]; 9];
    for i in 0..9 {
        for j in 0..9 {
            rows[i][j] = 0.5 * (a[(i, j)] + a[(j, i)]);
        }
    }
    rows
}

#[test]
fn givens_qr_reproduces_the_gram_matrix() {
    let mut qr = GivensQr9::default();
    let mut gram = SMatrix::<f64, 9, 9>::zeros();
    for i in 0..13 {
        let t = i as f64;
        let row = crate::minimal::epipolar_row(
            [t.sin() * 50.0, t * 3.0 - 7.0, 1.0],
            [t.cos() * 40.0, 11.0 - t * t, 1.0],
        );
        let v = SMatrix::<f64, 9, 1>::from_iterator(row);
        gram += v * v.transpose();
        qr.push(row);
    }
    let r = SMatrix::<f64, 9, 9>::from_fn(|i, j| qr.r[i][j]);
    for i in 0..9 {
        for j in 0..i {
            assert_eq!(r[(i, j)], 0.0);
        }
    }
    let rel = (r.transpose() * r - gram).norm() / gram.norm();
    assert!(rel < 1e-14, "relative error {rel}");
}

/// The Householder reduction as written row by row over the trailing
/// block (the textbook loops): the reference for [`tridiagonalize`].
fn tridiagonalize_rowwise(mut m: [[f64; 9]; 9]) -> ([f64; 9], [f64; 9]) {
    const N: usize = 9;
    let (mut d, mut e) = ([0.0; N], [0.0; N]);
    for k in 0..N - 2 {
        let mut v = [0.0; N];
        let mut norm2 = 0.0;
        for i in k + 1..N {
            v[i] = m[i][k];
            norm2 += v[i] * v[i];
        }
        let norm = norm2.sqrt();
        d[k] = m[k][k];
        if norm == 0.0 {
            continue;
        }
        let alpha = if v[k + 1] > 0.0 { -norm } else { norm };
        e[k] = alpha;
        v[k + 1] -= alpha;
        let vtv = norm2 - 2.0 * alpha * m[k + 1][k] + alpha * alpha;
        if vtv == 0.0 {
            continue;
        }
        let beta = 2.0 / vtv;
        let mut p = [0.0; N];
        for i in k + 1..N {
            let mut sum = 0.0;
            for j in k + 1..N {
                sum += m[i][j] * v[j];
            }
            p[i] = beta * sum;
        }
        let ptv: f64 = (k + 1..N).map(|i| p[i] * v[i]).sum();
        let kappa = 0.5 * beta * ptv;
        for i in k + 1..N {
            p[i] -= kappa * v[i];
        }
        for i in k + 1..N {
            for j in k + 1..N {
                m[i][j] -= v[i] * p[j] + p[i] * v[j];
            }
        }
    }
    d[N - 2] = m[N - 2][N - 2];
    d[N - 1] = m[N - 1][N - 1];
    e[N - 2] = m[N - 1][N - 2];
    (d, e)
}

#[test]
fn tridiagonalize_has_the_bits_of_the_rowwise_loops() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for trial in 0..200 {
        // Normal matrices XᵀX of random rows, as the 8-point builds
        // them (upper triangle mirrored), some with a zero column.
        let mut a = [[0.0; 9]; 9];
        for _ in 0..12 {
            let mut row: [f64; 9] = std::array::from_fn(|_| rng.gen_range(-3.0..3.0));
            if trial % 10 == 0 {
                row[4] = 0.0;
            }
            for r in 0..9 {
                for c in r..9 {
                    a[r][c] += row[r] * row[c];
                    a[c][r] = a[r][c];
                }
            }
        }
        let (d, e) = tridiagonalize(a);
        let (d0, e0) = tridiagonalize_rowwise(a);
        assert_eq!(d.map(f64::to_bits), d0.map(f64::to_bits), "trial {trial}");
        assert_eq!(e.map(f64::to_bits), e0.map(f64::to_bits), "trial {trial}");
    }
}

#[test]
fn eigenvalues_of_a_known_spectrum() {
    let lambda = [5.0, 3.0, 2.5, 1.0, 0.7, 0.3, 0.1, 1e-3, 0.0];
    let mut got = symmetric_eigenvalues(&spectral(lambda)).unwrap();
    got.sort_by(|a, b| b.total_cmp(a));
    for k in 0..9 {
        assert!((got[k] - lambda[k]).abs() < 1e-14 * 5.0, "{got:?}");
    }
}

#[test]
fn smallest_eigenvector_matches_nalgebra() {
    for (seed, lambda) in [
        [9.0, 4.0, 3.0, 2.0, 1.5, 1.0, 0.5, 0.2, 1e-6],
        [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.01, 0.0],
        [1e4, 10.0, 5.0, 1.0, 0.1, 0.01, 1e-3, 1e-5, 1e-9],
    ]
    .iter()
    .enumerate()
    {
        let a = spectral(*lambda);
        let pair = smallest_eigenpair(&a).unwrap();
        let m = SMatrix::<f64, 9, 9>::from_fn(|i, j| a[i][j]);
        let eig = nalgebra::SymmetricEigen::new(m);
        let k = eig.eigenvalues.imin();
        let reference = eig.eigenvectors.column(k);
        let v = SMatrix::<f64, 9, 1>::from(pair.vector);
        let err = (v - reference).norm().min((v + reference).norm());
        // Both solvers are backward stable: the eigenvector is known to
        // ε‖A‖ / (λ_2 − λ_min).
        let tolerance = 1e-14 * lambda[0] / (lambda[7] - lambda[8]);
        assert!(err < tolerance, "case {seed}: {err:e}");
        assert!((pair.second - lambda[7]).abs() < 1e-13 * lambda[0]);
        assert!((pair.largest - lambda[0]).abs() < 1e-13 * lambda[0]);
        // Residual ‖A v − λ v‖ at rounding level.
        let residual = (m * v - v * lambda[8]).norm();
        assert!(
            residual < 1e-13 * lambda[0],
            "case {seed}: residual {residual:e}"
        );
    }
}

#[test]
fn smallest_eigenpair_rejects_bad_input() {
    assert!(smallest_eigenpair(&[[0.0; 9]; 9]).is_none());
    let mut a = spectral([1.0; 9]);
    a[3][4] = f64::NAN;
    assert!(smallest_eigenpair(&a).is_none());
}

/// Columns of `U diag(s) Vᵀ` for two rotations.
fn build(s: [f64; 3], u: Rotation3<f64>, v: Rotation3<f64>) -> [[f64; 3]; 3] {
    let m = u.matrix() * Matrix3::from_diagonal(&Vector3::from(s)) * v.matrix().transpose();
    [0, 1, 2].map(|c| [m[(0, c)], m[(1, c)], m[(2, c)]])
}

#[test]
fn recovers_singular_values_with_relative_accuracy() {
    let u = Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    let v = Rotation3::from_euler_angles(-0.7, 0.4, 1.3);
    for s in [
        [3.0, 2.0, 1.0],
        [1.0, 0.7, 1e-9],
        [1.0, 1.0, 0.5],
        [5.0, 1e-4, 0.0],
    ] {
        let svd = jacobi_svd(build(s, u, v)).unwrap();
        let mut got = svd.singular_values;
        got.sort_by(|a, b| b.total_cmp(a));
        for k in 0..3 {
            assert!((got[k] - s[k]).abs() <= 1e-14 * s[0], "{s:?}: got {got:?}");
        }
        // A V = U Σ reproduces A: (A V) Vᵀ = A.
        let a = build(s, u, v);
        for r in 0..3 {
            for c in 0..3 {
                let rec: f64 = (0..3).map(|j| svd.av[j][r] * svd.v[j][c]).sum();
                assert!((rec - a[c][r]).abs() < 1e-14 * s[0]);
            }
        }
    }
}

#[test]
fn the_matrix_that_breaks_bidiagonal_qr_with_a_fixed_epsilon() {
    // A rank-2 matrix on which nalgebra 0.33's SVD recomposes with an
    // error of 1.3e-3 (absolute convergence threshold).
    let f = Matrix3::new(
        0.009809773112938404,
        -0.000701906143672865,
        0.7233672826455007,
        0.004625273924819647,
        0.001057489386272473,
        -0.11146879609683223,
        -0.6732565538793657,
        -0.10411923893359093,
        -0.00894666830244662,
    );
    let svd = jacobi_svd([0, 1, 2].map(|c| [f[(0, c)], f[(1, c)], f[(2, c)]])).unwrap();
    let (min, second, max) = svd.extremes();
    assert!(svd.singular_values[min] < 1e-15);
    assert!((second - 0.6797848877699924).abs() < 1e-14);
    assert!((max - 0.733411553194752).abs() < 1e-14);
}

#[test]
fn rejects_non_finite_input() {
    assert!(jacobi_svd([[1.0, f64::NAN], [0.0, 1.0]]).is_none());
}
