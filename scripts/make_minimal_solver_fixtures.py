"""Makes crates/geometry/tests/fixtures/minimal_solvers.json: oracle answers
of the five-point relative-pose solver on seeded random scenes.

    pip install poselib==2.0.5 numpy
    python3 scripts/make_minimal_solver_fixtures.py

* five_point: PoseLib 2.0.5's essential_matrix_5pt (all real essential
  matrices of Nister's solver) on 5 unit bearings K^-1 x.
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


def main():
    rng = np.random.default_rng(SEED)
    five = []
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

        # Each case also draws a 6- and a 7-match scene, as when the fixture
        # held those solvers' answers, so that the five-point cases stay
        # the ones committed.
        scene(rng, 6, noise)
        scene(rng, 7, noise)
    fixture = {
        "poselib": poselib.__version__,
        "seed": SEED,
        "five_point": five,
    }
    OUT.write_text(json.dumps(fixture, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
