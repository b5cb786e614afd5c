#!/usr/bin/env python3
r"""Progressive-X (Barath & Matas, ICCV 2019) two-view multi-motion fitting on
the AdelaideRMF F scenes, as a baseline for the misclassification error.

Usage: python3 scripts/progressivex_adelaidermf.py DATASET_DIR OUT_DIR [SCTL]

For every DATASET_DIR/<scene>.mat (MATLAB v5: `data` 6 x N = x1 y1 1 x2 y2 1,
`img1`, `img2`) this runs pyprogressivex.findTwoViewMotions once, times only
that call (time.perf_counter) and writes
  OUT_DIR/<scene>.labels.txt  one label per point in the .mat order
                              (0 = outlier, 1..K = the returned motions)
  OUT_DIR/times.csv           scene,n,seconds
and, when the path of the `sctl` binary is given, OUT_DIR/per_scene.csv:
scene,n,motions,me,me_all,seconds, with ME in both protocols from
`sctl metrics` against the .mat `label` (fractions, as in per_scene.csv of
`sctl run`).
The bindings return labels 0..K-1 for the K motions and K for the outlier
instance; they are mapped to 1..K and 0.

Parameters are those of the repository's own AdelaideRMF F evaluation,
dataset_comparison/adelaideF.ipynb (danini/progressive-x, commit f97364a):
threshold 0.75 px, conf 0.5, spatial_coherence_weight 0.5,
neighborhood_ball_radius 50, maximum_tanimoto_similarity 0.4, max_iters 10000,
minimum_point_number 7, maximum_model_number 4, sampler_id 2 (P-NAPSAC),
scoring_exponent 1.0. As in that notebook, the points are first ordered by
decreasing number of neighbours within the ball radius in the 4D
correspondence space (the notebook uses cv2.BFMatcher.radiusMatch, here the
same count in numpy); labels are mapped back to the .mat order.
Seed: the API exposes none (GC-RANSAC seeds std::mt19937 from
std::random_device), so runs are not repeatable. The module uses one thread
(no OpenMP code in it); OMP_NUM_THREADS=1 is set anyway.

Build/install (Debian 12, Python 3.11):
  apt-get install -y --no-install-recommends cmake libopencv-dev \
      libeigen3-dev libgflags-dev libgoogle-glog-dev
  pip install pybind11 numpy scipy
  # danini/progressive-x @ f97364a with its submodule graph-cut-ransac @ 0506f8a
  git clone https://github.com/danini/progressive-x /tmp/ppx/src
  git -C /tmp/ppx/src checkout f97364a
  git -C /tmp/ppx/src submodule update --init graph-cut-ransac
  mkdir -p /tmp/ppx/build && cd /tmp/ppx/build
  cmake ../src -DCMAKE_BUILD_TYPE=Release -DCREATE_SAMPLE_PROJECT=OFF \
      -DPYTHON_EXECUTABLE=$(which python3) \
      -Dpybind11_DIR=$(python3 -c 'import pybind11; print(pybind11.get_cmake_dir())')
  cmake --build . --target pyprogressivex -j1
  export PYTHONPATH=/tmp/ppx/build   # pyprogressivex.cpython-*.so lives here

Then, for example:
  cargo build --release -p sctl
  python3 scripts/progressivex_adelaidermf.py datasets/adelaidermf/F \
      /tmp/progressivex target/release/sctl
"""
import json
import os
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np
import scipy.io
import pyprogressivex

PARAMS = dict(threshold=0.75, conf=0.5, spatial_coherence_weight=0.5,
              neighborhood_ball_radius=50.0, maximum_tanimoto_similarity=0.4,
              max_iters=10000, minimum_point_number=7, maximum_model_number=4,
              sampler_id=2, scoring_exponent=1.0, do_logging=False)


def density_order(corrs, radius):
    """Indices by decreasing neighbour count within `radius` (4D, L2)."""
    x = corrs.astype(np.float32)
    d2 = ((x[:, None, :] - x[None, :, :]) ** 2).sum(-1)
    return np.argsort((d2 <= radius * radius).sum(1))[::-1]


def run_scene(path):
    m = scipy.io.loadmat(path)
    d = m["data"]
    corrs = np.stack([d[0], d[1], d[3], d[4]], axis=1).astype(np.float64)
    h1, w1 = m["img1"].shape[:2]
    h2, w2 = m["img2"].shape[:2]
    order = density_order(corrs, PARAMS["neighborhood_ball_radius"])
    pts = np.ascontiguousarray(corrs[order])
    t0 = time.perf_counter()
    motions, lab = pyprogressivex.findTwoViewMotions(pts, w1, h1, w2, h2,
                                                     **PARAMS)
    seconds = time.perf_counter() - t0
    k = len(motions) // 3
    lab = np.asarray(lab)
    out = np.where(lab < k, lab + 1, 0)
    labels = np.empty_like(out)
    labels[order] = out
    return labels, seconds


def errors(sctl, truth, labels):
    """(me, me_all) of `labels` (0 = outlier) against `truth`, by `sctl
    metrics` (whose predictions take -1 for an outlier)."""
    with tempfile.TemporaryDirectory() as tmp:
        gt, pred = os.path.join(tmp, "gt.txt"), os.path.join(tmp, "pred.txt")
        with open(gt, "w") as f:
            f.write("".join(f"{int(v)}\n" for v in truth))
        with open(pred, "w") as f:
            f.write("".join(f"{int(v) - 1}\n" for v in labels))
        out = subprocess.run([sctl, "metrics", "--gt", gt, "--pred", pred],
                             capture_output=True, text=True, check=True)
    m = json.loads(out.stdout)
    return m["me"], m["me_all"]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    data_dir, out_dir = sys.argv[1:3]
    sctl = sys.argv[3] if len(sys.argv) == 4 else None
    os.makedirs(out_dir, exist_ok=True)
    rows, evaluated = [], []
    for name in sorted(f for f in os.listdir(data_dir) if f.endswith(".mat")):
        scene = name[:-4]
        labels, seconds = run_scene(os.path.join(data_dir, name))
        with open(os.path.join(out_dir, scene + ".labels.txt"), "w") as f:
            f.write("".join(f"{int(v)}\n" for v in labels))
        rows.append(f"{scene},{len(labels)},{seconds:.6f}\n")
        print(rows[-1], end="", flush=True)
        if sctl:
            truth = scipy.io.loadmat(os.path.join(data_dir, name))["label"].ravel()
            me, me_all = errors(sctl, truth, labels)
            evaluated.append(f"{scene},{len(labels)},{int(labels.max())},"
                             f"{me:.6f},{me_all:.6f},{seconds:.6f}\n")
    with open(os.path.join(out_dir, "times.csv"), "w") as f:
        f.write("scene,n,seconds\n" + "".join(rows))
    if sctl:
        with open(os.path.join(out_dir, "per_scene.csv"), "w") as f:
            f.write("scene,n,motions,me,me_all,seconds\n" + "".join(evaluated))


if __name__ == "__main__":
    main()
