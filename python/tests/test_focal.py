"""sctl.focals_from_fundamental and sctl.bougnoux: the answers of `sctl focal`,
the multi-start rule against a plain re-implementation, exact recovery."""

import csv
import io
import math

import numpy as np
import pytest

import sctl
from conftest import shared_path, write_csv

ADELAIDE_SETS = [[1e-3, 1.0, 1e-3, 1.0], [5e-4, 1.0, 5e-4, 1.0], [1e-4, 1.0, 1e-4, 1.0], [5e-4, 2.0, 5e-4, 2.0]]


def rotation(a, b, c):
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
    rz = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
    return rz @ ry @ rx


def fundamental(f1, f2, angles, t):
    """K2^-T [t]x R K1^-1, unit Frobenius norm."""
    tx = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])
    F = np.diag([1 / f2, 1 / f2, 1]) @ tx @ rotation(*angles) @ np.diag([1 / f1, 1 / f1, 1])
    return F / np.linalg.norm(F)


def matrices():
    """Noiseless, perturbed and random matrices: successes and failures."""
    rng = np.random.default_rng(11)
    out = []
    for i in range(40):
        f1, f2 = rng.uniform(500, 1500, 2)
        F = fundamental(f1, f2, rng.normal(0, 0.2, 3), rng.normal(0, 1, 3) + [0, 0, 1])
        out.append(F + [0.0, 1e-5, 1e-3][i % 3] * rng.normal(size=(3, 3)))
    out += list(rng.normal(size=(10, 3, 3)))
    return np.array(out)


def cli_focal(cli, tmp_path, Fs):
    header = [f"F{i}{j}" for i in range(3) for j in range(3)]
    header += ["f_prior", "w_f1", "w_pp1", "w_f2", "w_pp2", "max_iters"]
    rows = [list(F.ravel()) + [1000.0, 5e-4, 1.0, 5e-4, 1.0, 50] for F in Fs]
    path = write_csv(tmp_path / "F.csv", header, rows)
    path.write_text(path.read_text().replace(",50.0\n", ",50\n"))
    return list(csv.DictReader(io.StringIO(cli("focal", "--input", path))))


def cell(value):
    return math.nan if value == "" else float(value)


def test_answers_equal_the_command_line(cli, tmp_path):
    Fs = matrices()
    rows = cli_focal(cli, tmp_path, Fs)
    robust = sctl.focals_from_fundamental(Fs, focal_prior=1000.0, weight_sets=[[5e-4, 1, 5e-4, 1]], max_iters=50)
    closed = sctl.bougnoux(Fs)
    assert len(rows) == len(Fs) == len(robust["status"]) == len(closed)
    statuses = set()
    for k, row in enumerate(rows):
        np.testing.assert_array_equal(closed[k], [cell(row["bougnoux_f1"]), cell(row["bougnoux_f2"])])
        status = robust["status"][k]
        statuses.add(status)
        assert (row["iter_status"] == "ok") == (status == "ok"), (k, row, status)
        if status == "ok":
            assert robust["f1"][k] == float(row["iter_f1"])
            assert robust["f2"][k] == float(row["iter_f2"])
            assert robust["iterations"][k] == int(row["iterations"])
        else:
            assert math.isnan(robust["f1"][k])
    assert "ok" in statuses and len(statuses) > 1, statuses  # both kinds of answer compared
    assert np.isnan(closed).any() and not np.isnan(closed).all()


def test_poselib_fixture_answers_equal_the_command_line(cli):
    """shared/fixtures/focal/poselib_focals.csv row by row, each with its own
    prior, weights and max_iters, through `sctl focal` and the package."""
    path = shared_path("fixtures", "focal", "poselib_focals.csv")
    rows = list(csv.DictReader(io.StringIO(cli("focal", "--input", path))))
    fixture = list(csv.DictReader(path.open()))
    assert len(rows) == len(fixture) > 100
    for row, case in zip(rows, fixture):
        F = np.array([float(case[f"F{i}{j}"]) for i in range(3) for j in range(3)]).reshape(3, 3)
        weights = [float(case[k]) for k in ("w_f1", "w_pp1", "w_f2", "w_pp2")]
        ours = sctl.focals_from_fundamental(F, focal_prior=float(case["f_prior"]), weight_sets=[weights],
                                            max_iters=int(case["max_iters"]))
        assert (ours["status"] == "ok") == (row["iter_status"] == "ok"), (case["id"], ours["status"])
        if ours["status"] == "ok":
            assert (ours["f1"], ours["f2"], ours["iterations"]) == (
                float(row["iter_f1"]), float(row["iter_f2"]), int(row["iterations"]))
        np.testing.assert_array_equal(sctl.bougnoux(F), [cell(row["bougnoux_f1"]), cell(row["bougnoux_f2"])])


