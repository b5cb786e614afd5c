"""sctl.load_hopef and sctl.load_adelaidermf: shapes and values against numpy's
own reading of the files, errors naming the file and the field."""

import numpy as np
import pytest

import sctl
from conftest import shared_path

FIXTURES = ("fixtures", "hopef-layout")


def good_scenes():
    return sorted(p.parent for p in shared_path(*FIXTURES, "good").glob("*/*/features_and_ground_truth.npz"))


def test_hopef_layout_fixture_loads_with_the_right_shapes():
    scenes = good_scenes()
    assert len(scenes) == 12
    for folder in scenes:
        scene = sctl.load_hopef(folder)
        features = np.load(folder / "features_and_ground_truth.npz")
        camera = np.load(folder / "camera_parameters.npz")
        n, k = len(features["labels"]), int(folder.parent.name)
        assert scene["name"] == f"{folder.parent.name}/{folder.name}"
        assert scene["x1"].shape == scene["x2"].shape == (n, 2) and scene["x1"].dtype == np.float64
        assert scene["labels"].shape == (n,) and scene["labels"].dtype == np.int32
        assert scene["F"].shape == (k, 3, 3)
        p1, p2 = features["points1"], features["points2"]
        np.testing.assert_array_equal(scene["x1"], p1[:, :2] / p1[:, 2:])
        np.testing.assert_array_equal(scene["x2"], p2[:, :2] / p2[:, 2:])
        np.testing.assert_array_equal(scene["labels"], features["labels"])
        np.testing.assert_array_equal(scene["F"], features["F"])
        K = camera["K"]
        np.testing.assert_array_equal(scene["principal_point"], [K[0, 2], K[1, 2]])
        assert scene["true_focal"] == K[0, 0]
        assert scene["image_size"] == (1024, 1024)  # HOPE-F's render size: no renders, no image_size
        assert scene["images"] is None
        assert set(np.unique(scene["labels"])) <= set(range(k + 1))


@pytest.mark.parametrize("case, field", [
    ("length_mismatch", "labels"),
    ("missing_labels", "labels"),
    ("nan_points", "points"),
    ("truncated", "not a readable .npz archive"),
])
def test_broken_hopef_scenes_raise_value_error_naming_file_and_field(case, field):
    folder = shared_path(*FIXTURES, "bad", case, "1", "0000")
    with pytest.raises(ValueError) as error:
        sctl.load_hopef(folder)
    message = str(error.value)
    assert str(folder / "features_and_ground_truth.npz") in message and field in message, message


def test_missing_hopef_folder_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match=str(tmp_path / "nowhere")):
        sctl.load_hopef(tmp_path / "nowhere")


def test_synthetic_scenes_load_as_written(synthetic):
    for folder in synthetic:
        scene = sctl.load_hopef(str(folder))
        k = int(folder.parent.name)
        n = len(scene["labels"])
        assert scene["x1"].shape == (n, 2) and scene["F"].shape == (k, 3, 3)
        assert len(set(scene["labels"].tolist()) - {0}) == k
        # Each motion's points satisfy its ground-truth F (noisy matches: px scale).
        for j in range(1, k + 1):
            mask = scene["labels"] == j
            d = sctl.sampson_distances(scene["F"][j - 1], scene["x1"][mask], scene["x2"][mask])
            assert np.median(d) < 2.0


def test_adelaidermf_scene_loads_with_its_images():
    path = shared_path("datasets", "adelaidermf", "F", "biscuitbook.mat")
    scene = sctl.load_adelaidermf(path, images=True)
    n = len(scene["labels"])
    assert scene["name"] == "biscuitbook"
    assert scene["x1"].shape == scene["x2"].shape == (n, 2) and n > 8
    assert set(np.unique(scene["labels"]).tolist()) == {0, 1, 2}  # outliers and two motions
    w, h = scene["image_size"]
    img1, img2 = scene["images"]
    assert img1.shape == img2.shape == (h, w, 3) and img1.dtype == np.uint8
    np.testing.assert_array_equal(scene["principal_point"], [(w - 1) / 2, (h - 1) / 2])
    assert scene["true_focal"] is None and scene["F"].shape == (0, 3, 3)
    inside = (scene["x1"] >= 0) & (scene["x1"] <= [w, h])
    assert inside.all()
    assert sctl.load_adelaidermf(path)["images"] is None


def test_bad_adelaidermf_files_raise_naming_the_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.mat"):
        sctl.load_adelaidermf(tmp_path / "missing.mat")
    garbage = tmp_path / "garbage.mat"
    garbage.write_bytes(b"MATLAB 5.0 MAT-file, but not really" + bytes(200))
    with pytest.raises(ValueError, match="garbage.mat"):
        sctl.load_adelaidermf(garbage)
