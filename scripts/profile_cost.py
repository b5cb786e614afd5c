#!/usr/bin/env python3
"""Cost of two profiles side by side, one thread (results/README.md, "Where
the fast profile stands"): for each data set, RUNS paired runs (A B A B …)
of `sctl run --threads 1`, then the medians of the per-scene median
(timings.csv total_s), of the whole process's CPU seconds (user + system,
/usr/bin/time) and of its ratio B / A pair by pair, and the largest peak
memory.

    python3 scripts/profile_cost.py SCTL [RUNS] [A=default] [B=fast]

Data: AdelaideRMF's 19 F scenes (5 seeds), the HOPE-F-faithful test scenes
0900-0909 (40 scenes) and the kitti-real test scenes of N 1000 1/0900-1/0996
step 4 (25 scenes), one seed. Run from the repository root, datasets
linked (scripts/link-datasets.sh). Nothing else should run meanwhile.
"""
import csv
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

DATA = {
    "AdelaideRMF": '[dataset]\nkind = "adelaidermf"\n',
    "HOPE-F-faithful": '[dataset]\nkind = "synthetic"\npreset = "hopef"\ngenerator_seed = 1\nindex_range = [900, 909]\n',
    "kitti-real, N 1000": '[dataset]\nkind = "synthetic"\npreset = "kitti-real"\ngenerator_seed = 1\nsplit = "test"\nscenes = ['
    + ", ".join(f'"1/{i:04d}"' for i in range(900, 1000, 4))
    + "]\n",
}
SEEDS = {"AdelaideRMF": "[12345, 23456, 34567, 45678, 56789]"}


def config(data, profile):
    seeds = SEEDS.get(data, "[12345]")
    return (
        f'name = "cost"\n{DATA[data]}\n[pipeline]\nprofile = "{profile}"\nthr_px = 2.5\n\n'
        f"[sweep]\nseed = {seeds}\n\n[plots]\nenabled = false\n"
    )


def run(sctl, cfg, out, tmp):
    timing = tmp / "time.txt"
    subprocess.run(
        ["/usr/bin/time", "-f", "%U %S %M", "-o", str(timing), sctl, "run", str(cfg), "--threads", "1", "--out", str(out)],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    user, system, rss_kb = timing.read_text().split()[-3:]
    with open(out / "timings.csv", newline="") as f:
        per_scene = statistics.median(float(r["total_s"]) for r in csv.DictReader(f))
    return per_scene, float(user) + float(system), int(rss_kb) / 1024


def main(argv):
    if not argv:
        sys.exit(__doc__)
    sctl = argv[0]
    runs = int(argv[1]) if len(argv) > 1 else 5
    a, b = (argv[2] if len(argv) > 2 else "default"), (argv[3] if len(argv) > 3 else "fast")
    print(f"| data | s/scene, {a} → {b} | whole process (CPU s), {a} → {b} | ratio {b} / {a} | peak memory, {a} → {b} |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for data in DATA:
            cfgs = {}
            for p in (a, b):
                cfgs[p] = tmp / f"{p}.toml"
                cfgs[p].write_text(config(data, p))
            results = {a: [], b: []}
            for i in range(runs):
                for p in (a, b):
                    results[p].append(run(sctl, cfgs[p], tmp / f"{p}{i}", tmp))
            med = {p: [statistics.median(r[k] for r in results[p]) for k in (0, 1)] for p in (a, b)}
            rss = {p: max(r[2] for r in results[p]) for p in (a, b)}
            ratio = statistics.median(rb[1] / ra[1] for ra, rb in zip(results[a], results[b]))
            print(
                f"| {data} | {med[a][0]:.4f} → {med[b][0]:.4f} | {med[a][1]:.2f} → {med[b][1]:.2f} s "
                f"| {ratio:.3f} | {rss[a]:.1f} → {rss[b]:.1f} MiB |"
            )


if __name__ == "__main__":
    main(sys.argv[1:])
