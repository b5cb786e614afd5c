#!/usr/bin/env python3
"""Where the default's motion count goes wrong on HOPE-F-like scenes:
each motion found is described by the truth of its matches, each true motion
by whether a found motion holds most of it (results/notes/selection.md,
"Where the count is lost").

Usage: python3 scripts/count_errors.py [--sctl BIN] [--preset hopef] [--first 800]
       [--last 899] [--seeds 12345,1,2] OUT_DIR

Writes the preset (`hopef` or `adelaide-like`; generator seed 1, as every
config of the family) into OUT_DIR/data with `sctl synth`, segments scenes
FIRST..LAST of its four categories with `sctl segment` (the default profile,
one thread, focal prior max(W, H), the scene's image size) and writes OUT_DIR/scenes.csv (one row per
scene: N, outliers, true motions and their sizes, motions found, found
motions whose majority is ground-truth outliers, true motions split, true
motions no found motion holds the majority of) and prints a summary. With
more than one seed, the labels of the first are described and each of its
motions is looked for among the motions the other seeds find (the same
matches within Jaccard >= 1/2): how often the motions of outliers and the
others come back (results/README.md, "Tried and not adopted", stability
selection). Needs numpy (the npz files).
"""
import argparse
import csv
import statistics
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np


def segment(sctl, matches_csv, size, seed, work):
    """The default's labels of one match file (-1 outliers) with this seed;
    `size` the images' (width, height)."""
    config = work / f"seed_{seed}.toml"
    if not config.exists():
        config.write_text(f"[pipeline]\nseed = {seed}\n")
    run = subprocess.run(
        [sctl, "segment", "--matches", str(matches_csv), "--width", str(size[0]),
         "--height", str(size[1]), "--threads", "1", "--config", str(config), "--out", "-"],
        capture_output=True, text=True, check=True)
    return np.array([int(x) for x in run.stdout.split()])


def comes_back(labels, others):
    """Per motion of `labels`: (its majority truth is outliers, in how many of
    `others` a motion covers it with Jaccard >= 1/2)."""
    back = []
    for c in sorted(set(labels.tolist()) - {-1}):
        mine = labels == c
        hits = 0
        for other in others:
            hits += any(2 * (mine & (other == d)).sum() >= (mine | (other == d)).sum()
                        for d in set(other.tolist()) - {-1})
        back.append(hits)
    return back


def write_matches(scene_dir, path):
    """The scene's matches as `x1,y1,x2,y2,label` (label 0 outlier); its
    truth and image size."""
    d = np.load(scene_dir / "features_and_ground_truth.npz")
    truth = d["labels"]
    with open(path, "w") as f:
        f.write("x1,y1,x2,y2,label\n")
        for a, b, t in zip(d["points1"], d["points2"], truth):
            f.write(f"{a[0]},{a[1]},{b[0]},{b[1]},{t}\n")
    size = np.load(scene_dir / "camera_parameters.npz")["image_size"]
    return truth, (int(size[0]), int(size[1]))


def majority_truth(truth, labels):
    """Per motion found (label order): the truth most of its matches have
    (0 gross outliers)."""
    return [Counter(truth[labels == c].tolist()).most_common(1)[0][0]
            for c in sorted(set(labels.tolist()) - {-1})]


def describe(truth, labels):
    """Counts of one scene: found motions by the majority of their matches."""
    motions = [g for g in sorted(set(truth.tolist())) if g != 0]
    majority = majority_truth(truth, labels)
    held = Counter(majority)
    return {
        "n": len(truth),
        "outliers": int((truth == 0).sum()),
        "true_motions": len(motions),
        "sizes": " ".join(str(int((truth == g).sum())) for g in motions),
        "found": len(majority),
        "found_of_outliers": held[0],
        "splits": sum(k - 1 for g, k in held.items() if g != 0 and k > 1),
        "missed": " ".join(str(int((truth == g).sum())) for g in motions if g not in held),
    }


def summary_back(back, runs):
    """How often the motions of outliers and the others come back."""
    for kind in (True, False):
        found = [hits for of_outliers, hits in back if of_outliers == kind]
        name = "of outliers" if kind else "of a true motion"
        share = " ".join(f"{k}: {sum(h == k for h in found)}" for k in range(runs + 1))
        print(f"found motions {name}: {len(found)}, found again in k of {runs} other runs: {share}")


def summary(rows):
    n = len(rows)
    right = sum(r["found"] == r["true_motions"] for r in rows)
    under = sum(r["found"] < r["true_motions"] for r in rows)
    missed = [int(s) for r in rows for s in r["missed"].split()]
    smallest = [min(int(s) for s in r["sizes"].split()) for r in rows if r["sizes"]]
    print(f"{n} scenes: count right {right} ({100 * right / n:.1f} %), "
          f"under {under}, over {n - right - under}")
    print(f"found motions mostly of outliers: {sum(r['found_of_outliers'] for r in rows)}; "
          f"true motions split: {sum(r['splits'] for r in rows)}")
    if missed:
        print(f"true motions held by no found motion: {len(missed)}, median size "
              f"{statistics.median(missed)}; under 10 matches {sum(s < 10 for s in missed)}, "
              f"10-19 {sum(10 <= s < 20 for s in missed)}")
    for k in (10, 15, 20):
        print(f"scenes whose every motion has >= {k} matches: "
              f"{sum(s >= k for s in smallest)} of {n}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--sctl", default="target/release/sctl")
    ap.add_argument("--preset", default="hopef", choices=["hopef", "adelaide-like"])
    ap.add_argument("--first", type=int, default=800)
    ap.add_argument("--last", type=int, default=899)
    ap.add_argument("--seeds", default="12345")
    args = ap.parse_args()
    seeds = [int(x) for x in args.seeds.split(",")]
    if args.out.exists() and any(args.out.iterdir()):
        sys.exit(f"count_errors: {args.out} is not empty; name a new directory")
    data = args.out / "data"
    subprocess.run([args.sctl, "synth", "--preset", args.preset, "--seed", "1", "--out",
                    str(data)], check=True, capture_output=True)
    rows, back = [], []
    for category in "1234":
        for scene in range(args.first, args.last + 1):
            name = f"{category}/{scene:04d}"
            matches = args.out / f"{category}_{scene:04d}.csv"
            truth, size = write_matches(data / name, matches)
            runs = [segment(args.sctl, matches, size, seed, args.out) for seed in seeds]
            rows.append({"scene": name, **describe(truth, runs[0])})
            of_outliers = [t == 0 for t in majority_truth(truth, runs[0])]
            back += zip(of_outliers, comes_back(runs[0], runs[1:]))
    with open(args.out / "scenes.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    summary(rows)
    if len(seeds) > 1:
        summary_back(back, len(seeds) - 1)


if __name__ == "__main__":
    main()
