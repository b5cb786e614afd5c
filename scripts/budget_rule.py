#!/usr/bin/env python3
"""The fast profile's fifth-round rule (results/README.md, "The most
accurate setting within the time budget"): the candidate of lowest ME
summed over the validation sets among those whose time is within the
budget.

    python3 scripts/budget_rule.py [BUDGET_S]

Reads, under results/:
- timing_fast_budget_adelaide_like/run*/timings.csv: a candidate's time is
  the median over the runs of the run's median per-scene total_s;
- validation_fast_budget_{hopef,kitti,adelaide_like}/summary.csv: a
  candidate's ME (thesis protocol) on a set is the mean over seeds of the
  seed's mean over scenes (me_mean); ME over all points likewise
  (me_all_mean), reported, not ruled on.
A candidate is (num_samples, guided_batch). BUDGET_S defaults to 0.02.
"""
import csv
import statistics
import sys
from collections import defaultdict
from pathlib import Path

RESULTS = Path(__file__).resolve().parent.parent / "results"
SETS = ["hopef", "kitti", "adelaide_like"]


def candidate(row):
    return int(row["num_samples"]), int(row["guided_batch"])


def times():
    """{candidate: median over runs of the run's median s/scene}, runs."""
    runs = sorted((RESULTS / "timing_fast_budget_adelaide_like").glob("run*/timings.csv"))
    if not runs:
        sys.exit("no results/timing_fast_budget_adelaide_like/run*/timings.csv")
    per_run = defaultdict(list)
    for path in runs:
        totals = defaultdict(list)
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                totals[candidate(row)].append(float(row["total_s"]))
        for c, t in totals.items():
            per_run[c].append(statistics.median(t))
    return {c: statistics.median(t) for c, t in per_run.items()}, per_run, len(runs)


def accuracy(name):
    """{candidate: (mean ME over seeds, mean ME all over seeds)} of one set."""
    me, me_all = defaultdict(list), defaultdict(list)
    with open(RESULTS / f"validation_fast_budget_{name}" / "summary.csv", newline="") as f:
        for row in csv.DictReader(f):
            me[candidate(row)].append(float(row["me_mean"]))
            me_all[candidate(row)].append(float(row["me_all_mean"]))
    return {c: (statistics.mean(me[c]), statistics.mean(me_all[c])) for c in me}


def main(argv):
    budget = float(argv[0]) if argv else 0.02
    time, per_run, n_runs = times()
    sets = {name: accuracy(name) for name in SETS}
    candidates = sorted(set(time).intersection(*sets.values()))
    total = {c: sum(sets[s][c][0] for s in SETS) for c in candidates}
    print(f"| candidate | s/scene (median of {n_runs} runs; range) | "
          + " | ".join(f"{s} ME (ME all)" for s in SETS) + " | ME summed | affordable |")
    print("|" + "---|" * (len(SETS) + 4))
    for c in candidates:
        cells = [f"{sets[s][c][0]:.2f} ({sets[s][c][1]:.2f})" for s in SETS]
        spread = f"{min(per_run[c]):.4f}–{max(per_run[c]):.4f}"
        print(f"| M {c[0]}, batches of {c[1]} | {time[c]:.4f} ({spread}) | "
              + " | ".join(cells)
              + f" | {total[c]:.2f} | {'yes' if time[c] <= budget else 'no'} |")
    affordable = [c for c in candidates if time[c] <= budget]
    if not affordable:
        print(f"\nno candidate within {budget} s")
        return
    chosen = min(affordable, key=lambda c: (total[c], time[c]))
    print(f"\nchosen: M {chosen[0]}, batches of {chosen[1]} "
          f"(ME summed {total[chosen]:.2f}, {time[chosen]:.4f} s per scene)")


if __name__ == "__main__":
    main(sys.argv[1:])
