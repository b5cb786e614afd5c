"""Makes crates/geometry/tests/fixtures/minimal_solvers.json: oracle answers
of the minimal relative-pose solvers on seeded random scenes.

    pip install poselib==2.0.5 numpy
    python3 scripts/make_minimal_solver_fixtures.py

* five_point: PoseLib 2.0.5's essential_matrix_5pt (all real essential
  matrices of Nister's solver) on 5 unit bearings K^-1 x.
* six_point: PoseLib 2.0.5's shared_focal_relpose_6pt on 6 pixel matches
  (principal point at the origin). PoseLib is called on the pixels divided
  by SCALE_6PT (its solver is not scaled internally) and its focal is
  multiplied back; it returns only the poses that pass its cheirality test,
  one entry per distinct focal is kept (focal in pixels and E = [t]x R).
* seven_point: PoseLib 2.0.5 has no 7-point binding; the reference is a
  direct numpy transcription of Hartley & Zisserman 11.1.2 (Hartley
  normalisation, SVD null space, det(F1 + t F2) interpolated at four t,
  numpy.roots, real roots only).

Half of the scenes are noise-free (then the truth is stored and must be
among the solutions), half have 0.5 px noise (the solvers still return exact
solutions of the perturbed sample).
"""
import json
import pathlib
import sys

import numpy as np
import poselib

ROOT = pathlib.Path(__file__).resolve().parent.parent
# The random rotation of the polish fixture's script (same scene family).
sys.dont_write_bytecode = True
sys.path.insert(0, str(ROOT / "crates/geometry/tests/fixtures"))
from make_poselib_refine import rotation  # noqa: E402

SEED = 20251202
CASES = 40
NOISE_PX = 0.5
SCALE_6PT = 1000.0
OUT = ROOT / "crates/geometry/tests/fixtures/minimal_solvers.json"


def skew(t):
    return np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])


def scene(rng, n, noise):
    """n matches of a random rigid motion seen by one camera (shared focal)."""
    r = rotation(rng, 0.4)
    t = rng.normal(size=3)
    t *= rng.uniform(0.5, 1.5) / np.linalg.norm(t)
    f = rng.uniform(500, 1500)
    p1, p2 = [], []
    while len(p1) < n:
        u, v = rng.uniform(-320, 320), rng.uniform(-240, 240)
        x = np.array([u / f, v / f, 1.0]) * rng.uniform(4, 12)
        y = r @ x + t
        if y[2] < 1:
            continue
        p1.append([u, v] + rng.normal(scale=noise, size=2) * (noise > 0))
        p2.append([f * y[0] / y[2], f * y[1] / y[2]] + rng.normal(scale=noise, size=2) * (noise > 0))
    return np.array(p1), np.array(p2), f, skew(t) @ r


def unit(m):
    m = np.asarray(m, dtype=float)
    return m / np.linalg.norm(m)


def bearings(p, f):
    h = np.column_stack([p / f, np.ones(len(p))])
    return h / np.linalg.norm(h, axis=1, keepdims=True)


def hartley(p):
    c = p.mean(axis=0)
    s = np.sqrt(2) / np.mean(np.linalg.norm(p - c, axis=1))
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])


def seven_point_reference(p1, p2):
    t1, t2 = hartley(p1), hartley(p2)
    h1 = (t1 @ np.column_stack([p1, np.ones(7)]).T).T
    h2 = (t2 @ np.column_stack([p2, np.ones(7)]).T).T
    a = np.einsum("ni,nj->nij", h2, h1).reshape(7, 9)
    _, _, vt = np.linalg.svd(a)
    f1, f2 = vt[-1].reshape(3, 3), vt[-2].reshape(3, 3)
    ts = np.array([-1.0, 0.0, 1.0, 2.0])
    dets = [np.linalg.det(f1 + t * f2) for t in ts]
    coeffs = np.polyfit(ts, dets, 3)
    out = []
    for root in np.roots(coeffs):
        if abs(root.imag) < 1e-8 * (1 + abs(root.real)):
            f = t2.T @ (f1 + root.real * f2) @ t1
            out.append(unit(f).reshape(-1).tolist())
    return out


def main():
    rng = np.random.default_rng(SEED)
    five, six, seven = [], [], []
    for k in range(CASES):
        noise = 0.0 if k < CASES // 2 else NOISE_PX

        p1, p2, f, e = scene(rng, 5, noise)
        b1, b2 = bearings(p1, f), bearings(p2, f)
        es = poselib.essential_matrix_5pt(np.ascontiguousarray(b1), np.ascontiguousarray(b2))
        five.append({
            "noise_px": noise,
            "bearings1": b1.tolist(),
            "bearings2": b2.tolist(),
            "essential_true": unit(e).reshape(-1).tolist(),
            "poselib": [unit(m).reshape(-1).tolist() for m in es],
        })

        p1, p2, f, e = scene(rng, 6, noise)
        h1 = np.column_stack([p1 / SCALE_6PT, np.ones(6)])
        h2 = np.column_stack([p2 / SCALE_6PT, np.ones(6)])
        pairs = poselib.shared_focal_relpose_6pt(np.ascontiguousarray(h1), np.ascontiguousarray(h2))
        found = []
        for pair in pairs:
            focal = pair.camera1.focal() * SCALE_6PT
            if any(abs(focal - g["focal"]) <= 1e-9 * focal for g in found):
                continue
            ess = skew(pair.pose.t) @ pair.pose.R
            found.append({"focal": focal, "essential": unit(ess).reshape(-1).tolist()})
        six.append({
            "noise_px": noise,
            "points1": p1.tolist(),
            "points2": p2.tolist(),
            "focal_true": f,
            "essential_true": unit(e).reshape(-1).tolist(),
            "poselib": found,
        })

        p1, p2, f, e = scene(rng, 7, noise)
        kinv = np.diag([1 / f, 1 / f, 1])
        seven.append({
            "noise_px": noise,
            "points1": p1.tolist(),
            "points2": p2.tolist(),
            "fundamental_true": unit(kinv @ e @ kinv).reshape(-1).tolist(),
            "reference": seven_point_reference(p1, p2),
        })
    fixture = {
        "poselib": poselib.__version__,
        "seed": SEED,
        "five_point": five,
        "six_point": six,
        "seven_point": seven,
    }
    OUT.write_text(json.dumps(fixture, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
