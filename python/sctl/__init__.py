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
- ``load_adelaidermf(path)``, ``load_hopef(folder)``: dataset scenes as arrays.

Every computation runs in Rust without the GIL.
"""

from . import _sctl
from ._sctl import *  # noqa: F403 (the names below)

__all__ = sorted(name for name in vars(_sctl) if not name.startswith("_"))
