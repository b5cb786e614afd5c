#!/usr/bin/env python3
"""Checks that a regenerated run equals a committed one on every column both
have: per_scene.csv and summary.csv cell for cell, wilcoxon.csv row for row
(rows keyed by their first cells). Columns only the new run has are listed.

    python3 scripts/compare_runs.py results/<run> /tmp/regen/<run>
"""
import csv
import sys
from pathlib import Path


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def compare(old_dir, new_dir, name, key_cells):
    old, new = rows(old_dir / name), rows(new_dir / name)
    if not old:
        return ([] if not new else [f"{name}: committed file empty"]), []
    common = [c for c in old[0] if c in new[0]]
    added = [c for c in new[0] if c not in old[0]]
    problems = [f"{name}: column {c} missing" for c in old[0] if c not in new[0]]
    key = lambda r: tuple(r[c] for c in key_cells(r))
    new_by_key = {key(r): r for r in new}
    old_keys = [key(r) for r in old]
    if name != "wilcoxon.csv" and len(old) != len(new):
        problems.append(f"{name}: {len(old)} rows committed, {len(new)} regenerated")
    for r, k in zip(old, old_keys):
        n = new_by_key.get(k)
        if n is None:
            problems.append(f"{name}: row {k} missing")
            continue
        for c in common:
            if r[c] != n[c]:
                problems.append(f"{name}: row {k} column {c}: {r[c]!r} -> {n[c]!r}")
    return problems, added


def main():
    old_dir, new_dir = Path(sys.argv[1]), Path(sys.argv[2])
    all_problems = []
    for name in ["per_scene.csv", "summary.csv", "wilcoxon.csv"]:
        if not (old_dir / name).exists():
            continue
        if name == "wilcoxon.csv":
            cells = lambda r: [c for c in r if c not in ("n", "statistic", "p_value", "mode_used")]
        else:
            cells = lambda r: list(r)[: list(r).index("scenes") + 1] if "scenes" in r else list(r)[: list(r).index("n")]
        problems, added = compare(old_dir, new_dir, name, cells)
        all_problems += problems
        print(f"{name}: {len(problems)} differences; new columns: {', '.join(added) or '-'}")
    for p in all_problems[:20]:
        print("  " + p)
    sys.exit(1 if all_problems else 0)


if __name__ == "__main__":
    main()
