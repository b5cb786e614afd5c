"""Nothing lost, nothing silent: Ctrl-C stops sctl.segment, the memory guard
refuses with MemoryError, None is a TypeError, absurd coordinates a ValueError
naming the row and column, and the input's warnings are SegmentationWarnings."""

import os
import signal
import sys
import threading
import time
import warnings

import numpy as np
import pytest

import sctl


def two_motions(n=200, seed=0):
    """A 640 x 480 scene of two rigid motions seen by one camera (f = 500)."""
    rng = np.random.default_rng(seed)
    X = rng.uniform([-2, -1.5, 6], [2, 1.5, 12], (n, 3))
    shift = np.where(np.arange(n)[:, None] < n // 2, [0.4, 0.0, 0.0], [-0.3, 0.2, 0.0])

    def project(P):
        return 500.0 * P[:, :2] / P[:, 2:] + [320.0, 240.0]

    return project(X), project(X + shift)


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to the own process")
def test_ctrl_c_interrupts_a_long_segmentation():
    x1, x2 = two_motions(300)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            # A million hypotheses: a minute of work without the interrupt.
            sctl.segment(x1, x2, (640, 480), num_samples=1_000_000, max_memory_mb=10**6)
    finally:
        timer.cancel()
    elapsed = time.monotonic() - started
    assert elapsed < 10.0, f"KeyboardInterrupt after {elapsed:.1f} s"
    # The package still works afterwards.
    seg = sctl.segment(x1, x2, (640, 480), num_samples=200)
    assert len(seg.labels) == 300


def test_an_explicit_bound_raises_memory_error_with_the_figures():
    x1, x2 = two_motions(2000)
    with pytest.raises(MemoryError, match="above max_memory_mb = 1: lower num_samples"):
        sctl.segment(x1, x2, (640, 480), num_samples=20_000, max_memory_mb=1)


@pytest.mark.skipif(not os.path.exists("/proc/meminfo"), reason="no MemAvailable")
def test_the_default_refuses_a_run_above_the_available_memory():
    # 100 000 matches x 10^7 hypotheses: terabytes of preferences.
    x1, x2 = two_motions(100_000)
    with pytest.raises(MemoryError) as err:
        sctl.segment(x1, x2, (640, 480), num_samples=10**7)
    text = str(err.value)
    for hint in ["MB are available (MemAvailable)", "cluster_subset", "num_samples", "max_memory_mb"]:
        assert hint in text, text


def test_none_is_a_type_error_naming_the_argument():
    x1, x2 = two_motions(40)
    with pytest.raises(TypeError, match="x1: expected an \\(N, 2\\) array of pixel coordinates, got None$"):
        sctl.segment(None, x2, (640, 480))
    rows = [list(p) for p in x2]
    rows[5][1] = None
    with pytest.raises(TypeError, match="x2: .* got None at row 5"):
        sctl.segment(x1, rows, (640, 480))


def test_absurd_coordinates_are_refused_naming_row_and_column():
    x1, x2 = two_motions(40)
    x2[7, 1] = 1e200
    with pytest.raises(ValueError, match="row 7, column y2: coordinate 1e200"):
        sctl.segment(x1, x2, (640, 480))


def test_height_width_image_size_warns_naming_both():
    x1, x2 = two_motions(200)
    with pytest.warns(sctl.SegmentationWarning, match=r"image_size = \(480, 640\).*Pass \(640, 480\)"):
        sctl.segment(x1, x2, (480, 640), num_samples=200)
    assert issubclass(sctl.SegmentationWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sctl.segment(x1, x2, (640, 480), num_samples=200)


def test_points_far_outside_the_image_warn_with_count_and_row():
    x1, x2 = two_motions(200)
    x1[[30, 31], 0] = 9000.0
    with pytest.warns(sctl.SegmentationWarning, match="2 of 200 matches .* row 30, x1 = 9000"):
        sctl.segment(x1, x2, (640, 480), num_samples=200)
