#!/usr/bin/env python3
"""A synthetic match file of three rigid motions seen by one camera, for
timing `sctl segment` at large N (results/README.md, "One default", "Cost at
large N"): a background (60 % of N), two movers (20 % and 10 %), 10 %
uniform outliers, 0.5 px noise, 1024 x 768, focal 900 px. Labels: 0
outlier, 1 background, 2 and 3 the movers.

Usage: python3 scripts/three_motion_pair.py N OUT.csv   (numpy; seed 7)
  then: sctl segment --matches OUT.csv --width 1024 --height 768 --threads 1
"""
import sys

import numpy as np

W, H, F = 1024, 768, 900.0


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


MOTIONS = [
    (0.6, rotation([0, 1, 0], 0.02), np.array([0.05, 0, -0.6]), (-500, 500), (4, 12)),
    (0.2, rotation([0, 1, 0.2], -0.1), np.array([0.4, 0, -0.3]), (-500, 0), (5, 8)),
    (0.1, rotation([1, 1, 0], 0.08), np.array([-0.2, 0.3, 0.1]), (0, 500), (5, 8)),
]


def scene(n, seed):
    rng = np.random.default_rng(seed)
    p1, p2, labels = [], [], []
    for label, (share, r, t, region, depth) in enumerate(MOTIONS, start=1):
        want, got = int(n * share), 0
        while got < want:
            m = (want - got) * 2
            u, v = rng.uniform(*region, m), rng.uniform(-370, 370, m)
            z = rng.uniform(*depth, m)
            x2 = np.stack([u / F * z, v / F * z, z], 1) @ r.T + t
            q = np.stack([F * x2[:, 0] / x2[:, 2], F * x2[:, 1] / x2[:, 2]], 1)
            ok = (x2[:, 2] > 0.5) & (np.abs(q[:, 0]) < 511) & (np.abs(q[:, 1]) < 383)
            a, b = np.stack([u, v], 1)[ok][: want - got], q[ok][: want - got]
            p1.append(a)
            p2.append(b)
            labels += [label] * len(a)
            got += len(a)
    rest = n - len(labels)
    for p in (p1, p2):
        p.append(np.stack([rng.uniform(-511, 511, rest), rng.uniform(-383, 383, rest)], 1))
    labels += [0] * rest
    centre = [511.5, 383.5]
    p1 = np.concatenate(p1) + rng.normal(0, 0.5, (n, 2)) + centre
    p2 = np.concatenate(p2) + rng.normal(0, 0.5, (n, 2)) + centre
    return p1, p2, labels


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    n, out = int(sys.argv[1]), sys.argv[2]
    p1, p2, labels = scene(n, 7)
    with open(out, "w") as f:
        f.write("x1,y1,x2,y2,label\n")
        for a, b, label in zip(p1, p2, labels):
            f.write(f"{a[0]:.3f},{a[1]:.3f},{b[0]:.3f},{b[1]:.3f},{label}\n")


if __name__ == "__main__":
    main()
