#!/usr/bin/env python3
"""The designs table of results/README.md: for each design (a run and the
parameter values that select its rows), ME and ME over all points (mean over
scene runs, %), the mean hypotheses kept, the median f_peak error where the
focal is known, the scenes with an implausible consensus, the mean seconds
per scene (timings.csv of the same run) and that time over the time of the
run's own 8-point baseline rows (a ratio that holds when the machine was
shared with other jobs).

    python3 scripts/design_table.py DATASET_LABEL LABEL=RUN_DIR[:key=value,...] ...

Example:
    python3 scripts/design_table.py AdelaideRMF \\
        "5-point=results/minimal_solvers_adelaidermf:minimal_solver=five-point"
"""
import csv
import statistics
import sys
from pathlib import Path


def select(rows, where):
    return [r for r in rows if all(r.get(k) == v for k, v in where.items())]


def cell(values, fmt):
    return fmt.format(statistics.mean(values)) if values else "–"


def design_row(dataset, label, spec):
    run, _, filters = spec.partition(":")
    where = dict(f.split("=", 1) for f in filters.split(",") if f)
    rows = select(list(csv.DictReader(open(Path(run) / "per_scene.csv"))), where)
    all_timings = list(csv.DictReader(open(Path(run) / "timings.csv")))
    timings = select(all_timings, where)
    if not rows:
        sys.exit(f"{run}: no row matches {where}")
    me = [100 * float(r["me"]) for r in rows if r["me"]]
    me_all = [100 * float(r["me_all"]) for r in rows if r.get("me_all")]
    kept = [float(r["hypotheses_kept"]) for r in rows]
    errors = [float(r["f_peak_error"]) for r in rows if r["f_peak_error"]]
    judged = [r for r in rows if r.get("focal_verdict")]
    implausible = sum(r["focal_verdict"] == "implausible" for r in judged)
    seconds = [float(t["total_s"]) for t in timings]
    baseline = [
        float(t["total_s"])
        for t in all_timings
        if t.get("method", "baseline") == "baseline"
        and t.get("minimal_solver", "eight-point") == "eight-point"
    ]
    return [
        label,
        dataset,
        str(len(rows)),
        cell(me, "{:.2f}"),
        cell(me_all, "{:.2f}"),
        cell(kept, "{:.0f}"),
        f"{statistics.median(errors):.2f}" if errors else "–",
        f"{implausible} / {len(judged)}" if judged else "–",
        cell(seconds, "{:.2f}"),
        f"{statistics.mean(seconds) / statistics.mean(baseline):.1f}" if baseline and seconds else "–",
    ]


def main():
    dataset, specs = sys.argv[1], sys.argv[2:]
    print("| design | data | scene runs | ME % | ME all % | kept | median f_peak error | f_peak implausible | s/scene | × 8-point baseline |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for spec in specs:
        label, _, rest = spec.partition("=")
        print("| " + " | ".join(design_row(dataset, label, rest)) + " |")


if __name__ == "__main__":
    main()
