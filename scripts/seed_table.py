#!/usr/bin/env python3
"""A multi-seed design table of results/README.md from one run: for each
design (parameter values that select its rows), ME per seed, its mean and
standard deviation over seeds, ME over all points, the one-tailed Wilcoxon
p-values of "better" and of "worse than the reference" pooled over every
(scene, seed) pair (computed by `sctl wilcoxon`), the scenes better / worse by their mean over
seeds, and the median and mean seconds per scene (timings.csv).

    python3 scripts/seed_table.py SCTL RUN_DIR REFERENCE LABEL=key=value[,key=value] ...

REFERENCE is `key=value[,key=value]` selecting the reference design, which
is also the first row. Example:
    python3 scripts/seed_table.py target/release/sctl results/fast_profile_adelaidermf \\
        num_samples=3000,irls_iters=5 "fast=num_samples=1000,irls_iters=1"
"""
import csv
import json
import statistics
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path


def parse_where(spec):
    return dict(f.split("=", 1) for f in spec.split(",") if f)


def select(rows, where):
    return [r for r in rows if all(r.get(k) == v for k, v in where.items())]


def by_scene_seed(rows, metric):
    return {(r["scene"], r.get("seed", "")): 100 * float(r[metric]) for r in rows}


def pooled_p(sctl, reference, design, alternative):
    """One-tailed p of the design's ME being lower (`greater`: the
    reference's is larger) or higher (`less`) over the common pairs; None
    when every pair is equal."""
    keys = sorted(set(reference) & set(design))
    if all(reference[k] == design[k] for k in keys):
        return None
    with tempfile.TemporaryDirectory() as tmp:
        a, b = Path(tmp) / "a.txt", Path(tmp) / "b.txt"
        a.write_text("\n".join(str(reference[k]) for k in keys) + "\n")
        b.write_text("\n".join(str(design[k]) for k in keys) + "\n")
        out = subprocess.run(
            [sctl, "wilcoxon", "--baseline", str(a), "--method", str(b),
             "--alternative", alternative],
            capture_output=True, text=True, check=True,
        ).stdout
    return json.loads(out)["p_value"]


def scene_means(values):
    per_scene = defaultdict(list)
    for (scene, _), v in values.items():
        per_scene[scene].append(v)
    return {s: statistics.mean(v) for s, v in per_scene.items()}


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    sctl, run, reference_spec = sys.argv[1], Path(sys.argv[2]), sys.argv[3]
    rows = list(csv.DictReader(open(run / "per_scene.csv")))
    timings = list(csv.DictReader(open(run / "timings.csv")))
    designs = [("reference", reference_spec)] + [
        tuple(d.split("=", 1)) for d in sys.argv[4:]
    ]
    reference = by_scene_seed(select(rows, parse_where(reference_spec)), "me")
    seeds = sorted({r.get("seed", "") for r in rows})
    print("| design | " + " | ".join(f"seed {s}" for s in seeds)
          + " | ME mean (std over seeds) | ME all | p better / worse, pairs | scenes better / worse | s/scene median (mean) |")
    print("|" + "---|" * (len(seeds) + 6))
    for label, spec in designs:
        where = parse_where(spec)
        chosen = select(rows, where)
        me = by_scene_seed(chosen, "me")
        me_all = by_scene_seed(chosen, "me_all")
        per_seed = [
            statistics.mean(v for (_, s), v in me.items() if s == seed) for seed in seeds
        ]
        spread = statistics.pstdev(per_seed) if len(per_seed) > 1 else 0.0
        seconds = [float(t["total_s"]) for t in select(timings, where)]
        if label == "reference":
            p, wins = "", ""
        else:
            better_p = pooled_p(sctl, reference, me, "greater")
            worse_p = pooled_p(sctl, reference, me, "less")
            ref_scene, own_scene = scene_means(reference), scene_means(me)
            better = sum(own_scene[s] < ref_scene[s] - 1e-9 for s in own_scene)
            worse = sum(own_scene[s] > ref_scene[s] + 1e-9 for s in own_scene)
            pairs = len(set(reference) & set(me))
            p = (
                f"{better_p:.2g} / {worse_p:.2g}, {pairs}"
                if better_p is not None
                else f"all {pairs} equal"
            )
            wins = f"{better} / {worse}"
        print(
            f"| {label} ({spec}) | "
            + " | ".join(f"{v:.2f}" for v in per_seed)
            + f" | {statistics.mean(per_seed):.2f} ({spread:.2f}) | {statistics.mean(me_all.values()):.2f}"
            + f" | {p} | {wins} | {statistics.median(seconds):.3f} ({statistics.mean(seconds):.3f}) |"
        )


if __name__ == "__main__":
    main()
