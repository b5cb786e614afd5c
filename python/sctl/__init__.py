"""Two-view motion segmentation with semi-calibrated cameras, from numpy.

Semi-calibrated T-Linkage ("Two-View Motion Segmentation with Semi-Calibrated
Cameras via Hypothesis Filtering", Algorithm 1) splits point matches between
two images of one camera into rigid motions and outliers; the uncalibrated
T-Linkage baseline is ``method="baseline"``.

- ``segment(x1, x2, image_size, ...)``: labels, f_peak, counts, timings;
- ``focals_from_fundamental(F, focal_prior=...)``, ``bougnoux(F)``: focal
  lengths from fundamental matrices;
- ``t_linkage(preferences)``, ``sampson_distances(F, x1, x2)``,
  ``metrics(pred, gt)``;
- ``load_adelaidermf(path)``, ``load_hopef(folder)``: dataset scenes as arrays;
- ``sift_matches(img1, img2, ratio=0.8)``: the SIFT matches of two images
  (OpenCV, the ``opencv`` extra: ``pip install "./python[opencv]"``).

Every computation runs in Rust without the GIL; ``segment`` stops on Ctrl-C
(KeyboardInterrupt) and reports suspicious input as ``SegmentationWarning``.
"""

from . import _sctl
from ._sctl import *  # noqa: F403 (the names below)
from ._sift import sift_matches

__all__ = sorted([name for name in vars(_sctl) if not name.startswith("_")] + ["sift_matches"])
