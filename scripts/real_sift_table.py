#!/usr/bin/env python3
"""The real-sift table (datasets/real-sift/README.md): per run, ME and ME over
all points (%, mean over scenes x seeds, known matches only), the motions
found against the true motions among the known labels, the mean seconds
per scene (timings.csv) and the scenes whose ME, averaged over the seeds,
is above 15 %. Standard library only.

    python3 scripts/real_sift_table.py results/real_sift_default results/real_sift_fast ...
"""
import csv
import statistics
import sys
from collections import defaultdict
from pathlib import Path

THRESHOLD = 15.0


def row(run):
    rows = list(csv.DictReader(open(Path(run) / "per_scene.csv")))
    timings = list(csv.DictReader(open(Path(run) / "timings.csv")))
    me = [100 * float(r["me"]) for r in rows]
    me_all = [100 * float(r["me_all"]) for r in rows]
    found = [int(r["motions"]) for r in rows]
    truth = [int(r["gt_motions"]) for r in rows]
    exact = sum(f == t for f, t in zip(found, truth))
    by_scene = defaultdict(list)
    for r in rows:
        by_scene[r["scene"]].append(100 * float(r["me"]))
    high = sorted(
        ((statistics.mean(v), s) for s, v in by_scene.items() if statistics.mean(v) > THRESHOLD),
        reverse=True,
    )
    seconds = statistics.mean(float(t["total_s"]) for t in timings)
    return (
        f"| {Path(run).name} | {len(rows)} | {statistics.mean(me):.2f} | {statistics.mean(me_all):.2f} "
        f"| {statistics.mean(found):.2f} / {statistics.mean(truth):.2f} | {exact}/{len(rows)} "
        f"| {seconds:.3f} | {', '.join(f'{s} {m:.1f}' for m, s in high) or 'none'} |"
    )


def main(runs):
    print(
        "| run | scene runs | ME % | ME all points % | motions found / true (mean) "
        f"| runs with the true count | s/scene | scenes with ME > {THRESHOLD:.0f} % (mean over seeds) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---|")
    for run in runs:
        print(row(run))


if __name__ == "__main__":
    main(sys.argv[1:])
