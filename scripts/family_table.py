#!/usr/bin/env python3
"""ME, the motions found against the truth, and s/scene by N of a run on a
randomised family (driving-random, objects-3d) or any labelled synthetic
run.

Usage: python3 scripts/family_table.py results/<run>

Reads <run>/per_scene.csv and <run>/timings.csv. For every combination of
the run's swept parameters except `seed` (seeds are pooled: each (scene,
seed) is one unit), prints a Markdown table of: units; ME and ME_ALL in
percent, mean ± std (ddof 0) over units, as summary.csv computes them; the
share of units whose number of motions found equals the truth
(`motions` = `gt_motions`), with more / fewer; mean found / mean true; and a
second table of the mean total s/unit (timings.csv `total_s`) by N bin.
Standard library only.
"""
import csv
import statistics
import sys
from collections import OrderedDict

BINS = [(0, 500), (500, 2000), (2000, 5000), (5000, 10000), (10000, 10**9)]


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def combo_of(row, columns):
    params = [c for c in columns[: columns.index("scene")] if c != "seed"]
    return ", ".join(f"{k}={row[k]}" for k in params)


def pct(values):
    return f"{100 * statistics.fmean(values):.2f} ± {100 * statistics.pstdev(values):.2f}"


def bin_label(lo, hi):
    return f"{lo}-{hi - 1}" if hi < 10**9 else f">= {lo}"


def main(run):
    scenes = read(f"{run}/per_scene.csv")
    timings = read(f"{run}/timings.csv")
    groups = OrderedDict()
    for row in scenes:
        if row["status"] != "ok":
            continue
        groups.setdefault(combo_of(row, list(scenes[0].keys())), []).append(row)
    print("| combination | units | ME % | ME_ALL % | motions = truth | more / fewer | mean found / mean true |")
    print("|---|---|---|---|---|---|---|")
    for combo, rows in groups.items():
        found = [int(r["motions"]) for r in rows]
        truth = [int(r["gt_motions"]) for r in rows]
        exact = sum(f == t for f, t in zip(found, truth))
        more = sum(f > t for f, t in zip(found, truth))
        fewer = sum(f < t for f, t in zip(found, truth))
        print(
            f"| {combo} | {len(rows)} | {pct([float(r['me']) for r in rows])} "
            f"| {pct([float(r['me_all']) for r in rows])} "
            f"| {100 * exact / len(rows):.1f} % ({exact}) | {more} / {fewer} "
            f"| {statistics.fmean(found):.2f} / {statistics.fmean(truth):.2f} |"
        )
    by_bin = OrderedDict()
    for row in timings:
        combo = combo_of(row, list(timings[0].keys()))
        n = int(row["n"])
        b = next(b for b in BINS if b[0] <= n < b[1])
        by_bin.setdefault(combo, {}).setdefault(b, []).append(float(row["total_s"]))
    print()
    print("| combination | N | units | s/unit (mean) |")
    print("|---|---|---|---|")
    for combo, bins in by_bin.items():
        for b in BINS:
            if b in bins:
                t = bins[b]
                print(f"| {combo} | {bin_label(*b)} | {len(t)} | {statistics.fmean(t):.2f} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
