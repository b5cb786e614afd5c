#!/usr/bin/env python3
"""ME and focal consensus error per category of a HOPE-F (or hopef-like
synthetic) run.

Usage: python3 scripts/category_table.py results/<run>/per_scene.csv

Scene names are `<category>/<index>` (the category is the number of moving
objects). Prints two Markdown tables: for every combination of the run's
swept parameters and every category, (1) the mean ± std (ddof 0) of ME in
percent, as summary.csv computes them, with the number of scenes; (2) where
f_peak_error = |f_peak - f_true| / f_true is known, its median and the share
of scenes with an error of at most 0.25. Standard library only.
"""
import csv
import statistics
import sys
from collections import OrderedDict


def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    columns = list(rows[0].keys())
    params = columns[: columns.index("scene")]
    me = OrderedDict()
    focal = OrderedDict()
    for row in rows:
        combo = ", ".join(f"{k}={row[k]}" for k in params)
        category = row["scene"].split("/")[0]
        if row["me"] != "":
            me.setdefault(combo, OrderedDict()).setdefault(category, []).append(100 * float(row["me"]))
        if row.get("f_peak_error", "") != "":
            focal.setdefault(combo, OrderedDict()).setdefault(category, []).append(float(row["f_peak_error"]))

    def table(title, groups, cell):
        categories = sorted({c for g in groups.values() for c in g})
        print(f"{title}\n")
        print("| combination | " + " | ".join(f"category {c}" for c in categories) + " | all |")
        print("|---|" + "---|" * (len(categories) + 1))
        for combo, by_category in groups.items():
            cells = [cell(by_category[c]) if c in by_category else "–" for c in categories]
            cells.append(cell([v for vs in by_category.values() for v in vs]))
            print(f"| {combo} | " + " | ".join(cells) + " |")
        print()

    table(
        "ME % (mean ± std, scenes)",
        me,
        lambda v: f"{statistics.fmean(v):.2f} ± {statistics.pstdev(v):.2f} ({len(v)})",
    )
    if focal:
        table(
            "|f_peak - f_true| / f_true (median; share <= 0.25)",
            focal,
            lambda v: f"{statistics.median(v):.3f}; {sum(x <= 0.25 for x in v) / len(v):.0%}",
        )


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
