//! Prototype: a five-point hypothesis refitted on the essential manifold
//! at the focal prior (5 degrees of freedom: `F = K⁻ᵀ [t]× R K⁻¹`),
//! Gauss–Newton on the Tukey-weighted signed Sampson residuals of the
//! matches within `thr_px`.

use geometry::Correspondences;
use nalgebra::{Matrix3, Rotation3, SMatrix, SVector, Vector3};

type V5 = SVector<f64, 6>;
type M5 = SMatrix<f64, 6, 6>;

struct Pose {
    r: Matrix3<f64>,
    t: Vector3<f64>,
    focal: f64,
}

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

impl Pose {
    fn from_f(f: &Matrix3<f64>, focal: f64) -> Option<Self> {
        let k = Matrix3::new(focal, 0.0, 0.0, 0.0, focal, 0.0, 0.0, 0.0, 1.0);
        let e = k * f * k;
        let svd = e.svd(true, true);
        let mut u = svd.u?;
        let mut v_t = svd.v_t?;
        if u.determinant() < 0.0 {
            u = -u;
        }
        if v_t.determinant() < 0.0 {
            v_t = -v_t;
        }
        let w = Matrix3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        Some(Self {
            r: u * w * v_t,
            t: u.column(2).into_owned(),
            focal,
        })
    }

    fn f(&self, _focal: f64) -> Matrix3<f64> {
        let focal = self.focal;
        let ki = Matrix3::new(1.0 / focal, 0.0, 0.0, 0.0, 1.0 / focal, 0.0, 0.0, 0.0, 1.0);
        let f = ki * skew(&self.t) * self.r * ki;
        f / f.norm()
    }

    fn step(&self, d: &V5) -> Self {
        let (b1, b2) = tangent(&self.t);
        let rot = Rotation3::new(Vector3::new(d[0], d[1], d[2]));
        let t = (self.t + b1 * d[3] + b2 * d[4]).normalize();
        Self {
            r: rot.matrix() * self.r,
            t,
            focal: self.focal * d[5].exp(),
        }
    }
}

fn tangent(t: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let a = if t.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let b1 = t.cross(&a).normalize();
    let b2 = t.cross(&b1);
    (b1, b2)
}

fn signed(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let x1 = Vector3::new(p1[0], p1[1], 1.0);
    let x2 = Vector3::new(p2[0], p2[1], 1.0);
    let fx1 = f * x1;
    let ftx2 = f.transpose() * x2;
    let e = x2.dot(&fx1);
    let g = fx1.x * fx1.x + fx1.y * fx1.y + ftx2.x * ftx2.x + ftx2.y * ftx2.y;
    if g > 0.0 {
        e / g.sqrt()
    } else {
        f64::INFINITY
    }
}

fn free_focal() -> bool {
    std::env::var("SCTL_PROTO_EFOCAL").is_ok_and(|v| v == "1")
}

fn tukey(r: f64, c: f64) -> (f64, f64) {
    // (weight, rho)
    if r.abs() >= c {
        return (0.0, c * c / 6.0);
    }
    let u = 1.0 - (r / c) * (r / c);
    (u * u, c * c / 6.0 * (1.0 - u * u * u))
}

/// The refit, `iters` Gauss–Newton rounds; None when the start is not an
/// essential matrix at `focal` or fewer than 6 matches lie within `thr_px`.
pub fn refit(
    points: &Correspondences,
    f0: &Matrix3<f64>,
    focal: f64,
    thr_px: f64,
    iters: usize,
) -> Option<Matrix3<f64>> {
    let mut pose = Pose::from_f(f0, focal)?;
    let n = points.len();
    let cost = |pose: &Pose, set: &[usize], c: f64| -> f64 {
        let f = pose.f(focal);
        set.iter()
            .map(|&i| tukey(signed(&f, points.point1(i), points.point2(i)), c).1)
            .sum()
    };
    for _ in 0..iters {
        let f = pose.f(focal);
        let inl: Vec<usize> = (0..n)
            .filter(|&i| signed(&f, points.point1(i), points.point2(i)).abs() <= thr_px)
            .collect();
        if inl.len() < 6 {
            return None;
        }
        let r0: Vec<f64> = inl
            .iter()
            .map(|&i| signed(&f, points.point1(i), points.point2(i)))
            .collect();
        let c = if std::env::var("SCTL_PROTO_EMAD").is_ok_and(|v| v == "1") {
            let mut a: Vec<f64> = r0.iter().map(|r| r.abs()).collect();
            a.sort_by(f64::total_cmp);
            (4.685 * 1.4826 * a[a.len() / 2]).min(thr_px).max(1e-9)
        } else {
            thr_px
        };
        let h = 1e-6;
        let dims = if free_focal() { 6 } else { 5 };
        let fs: Vec<Matrix3<f64>> = (0..dims)
            .map(|k| {
                let mut d = V5::zeros();
                d[k] = h;
                pose.step(&d).f(focal)
            })
            .collect();
        let mut jtj = M5::zeros();
        let mut jtr = V5::zeros();
        for (j, &i) in inl.iter().enumerate() {
            let (p1, p2) = (points.point1(i), points.point2(i));
            let row = V5::from_fn(|k, _| {
                if k < dims {
                    (signed(&fs[k], p1, p2) - r0[j]) / h
                } else {
                    0.0
                }
            });
            let (w, _) = tukey(r0[j], c);
            jtj += row * row.transpose() * w;
            jtr += row * (w * r0[j]);
        }
        let damp = 1e-9 * jtj.trace().max(1e-30);
        let mut a = jtj + M5::identity() * damp;
        if dims == 5 {
            a[(5, 5)] = 1.0;
        }
        let Some(d) = a.cholesky().map(|c| c.solve(&(-jtr))) else {
            break;
        };
        let next = pose.step(&d);
        if cost(&next, &inl, c) < cost(&pose, &inl, c) {
            pose = next;
        } else {
            break;
        }
        if d.norm() < 1e-10 {
            break;
        }
    }
    let f = pose.f(focal);
    f.iter().all(|v| v.is_finite()).then_some(f)
}