def test_multi_start_keeps_the_fewest_iterations():
    """The reference's rule, re-implemented: fewest iterations, then the
    smallest |f1 - f2|, then the earlier weight set."""
    Fs = matrices()
    multi = sctl.focals_from_fundamental(Fs, focal_prior=1000.0)
    explicit = sctl.focals_from_fundamental(Fs, focal_prior=1000.0, weight_sets=ADELAIDE_SETS, max_iters=100)
    np.testing.assert_array_equal(multi["f1"], explicit["f1"])
    singles = [sctl.focals_from_fundamental(Fs, focal_prior=1000.0, weight_sets=[w]) for w in ADELAIDE_SETS]
    for k in range(len(Fs)):
        ok = [(s["iterations"][k], abs(s["f1"][k] - s["f2"][k]), i)
              for i, s in enumerate(singles) if s["status"][k] == "ok"]
        if not ok:
            assert multi["status"][k] == singles[0]["status"][k]
            continue
        best = singles[min(ok)[2]]
        assert multi["status"][k] == "ok"
        for key in ("f1", "f2", "iterations"):
            assert multi[key][k] == best[key][k], (k, key)
        np.testing.assert_array_equal(multi["pp1"][k], best["pp1"][k])


def test_one_matrix_gives_scalars_equal_to_the_stack():
    Fs = matrices()[:3]
    stack = sctl.focals_from_fundamental(Fs, focal_prior=1000.0)
    one = sctl.focals_from_fundamental(Fs[1], focal_prior=1000.0)
    assert isinstance(one["f1"], float) and isinstance(one["status"], str)
    assert one["pp1"].shape == (2,) and stack["pp1"].shape == (3, 2)
    assert one["f1"] == stack["f1"][1] and one["iterations"] == stack["iterations"][1]
    np.testing.assert_array_equal(sctl.bougnoux(Fs[1]), sctl.bougnoux(Fs)[1])


def test_bougnoux_recovers_both_focals_of_a_noiseless_matrix():
    F = fundamental(700.0, 1300.0, (0.1, -0.2, 0.05), (0.3, -0.1, 1.0))
    np.testing.assert_allclose(sctl.bougnoux(F), [700.0, 1300.0], rtol=1e-9)
    # A principal point moves the coordinates: the same camera seen from pixels.
    T = np.array([[1, 0, -320.0], [0, 1, -240.0], [0, 0, 1]])
    np.testing.assert_allclose(sctl.bougnoux(T.T @ F @ T, pp1=(320, 240), pp2=(320, 240)),
                               [700.0, 1300.0], rtol=1e-6)


def test_failures_become_the_prior_on_request():
    Fs = matrices()
    report = sctl.focals_from_fundamental(Fs, focal_prior=1000.0, weight_sets=[[5e-4, 1, 5e-4, 1]])
    prior = sctl.focals_from_fundamental(Fs, focal_prior=1000.0, weight_sets=[[5e-4, 1, 5e-4, 1]],
                                         on_failure="prior")
    failed = [k for k, s in enumerate(report["status"]) if s in ("no-real-solution", "non-finite", "no-convergence")]
    assert failed
    for k in failed:
        assert prior["status"][k] == "prior" and prior["f1"][k] == prior["f2"][k] == 1000.0
    zero = sctl.focals_from_fundamental(np.zeros((3, 3)), focal_prior=1000.0)
    assert zero["status"] == "invalid-matrix" and math.isnan(zero["f1"])


@pytest.mark.parametrize("kwargs, message", [
    ({"F": np.eye(3)[:2]}, "F: expected a 3 x 3 matrix"),
    ({"F": np.full((3, 3), np.inf)}, "F: non-finite"),
    ({"focal_prior": 0.0}, "focal_prior"),
    ({"focal_prior": "big"}, "focal_prior"),
    ({"weight_sets": "kitti"}, "weight_sets"),
    ({"weight_sets": [[1, 0, 1, 1]]}, "weight_sets"),
    ({"max_iters": 0}, "max_iters"),
    ({"on_failure": "never"}, "on_failure"),
])
def test_bad_arguments_raise_value_error_naming_them(kwargs, message):
    args = {"F": np.eye(3), "focal_prior": 1000.0, **kwargs}
    with pytest.raises(ValueError, match=message):
        sctl.focals_from_fundamental(args.pop("F"), **args)
