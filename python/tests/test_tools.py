"""sctl.t_linkage, sctl.sampson_distances and sctl.metrics against the
command line and plain numpy definitions."""

import json

import numpy as np
import pytest

import sctl
from conftest import shared_path


def block_preferences(rng, sizes, hypotheses_per_block=6):
    """Points of block b prefer the hypotheses of block b (values in (0.2, 1]),
    others barely; a few points prefer nothing."""
    n, m = sum(sizes), hypotheses_per_block * len(sizes)
    P = np.zeros((n, m))
    start = 0
    for b, size in enumerate(sizes):
        cols = slice(b * hypotheses_per_block, (b + 1) * hypotheses_per_block)
        P[start:start + size, cols] = rng.uniform(0.2, 1.0, (size, hypotheses_per_block))
        start += size
    P[rng.random(P.shape) < 0.03] = 0.05
    return P[rng.permutation(n)]


def test_t_linkage_equals_the_command_line(cli, tmp_path):
    rng = np.random.default_rng(3)
    P = np.vstack([block_preferences(rng, [30, 20, 5]), np.zeros((4, 18))])
    path = tmp_path / "P.csv"
    path.write_text("\n".join(",".join(repr(float(v)) for v in row) for row in P) + "\n")
    expected = np.array(cli("tlinkage", "--input", path, "--min-cluster-size", 8).split(), dtype=np.int64)
    labels = sctl.t_linkage(P, min_cluster_size=8)
    np.testing.assert_array_equal(labels, expected)
    # The blocks themselves: two clusters of 30 and 20, the rest outliers.
    assert sorted(np.bincount(labels[labels >= 0]).tolist()) == [20, 30]
    assert np.sum(labels == -1) == 9


def test_t_linkage_without_hypotheses_leaves_every_point_alone():
    np.testing.assert_array_equal(sctl.t_linkage(np.zeros((5, 0))), [-1] * 5)
    np.testing.assert_array_equal(sctl.t_linkage(np.zeros((3, 0)), min_cluster_size=1), [0, 1, 2])


def test_t_linkage_rejects_bad_preferences():
    with pytest.raises(ValueError, match="preferences: invalid preference 1.5 for point 1"):
        sctl.t_linkage([[0.5, 0.1], [1.5, 0.0]])
    with pytest.raises(ValueError, match="preferences: expected a 2-D"):
        sctl.t_linkage([0.5, 0.1])
    with pytest.raises(ValueError, match="min_cluster_size"):
        sctl.t_linkage([[0.5]], min_cluster_size=-1)


def test_sampson_distances_equal_the_plain_formula():
    rng = np.random.default_rng(5)
    F = rng.normal(size=(3, 3))
    x1, x2 = rng.uniform(0, 640, (50, 2)), rng.uniform(0, 640, (50, 2))
    h1, h2 = np.hstack([x1, np.ones((50, 1))]), np.hstack([x2, np.ones((50, 1))])
    Fx1, Ftx2 = h1 @ F.T, h2 @ F
    e = np.sum(h2 * Fx1, axis=1)
    expected = e**2 / (Fx1[:, 0] ** 2 + Fx1[:, 1] ** 2 + Ftx2[:, 0] ** 2 + Ftx2[:, 1] ** 2)
    np.testing.assert_allclose(sctl.sampson_distances(F, x1, x2, squared=True), expected, rtol=1e-10)
    np.testing.assert_allclose(sctl.sampson_distances(F, x1, x2), np.sqrt(expected), rtol=1e-10)
    with pytest.raises(ValueError, match="F: expected one 3 x 3 matrix"):
        sctl.sampson_distances(np.stack([F, F]), x1, x2)


def test_metrics_equal_the_command_line(cli, tmp_path):
    rng = np.random.default_rng(9)
    gt = rng.integers(0, 4, 200)
    pred = np.where(rng.random(200) < 0.8, gt - 1, rng.integers(-1, 5, 200))
    (tmp_path / "gt.txt").write_text("\n".join(map(str, gt)))
    (tmp_path / "pred.txt").write_text("\n".join(map(str, pred)))
    expected = json.loads(cli("metrics", "--gt", tmp_path / "gt.txt", "--pred", tmp_path / "pred.txt"))
    assert sctl.metrics(pred, gt) == expected
    # A perfect segmentation under other ids.
    perfect = sctl.metrics([5, 5, 9, 9, -1], [1, 1, 2, 2, 0])
    assert (perfect["me"], perfect["acc"], perfect["fnr"], perfect["pur"], perfect["ari"]) == (0, 1, 0, 1, 1)
    assert perfect["me_all"] == 0
    # An outlier absorbed into a cluster is an error over all points only.
    absorbed = sctl.metrics([2, 2, 2], [1, 1, 0])
    assert (absorbed["me"], absorbed["me_all"]) == (0, pytest.approx(1 / 3))


def test_metrics_reject_bad_labels():
    with pytest.raises(ValueError, match="differ in length"):
        sctl.metrics([1, 2], [1])
    with pytest.raises(ValueError, match="pred: labels must be integers, got dtype float64"):
        sctl.metrics([0.5, 1.0], [1, 1])
    with pytest.raises(ValueError, match="ground-truth label -3 at index 1"):
        sctl.metrics([0, 0], [1, -3])


def test_metrics_equal_scikit_learn_and_the_definitions():
    """shared/fixtures/stats/clustering.json: scikit-learn's ARI and NMI and
    docs/method.md's ME, PUR and FNR on label vectors."""
    cases = json.loads(shared_path("fixtures", "stats", "clustering.json").read_text())
    for case in cases:
        m = sctl.metrics(np.array(case["pred"]), np.array(case["gt"]))
        for ours, theirs in [("me", "me"), ("fnr", "fnr"), ("pur", "purity"), ("ari", "ari"), ("nmi", "nmi")]:
            assert m[ours] == pytest.approx(case[theirs], rel=1e-12, abs=1e-12), (ours, case)
