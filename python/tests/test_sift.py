"""sctl.sift_matches: SIFT matches of a textured image and a known shift of
it agree with the shift; paths and arrays give the same matches; without
OpenCV an ImportError names the install command. The README's example runs
on two image files."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import sctl

SHIFT = (17, 9)  # (dx, dy): image 2 is image 1 moved by -SHIFT


def textured_pair(height=240, width=320, seed=3):
    """A smooth random texture and the same scene shifted by SHIFT pixels."""
    rng = np.random.default_rng(seed)
    dx, dy = SHIFT
    big = rng.uniform(0, 255, (height + dy + 16, width + dx + 16))
    # A separable box blur, four times: blobs SIFT finds at several scales.
    kernel = np.ones(5) / 5
    for _ in range(4):
        big = np.apply_along_axis(np.convolve, 0, big, kernel, mode="same")
        big = np.apply_along_axis(np.convolve, 1, big, kernel, mode="same")
    big = (big - big.min()) / (big.max() - big.min()) * 255
    big = big.astype(np.uint8)
    return big[:height, :width], big[dy:dy + height, dx:dx + width]


def test_matches_agree_with_a_known_shift(tmp_path):
    cv2 = pytest.importorskip("cv2")
    img1, img2 = textured_pair()
    x1, x2 = sctl.sift_matches(img1, img2)
    assert x1.shape == x2.shape and x1.shape[1] == 2 and x1.dtype == np.float64
    assert len(x1) >= 50, f"{len(x1)} matches"
    error = np.linalg.norm(x1 - x2 - np.array(SHIFT), axis=1)
    assert np.mean(error < 1.0) > 0.95, np.sort(error)[-10:]
    # Image files give the same matches; RGB arrays the grey image's.
    p1, p2 = tmp_path / "a.png", tmp_path / "b.png"
    cv2.imwrite(str(p1), img1)
    cv2.imwrite(str(p2), img2)
    y1, y2 = sctl.sift_matches(p1, str(p2))
    np.testing.assert_array_equal(y1, x1)
    np.testing.assert_array_equal(y2, x2)
    z1, z2 = sctl.sift_matches(np.dstack([img1] * 3), img2 / 255.0)
    np.testing.assert_array_equal(z1, x1)
    np.testing.assert_array_equal(z2, x2)
    # A stricter ratio keeps a subset.
    s1, _ = sctl.sift_matches(img1, img2, ratio=0.5)
    assert 0 < len(s1) <= len(x1)


def test_bad_arguments_name_the_problem(tmp_path):
    pytest.importorskip("cv2")
    img1, img2 = textured_pair()
    with pytest.raises(FileNotFoundError, match="img2: no such image file"):
        sctl.sift_matches(img1, tmp_path / "missing.png")
    with pytest.raises(ValueError, match="ratio"):
        sctl.sift_matches(img1, img2, ratio=1.5)
    with pytest.raises(ValueError, match="img1: expected an image path or"):
        sctl.sift_matches(np.zeros(10), img2)


def test_without_opencv_the_import_error_names_the_command(monkeypatch):
    monkeypatch.setitem(sys.modules, "cv2", None)  # `import cv2` raises ImportError
    with pytest.raises(ImportError, match=re.escape('pip install "./python[opencv]"')):
        sctl.sift_matches(np.zeros((8, 8)), np.zeros((8, 8)))


def test_the_readme_example_runs_on_two_image_files(tmp_path):
    cv2 = pytest.importorskip("cv2")
    readme = (Path(__file__).parents[1] / "README.md").read_text()
    block = re.search(r"## Example.*?```python\n(.*?)```", readme, re.S)
    assert block, "python/README.md has no example"
    script = tmp_path / "example.py"
    script.write_text(block.group(1))
    img1, img2 = textured_pair()
    cv2.imwrite(str(tmp_path / "one.png"), img1)
    cv2.imwrite(str(tmp_path / "two.png"), img2)
    run = subprocess.run(
        [sys.executable, str(script), str(tmp_path / "one.png"), str(tmp_path / "two.png")],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stderr
    assert "matches" in run.stdout and "Segmentation" in run.stdout, run.stdout
