#!/usr/bin/env python3
"""The fast profile's validation rule (results/README.md, "Three seeds and a
margin tied to the target" and "A third validation set"): for each
candidate, its ME (thesis protocol) as the mean over seeds on each
validation set, its excess over the default's mean there, and whether it
passes (excess <= MARGIN on every set); then the candidate the rule takes.

    python3 scripts/validation_rule.py [--anchor-best] MARGIN SET ...

Each SET is `name:DEFAULT_RUN:CANDIDATE_RUN[+CANDIDATE_RUN...]`, run
directories under results/. A candidate is one combination of the swept
keys other than `seed` in a candidate run's summary.csv plus that run's
fixed `sampling`, `num_samples` and `guided_batch` (from its config.toml;
the batch only for guided sampling); the same candidates must appear on
every set. The rule takes the cheapest passing
candidate: the smallest num_samples, then guided before mixed, then the
larger guided_batch; when none passes, the one whose largest excess is
smallest. With --anchor-best the excess on each set is measured from the
best ME there (of the candidates and the default) instead of the
default's (a proposal, results/README.md, "Where the fast profile
stands"). Example (the third guided round):

    python3 scripts/validation_rule.py 0.89 \\
        hopef:validation_default_seeds_hopef:validation_fast_guided_seeds_hopef+validation_fast_mixed_seeds_hopef \\
        kitti:validation_default_seeds_kitti:validation_fast_guided_seeds_kitti+validation_fast_mixed_seeds_kitti \\
        adelaide-like:validation_default_seeds_adelaide_like:validation_fast_guided_seeds_adelaide_like+validation_fast_mixed_seeds_adelaide_like
"""
import csv
import sys
import tomllib
from collections import defaultdict
from pathlib import Path

RESULTS = Path(__file__).resolve().parent.parent / "results"
SUMMARY_FIXED = {"method", "seed", "scenes"}


def mean_me_by_candidate(run):
    """{candidate: mean ME over seeds} of one run; a candidate is a tuple of
    (key, value) pairs: the run's swept keys and its fixed sampling, M and
    guided batch."""
    config = tomllib.loads((RESULTS / run / "config.toml").read_text())
    pipeline = config.get("pipeline", {})
    fixed = {k: str(pipeline[k]) for k in ("sampling", "num_samples", "guided_batch") if k in pipeline}
    values = defaultdict(list)
    with open(RESULTS / run / "summary.csv", newline="") as f:
        for row in csv.DictReader(f):
            keys = dict(fixed)
            for k, v in row.items():
                if k in SUMMARY_FIXED or k.endswith(("_mean", "_std", "_scenes")) or k.startswith("hypotheses_"):
                    continue
                keys[k] = v
            if keys.get("sampling") != "guided":
                keys.pop("guided_batch", None)
            values[tuple(sorted(keys.items()))].append(float(row["me_mean"]))
    return {c: sum(v) / len(v) for c, v in values.items()}


def cost_order(candidate):
    keys = dict(candidate)
    return (
        int(keys.get("num_samples", 0)),
        0 if keys.get("sampling") == "guided" else 1,
        -int(keys.get("guided_batch", 0)),
    )


def label(candidate):
    keys = dict(candidate)
    text = f"{keys.get('sampling', '?')} M {keys.get('num_samples', '?')}"
    if "guided_batch" in keys:
        text += f", batches of {keys['guided_batch']}"
    return text


def main(argv):
    anchor_best = bool(argv) and argv[0] == "--anchor-best"
    if anchor_best:
        argv = argv[1:]
    if len(argv) < 2:
        sys.exit(__doc__)
    margin = float(argv[0])
    sets = []
    for spec in argv[1:]:
        name, default_run, candidate_runs = spec.split(":")
        default = mean_me_by_candidate(default_run)
        if len(default) != 1:
            sys.exit(f"{default_run}: expected one design, found {len(default)}")
        reference = next(iter(default.values()))
        candidates = {}
        for run in candidate_runs.split("+"):
            candidates.update(mean_me_by_candidate(run))
        if anchor_best:
            reference = min(reference, *candidates.values())
        sets.append((name, reference, candidates))
    common = set.intersection(*(set(c) for _, _, c in sets))
    if not common:
        sys.exit("no candidate appears on every set")
    anchor = "best" if anchor_best else "default"
    header = ["candidate"] + [f"{n} ({anchor} {ref:.2f})" for n, ref, _ in sets] + ["passes"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    by_cost = sorted(common, key=cost_order)
    worst = {}
    for c in by_cost:
        excess = [cands[c] - ref for _, ref, cands in sets]
        worst[c] = max(excess)
        cells = [f"{cands[c]:.2f} ({e:+.2f})" for (_, _, cands), e in zip(sets, excess)]
        print(f"| {label(c)} | " + " | ".join(cells) + f" | {'yes' if worst[c] <= margin else 'no'} |")
    passing = [c for c in by_cost if worst[c] <= margin]
    if passing:
        print(f"\nchosen (cheapest passing): {label(passing[0])}")
    else:
        best = min(common, key=lambda c: (worst[c], cost_order(c)))
        print(f"\nnone passes; smallest worst excess: {label(best)} ({worst[best]:+.2f})")


if __name__ == "__main__":
    main(sys.argv[1:])
