#!/usr/bin/env python3
"""Focal lengths of a hypotheses dump by PoseLib, as the reference
implementation computes them (results/README.md, "PoseLib's answers on our
hypotheses").

Usage: python3 scripts/poselib_focals.py HYPS.csv FOCALS.csv [hopef]
       python3 scripts/poselib_focals.py summary F_PRIOR TAU_RANGE FOCALS.csv...

HYPS.csv comes from `sctl hypotheses CONFIG --out HYPS.csv` (columns scene,
hypothesis, f_prior, F00..F22). For every hypothesis this runs PoseLib's
focals_from_fundamental_iterative with each of the reference code's weight
sets (AdelaideRMF: 4 sets, max_iters 100; `hopef`: 6 sets, max_iters 120)
and keeps the answer with the fewest iterations, ties by the smallest
|f1 - f2| (the reference code's choose_weights), whatever PoseLib returns.

Writes scene, hypothesis, f1, f2, iterations, kruppa_residual and F00..F22
(copied, so that `focal_solver = "external"` can check that the file belongs
to its hypotheses). kruppa_residual = max |g_i(x)| / max |g_i(p)| at the
answer x (docs/method.md step 4): above 1e-6 the answer is no solution of the
Kruppa equations (the fixture's `infeasible`); 1 for the prior itself.

`summary` prints what the answers of FOCALS.csv are: the prior (f1 = f2 =
F_PRIOR, exactly and after truncation to integers), non-finite, solutions of
the Kruppa equations (kruppa_residual <= 1e-6) and non-solutions, each also
counted inside the band |f_avg - F_PRIOR| <= TAU_RANGE * F_PRIOR, f1, f2 > 0
(standard library only).

Needs `pip install poselib==2.0.5 numpy` (the version the thesis tables and
the fixtures were made with).
"""
import csv
import math
import sys
from collections import Counter

try:
    import numpy as np
    import poselib
except ImportError:  # `summary` needs neither
    np = poselib = None

ADELAIDE = [(1e-3, 1, 1e-3, 1), (5e-4, 1, 5e-4, 1), (1e-4, 1, 1e-4, 1), (5e-4, 2, 5e-4, 2)]
HOPEF = ADELAIDE + [(1e-3, 2, 1e-3, 2), (1e-4, 3, 1e-4, 3)]


def summary(f_prior, tau_range, paths):
    f_prior, tau_range = float(f_prior), float(tau_range)
    counts = Counter()
    for path in paths:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                f1, f2 = float(row["f1"]), float(row["f2"])
                counts["answers"] += 1
                if not (math.isfinite(f1) and math.isfinite(f2)):
                    counts["non-finite"] += 1
                    continue
                if f1 == f2 == f_prior:
                    counts["prior, exactly"] += 1
                    continue
                if math.trunc(f1) == math.trunc(f2) == f_prior:
                    counts["prior after truncation"] += 1
                    continue
                kind = "solution" if float(row["kruppa_residual"]) <= 1e-6 else "non-solution"
                band = f1 > 0 and f2 > 0 and abs((f1 + f2) / 2 - f_prior) <= tau_range * f_prior
                counts[kind] += 1
                counts[f"{kind}, in the band"] += band
    total = counts.pop("answers")
    print(f"{total} answers")
    for key in ["prior, exactly", "prior after truncation", "non-solution", "non-solution, in the band",
                "solution", "solution, in the band", "non-finite"]:
        print(f"{key:28} {counts[key]:8} {100 * counts[key] / total:6.2f} %")


def kruppa(fundamental, x):
    """(g1, g2) of docs/method.md step 4 at x = (f1, u1, v1, f2, u2, v2), F scaled to unit norm."""
    u, s, vt = np.linalg.svd(fundamental / np.linalg.norm(fundamental))
    v = vt.T

    def conic(f, pu, pv):
        return np.array([[f * f + pu * pu, pu * pv, pu], [pu * pv, f * f + pv * pv, pv], [pu, pv, 1.0]])

    w1, w2 = conic(*x[:3]), conic(*x[3:])
    u1, u2, v1, v2 = u[:, 0], u[:, 1], v[:, 0], v[:, 1]
    g1 = s[0] * (v1 @ w1 @ v1) * (u1 @ w2 @ u2) + s[1] * (v1 @ w1 @ v2) * (u2 @ w2 @ u2)
    g2 = s[0] * (v1 @ w1 @ v2) * (u1 @ w2 @ u1) + s[1] * (v2 @ w1 @ v2) * (u1 @ w2 @ u2)
    return np.array([g1, g2])


def relative_residual(fundamental, x, f_prior):
    if not np.all(np.isfinite(x)):
        return float("nan")
    at_prior = np.abs(kruppa(fundamental, [f_prior, 0.0, 0.0, f_prior, 0.0, 0.0])).max()
    return float(np.abs(kruppa(fundamental, x)).max() / at_prior)


def best_answer(fundamental, f_prior, weight_sets, max_iters):
    camera = {"model": "SIMPLE_PINHOLE", "width": -1, "height": -1, "params": [f_prior, 0.0, 0.0]}
    best = None
    for weights in weight_sets:
        cam1, cam2, iterations = poselib.focals_from_fundamental_iterative(
            fundamental, camera, camera, max_iters=max_iters, weights=np.asarray(weights, dtype=float)
        )
        f1, f2 = float(cam1.focal()), float(cam2.focal())
        key = (int(iterations), abs(f1 - f2))
        if best is None or key < best[0]:
            x = list(cam1.params) + list(cam2.params)
            best = (key, f1, f2, int(iterations), x)
    f1, f2, iterations, x = best[1:]
    return f1, f2, iterations, relative_residual(fundamental, np.array(x, dtype=float), f_prior)


def main(hyps_path, out_path, dataset="adelaidermf"):
    if poselib is None:
        sys.exit("needs PoseLib and NumPy: pip install poselib==2.0.5 numpy")

    weight_sets, max_iters = (HOPEF, 120) if dataset == "hopef" else (ADELAIDE, 100)
    names = [f"F{i}{j}" for i in range(3) for j in range(3)]
    with open(hyps_path, newline="") as f_in, open(out_path, "w", newline="") as f_out:
        out = csv.writer(f_out)
        out.writerow(["scene", "hypothesis", "f1", "f2", "iterations", "kruppa_residual"] + names)
        for row in csv.DictReader(f_in):
            fundamental = np.array([float(row[n]) for n in names]).reshape(3, 3)
            prior = float(row["f_prior"])
            f1, f2, iterations, residual = best_answer(fundamental, prior, weight_sets, max_iters)
            out.writerow(
                [row["scene"], row["hypothesis"], repr(f1), repr(f2), iterations, f"{residual:.3e}"]
                + [row[n] for n in names]
            )


if __name__ == "__main__":
    if len(sys.argv) >= 5 and sys.argv[1] == "summary":
        summary(sys.argv[2], sys.argv[3], sys.argv[4:])
    elif len(sys.argv) in (3, 4):
        main(*sys.argv[1:])
    else:
        sys.exit(__doc__)
