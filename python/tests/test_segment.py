"""sctl.segment: the labels of `sctl segment` on the same input and seed, every
[pipeline] key as a keyword, errors naming the key."""

import re
import threading

import numpy as np
import pytest

import sctl
from conftest import write_csv

SEED = 2024
# Small M keeps the comparison fast; the variants exercise keys of every type.
THESIS = {"method": "semical", "minimal_solver": "eight-point"}
VARIANTS = [
    {},
    THESIS,
    {**THESIS, "tau_range": 0.25, "weight_sets": "hopef", "max_iters": 120, "focal_failure": "prior",
     "truncate_focals": True, "local_test": "reference-code", "eight_point": "plain"},
    {"method": "semical", "linkage": "j-linkage", "thr_px": 3,
     "min_cluster_size": 10, "irls_iters": 3,
     "weight_sets": [[1e-3, 1.0, 1e-3, 1.0], [1e-4, 2.0, 1e-4, 2.0]]},
    # A profile as the base: `profile` in the [pipeline] table, and a keyword.
    {"profile": "thesis", "tau_range": 0.25},
    {"profile": "default", "sampling": "localized", "minimal_solutions": "best"},
    {"final_assignment": "none", "size_rule": {"relative-min": 0.05}, "cluster_subset": 40,
     "subset_extension": "preference"},
]


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + " }"
    return repr(v)


def cli_segment(cli, tmp_path, scene, params):
    """Labels and summary line of `sctl segment` on the scene's matches."""
    matches = write_csv(tmp_path / "matches.csv", ["x1", "y1", "x2", "y2"],
                        np.hstack([scene["x1"], scene["x2"]]))
    config = tmp_path / "config.toml"
    config.write_text("[pipeline]\n" + "".join(f"{k} = {toml_value(v)}\n" for k, v in params.items()))
    labels_file = tmp_path / "labels.txt"
    w, h = scene["image_size"]
    summary = cli("segment", "--matches", matches, "--width", w, "--height", h,
                  "--config", config, "--out", labels_file)
    return np.loadtxt(labels_file, dtype=np.int64, ndmin=1), summary


@pytest.mark.parametrize("variant", range(len(VARIANTS)))
def test_labels_equal_the_command_line(cli, synthetic, tmp_path, variant):
    scenes = synthetic if variant == 0 else synthetic[:1]
    for i, folder in enumerate(scenes):
        scene = sctl.load_hopef(folder)
        params = {"num_samples": 300, "seed": SEED + i, **VARIANTS[variant]}
        expected, summary = cli_segment(cli, tmp_path, scene, params)
        seg = sctl.segment(scene["x1"], scene["x2"], scene["image_size"], **params)
        assert seg.labels.dtype == np.int32
        np.testing.assert_array_equal(seg.labels, expected, err_msg=f"{folder}, {params}")
        counts = re.search(r"(\d+) motion\(s\) found, (\d+) outliers; hypotheses kept (\d+) of (\d+) generated "
                           r"\((\d+) refined\)", summary).groups()
        assert tuple(map(int, counts)) == (seg.motions, seg.outliers, seg.kept, seg.generated, seg.refined)
        peak = re.search(r"f_peak (\S+) px", summary)
        assert (seg.f_peak is None) == (peak is None)
        if peak:
            assert f"{seg.f_peak:.1f}" == peak.group(1)


