#!/usr/bin/env python3
"""How many matches share a keypoint with another match (coordinates equal
after rounding to 0.01 px, in image 1 or image 2: the keypoints of
`crates/segmentation/src/selection/uniqueness.rs`), among the ground-truth
outliers and among the inliers (results/notes/selection.md, "Keypoints").

Usage:
  python3 scripts/shared_keypoints.py [--sctl BIN] [--first 800] [--last 899] PRESET OUT_DIR
      writes the synthetic PRESET (generator seed 1, as every config of the
      family) into OUT_DIR with `sctl synth` and counts over scenes
      FIRST..LAST of every category folder;
  python3 scripts/shared_keypoints.py --matches DIR
      counts over the match files DIR/*.csv (`x1,y1,x2,y2,label`; label 0
      outlier, `unknown` counted apart), e.g. datasets/real-sift.
Needs numpy (the npz files).
"""
import argparse
import csv
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np

STEP_PX = 0.01


def shared(points):
    """Per row of an N x 2 array: whether another row is the same keypoint."""
    keys = [tuple(k) for k in np.round(np.asarray(points) / STEP_PX).astype(np.int64)]
    count = Counter(keys)
    return np.array([count[k] > 1 for k in keys])


def tally(totals, p1, p2, kinds):
    """Adds each match's kind (outlier / inlier / unknown) and whether it
    shares a keypoint."""
    share = shared(p1) | shared(p2)
    for kind, s in zip(kinds, share):
        totals[kind][0] += int(s)
        totals[kind][1] += 1


def synthetic(args, totals):
    if args.out.exists() and any(args.out.iterdir()):
        sys.exit(f"shared_keypoints: {args.out} is not empty; name a new directory")
    subprocess.run([args.sctl, "synth", "--preset", args.preset, "--seed", "1", "--out",
                    str(args.out)], check=True, capture_output=True)
    for category in sorted(p for p in args.out.iterdir() if p.is_dir()):
        for scene in range(args.first, args.last + 1):
            path = category / f"{scene:04d}" / "features_and_ground_truth.npz"
            if not path.exists():
                continue
            d = np.load(path)
            kinds = ["outlier" if label == 0 else "inlier" for label in d["labels"]]
            tally(totals, d["points1"][:, :2], d["points2"][:, :2], kinds)


def match_files(directory, totals):
    for path in sorted(directory.glob("*.csv")):
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        p1 = [[float(r["x1"]), float(r["y1"])] for r in rows]
        p2 = [[float(r["x2"]), float(r["y2"])] for r in rows]
        kinds = ["unknown" if r["label"] == "unknown" else
                 "outlier" if r["label"] == "0" else "inlier" for r in rows]
        tally(totals, p1, p2, kinds)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("preset", nargs="?")
    ap.add_argument("out", nargs="?", type=Path)
    ap.add_argument("--sctl", default="target/release/sctl")
    ap.add_argument("--first", type=int, default=800)
    ap.add_argument("--last", type=int, default=899)
    ap.add_argument("--matches", type=Path)
    args = ap.parse_args()
    totals = {kind: [0, 0] for kind in ("outlier", "inlier", "unknown")}
    if args.matches:
        match_files(args.matches, totals)
    elif args.preset and args.out:
        synthetic(args, totals)
    else:
        ap.error("give PRESET OUT_DIR, or --matches DIR")
    for kind, (share, total) in totals.items():
        if total:
            print(f"{kind}: {share} of {total} share a keypoint ({100 * share / total:.1f} %)")


if __name__ == "__main__":
    main()