def test_result_is_consistent(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    seg = sctl.segment(scene["x1"], scene["x2"], scene["image_size"], num_samples=300, **THESIS)
    labels = seg.labels
    assert len(seg) == len(labels) == len(scene["x1"])
    assert seg.outliers == int(np.sum(labels == -1))
    assert seg.motions == len(seg.clusters) == len(set(labels[labels >= 0].tolist()))
    for label, size, F in seg.clusters:
        assert size == int(np.sum(labels == label))
        assert F is None or F.shape == (3, 3)
    assert seg.generated == 300 >= seg.refined >= seg.local_ok >= seg.kept
    assert len(seg.hypothesis_status) == 300 == len(seg.hypothesis_focals)
    assert seg.hypothesis_status.count("kept") == seg.kept
    assert set(seg.timings) == {"sampling", "refine", "focal", "consensus", "preferences",
                                "clustering", "cluster_fit", "total"}
    assert seg.consensus["f_peak"] == seg.f_peak
    assert seg.principal_point == ((scene["image_size"][0] - 1) / 2, (scene["image_size"][1] - 1) / 2)
    assert seg.focal_prior == max(scene["image_size"])
    assert seg.params == {**sctl.default_params(), "num_samples": 300, **THESIS}
    assert seg.focal_verdict in ("plausible", "implausible", "none")
    assert f"motions={seg.motions}" in repr(seg) and f"outliers={seg.outliers}" in repr(seg)


def test_cluster_f_fits_its_points_in_centred_coordinates(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    seg = sctl.segment(scene["x1"], scene["x2"], scene["image_size"], num_samples=300)
    pp = np.array(seg.principal_point)
    for label, _, F in seg.clusters:
        inliers = seg.labels == label
        d = sctl.sampson_distances(F, scene["x1"][inliers] - pp, scene["x2"][inliers] - pp)
        assert np.median(d) < 2.5  # thr_px


def test_same_seed_same_labels_and_principal_point_is_used(synthetic):
    scene = sctl.load_hopef(synthetic[1])
    args = (scene["x1"], scene["x2"], scene["image_size"])
    a = sctl.segment(*args, num_samples=200, seed=5)
    b = sctl.segment(*args, num_samples=200, seed=5)
    np.testing.assert_array_equal(a.labels, b.labels)
    c = sctl.segment(*args, num_samples=200, seed=5, principal_point=scene["principal_point"],
                     focal_prior=900.0)
    assert c.principal_point == tuple(scene["principal_point"]) and c.focal_prior == 900.0


def test_docstring_points_to_the_generated_key_lists():
    # The keys and defaults themselves are checked against the stub in
    # test_stub.py; the docstring names where they are listed.
    assert "seed=12345" in sctl.segment.__text_signature__
    assert "sctl/__init__.pyi" in sctl.segment.__doc__
    assert "Parameter keys" in sctl.segment.__doc__


@pytest.mark.parametrize("kwargs, key", [
    ({"num_sample": 300}, "num_sample"),
    ({"num_samples": 1.5}, "num_samples"),
    ({"num_samples": 0}, "num_samples"),
    ({"method": "calibrated"}, "method"),
    ({"thr_px": float("nan")}, "thr_px"),
    ({"tau_diff": -1}, "tau_diff"),
    ({"refine": "yes"}, "refine"),
    ({"weight_sets": [[1, 2, 3]]}, "weight_sets"),
    ({"weight_sets": "kitti"}, "weight_sets"),
    ({"seed": -1}, "seed"),
    ({"recover_outliers": "refit"}, "recover_outliers"),
    ({"final_assignment": "merge-refit"}, "final_assignment"),
    ({"sampling": "mixed"}, "sampling"),
    ({"focal_solver": "external", "method": "semical"}, "external"),
])
def test_bad_parameters_raise_value_error_naming_the_key(synthetic, kwargs, key):
    scene = sctl.load_hopef(synthetic[0])
    with pytest.raises(ValueError, match=f"`?{key}"):
        sctl.segment(scene["x1"], scene["x2"], scene["image_size"], **kwargs)


def test_bad_input_raises_value_error():
    rng = np.random.default_rng(0)
    x = rng.uniform(0, 100, (20, 2))
    cases = [
        ((x[:, :1], x, (100, 100)), "x1: expected an \\(N, 2\\) array"),
        ((x, x[:10], (100, 100)), "x1 has 20 points but x2 has 10"),
        ((x[:5], x[:5], (100, 100)), "5 correspondences"),
        ((x, np.where(np.arange(40).reshape(20, 2) == 7, np.nan, x), (100, 100)), "x2: non-finite value NaN at row 3"),
        ((x, x, (100, 0)), "image_size"),
        ((x, [["a", "b"]] * 20, (100, 100)), "x2: not an array of numbers"),
    ]
    for args, message in cases:
        with pytest.raises(ValueError, match=message):
            sctl.segment(*args)
    with pytest.raises(ValueError, match="principal_point"):
        sctl.segment(x, x, (100, 100), principal_point=(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="focal_prior"):
        sctl.segment(x, x, (100, 100), focal_prior=-5.0)


def test_the_gil_is_released_while_segmenting(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    started, done = threading.Event(), threading.Event()

    def work():
        started.set()
        sctl.segment(scene["x1"], scene["x2"], scene["image_size"], num_samples=3000)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    started.wait()
    spins = 0
    while not done.is_set():
        spins += 1  # runs only while the segmentation does not hold the GIL
    thread.join()
    # Holding the GIL for the whole call would leave a few hundred spins at most.
    assert spins > 10_000


def test_default_is_five_point_without_a_focal_stage(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    seg = sctl.segment(scene["x1"], scene["x2"], scene["image_size"], num_samples=300)
    defaults = sctl.default_params()
    assert (defaults["method"], defaults["minimal_solver"]) == ("baseline", "five-point")
    assert seg.f_peak is None and seg.consensus is None and seg.focal_verdict is None
    assert seg.kept == seg.refined


def test_profile_gives_every_key_not_passed(synthetic):
    scene = sctl.load_hopef(synthetic[0])
    args = (scene["x1"], scene["x2"], scene["image_size"])
    assert sctl.default_params() == sctl.default_params("default") == sctl.default_params(profile=None)
    thesis = sctl.default_params(profile="thesis")
    assert (thesis["method"], thesis["minimal_solver"]) == ("semical", "eight-point")
    assert thesis != sctl.default_params()
    for profile in ("default", "thesis"):
        params = sctl.default_params(profile)
        assert set(params) == set(sctl.default_params())
        # Keywords override the profile's values; the others are the profile's.
        seg = sctl.segment(*args, profile=profile, num_samples=200, seed=3)
        assert seg.params == {**params, "num_samples": 200, "seed": 3}
        explicit = sctl.segment(*args, **{**params, "num_samples": 200, "seed": 3})
        np.testing.assert_array_equal(seg.labels, explicit.labels, err_msg=profile)
        assert (seg.generated, seg.refined, seg.kept) == (explicit.generated, explicit.refined, explicit.kept)
    assert sctl.segment(*args, profile="thesis", num_samples=100).params == {**thesis, "num_samples": 100}


@pytest.mark.parametrize("profile", ["quick", "Fast", 3, ""])
def test_unknown_profile_raises_value_error_listing_the_profiles(synthetic, profile):
    scene = sctl.load_hopef(synthetic[0])
    message = r"`profile`.*default, thesis"
    with pytest.raises(ValueError, match=message):
        sctl.segment(scene["x1"], scene["x2"], scene["image_size"], profile=profile)
    with pytest.raises(ValueError, match=message):
        sctl.default_params(profile)


@pytest.mark.parametrize("profile", ["fast", "large"])
def test_a_retired_profile_says_what_became_of_it(profile):
    with pytest.raises(ValueError, match=rf"profile `{profile}` was folded into the default"):
        sctl.default_params(profile)
