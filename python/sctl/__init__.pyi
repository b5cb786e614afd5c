"""Type stubs of the sctl package (the compiled module sctl._sctl)."""

import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, TypedDict, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "Segmentation",
    "SegmentationWarning",
    "bougnoux",
    "default_params",
    "focals_from_fundamental",
    "load_adelaidermf",
    "load_hopef",
    "metrics",
    "sampson_distances",
    "segment",
    "sift_matches",
    "t_linkage",
]

_Points = npt.ArrayLike  # (N, 2) pixel coordinates
_Matrix = npt.ArrayLike  # (3, 3) or (K, 3, 3)
_WeightSets = Union[Literal["adelaidermf", "hopef"], Sequence[Sequence[float]]]
_Profile = Literal["default", "thesis"]

@final
class Segmentation:
    """The result of ``segment``: labels and what is needed to trust them."""

    @property
    def labels(self) -> npt.NDArray[np.int32]:
        """One label per match: 0, 1, ... for the motions, -1 for outliers."""
    @property
    def f_peak(self) -> Optional[float]:
        """The consensus focal length (px, Eq. 37); None for the baseline."""
    @property
    def motions(self) -> int: ...
    @property
    def outliers(self) -> int: ...
    @property
    def generated(self) -> int: ...
    @property
    def refined(self) -> int: ...
    @property
    def local_ok(self) -> int: ...
    @property
    def kept(self) -> int: ...
    @property
    def focal_failures(self) -> int: ...
    @property
    def focal_priors(self) -> int: ...
    @property
    def timings(self) -> Dict[str, float]:
        """Seconds per stage: sampling, refine, focal, consensus, preferences,
        clustering, cluster_fit, total."""
    @property
    def clusters(self) -> List[Tuple[int, int, Optional[npt.NDArray[np.float64]]]]:
        """(label, size, F) per motion; F in principal-point-centred pixels."""
    @property
    def degenerate(self) -> Optional[str]: ...
    @property
    def consensus_fallback(self) -> bool: ...
    @property
    def focal_verdict(self) -> Optional[Literal["plausible", "implausible", "none"]]:
        """f_peak against 0.3-3 x the focal prior; None without a focal stage."""
    @property
    def consensus(self) -> Optional[Dict[str, Any]]: ...
    @property
    def hypothesis_status(self) -> List[str]: ...
    @property
    def hypothesis_focals(self) -> npt.NDArray[np.float64]: ...
    @property
    def principal_point(self) -> Tuple[float, float]: ...
    @property
    def focal_prior(self) -> float: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    def __len__(self) -> int: ...

def segment(
    x1: _Points,
    x2: _Points,
    image_size: Tuple[int, int],
    *,
    principal_point: Optional[Tuple[float, float]] = None,
    focal_prior: Optional[float] = None,
    profile: _Profile = "default",
    # keys: generated from segmentation::KEYS, see crates/cli/src/config/keys.rs
    method: Literal["baseline", "semical"] = "baseline",
    num_samples: int = 1000,
    mss_size: int = 8,
    thr_px: float = 2.5,
    tau_diff: float = 0.05,
    tau_range: float = 0.2,
    irls_iters: int = 1,
    irls_fit: Literal["normalized", "plain"] = "normalized",
    irls_unit_weight_fallback: bool = True,
    irls_sigma_offset_px: float = 0.0,
    irls_polish: bool = False,
    refine: bool = True,
    eight_point: Literal["normalized", "plain"] = "normalized",
    minimal_solver: Literal["five-point", "eight-point"] = "five-point",
    minimal_solutions: Literal["best", "best-unpolished"] = "best-unpolished",
    sampling: Literal["uniform", "localized", "guided"] = "guided",
    guided_batch: int = 50,
    focal_solver: Literal["kocur", "bougnoux", "external"] = "kocur",
    weight_sets: Union[Literal["adelaidermf", "hopef"], Sequence[Sequence[float]]] = "adelaidermf",
    max_iters: int = 100,
    focal_failure: Literal["report", "prior"] = "report",
    truncate_focals: bool = False,
    local_test: Literal["algorithm1", "reference-code"] = "algorithm1",
    linkage: Literal["t-linkage", "j-linkage"] = "t-linkage",
    min_cluster_size: int = 8,
    size_rule: Union[Literal["min-size"], Dict[str, float]] = "min-size",
    final_assignment: Literal["nfa", "merge", "none"] = "nfa",
    cluster_subset: int = 1000,
    subset_extension: Literal["preference-explained", "preference"] = "preference-explained",
    max_memory_mb: int = 0,
    seed: int = 12345,
    # end of the keys
) -> Segmentation:
    """Segments matches into rigid motions (T-Linkage of five-point
    hypotheses at the focal prior; the thesis: method="semical",
    minimal_solver="eight-point", or profile="thesis"). The keywords given
    override the profile's values (the defaults shown are those of
    profile="default")."""

def default_params(profile: _Profile = "default") -> Dict[str, Any]:
    """The keyword parameters of ``segment`` on ``profile``."""

class _FocalAnswer(TypedDict):
    f1: Any
    f2: Any
    pp1: npt.NDArray[np.float64]
    pp2: npt.NDArray[np.float64]
    iterations: Any
    status: Any

def focals_from_fundamental(
    F: _Matrix,
    *,
    focal_prior: float,
    weight_sets: _WeightSets = "adelaidermf",
    max_iters: int = 100,
    on_failure: Literal["report", "prior"] = "report",
) -> _FocalAnswer:
    """Robust focal lengths (Kocur-Kyselica-Kukelova, multi-start) of F or a stack."""

def bougnoux(
    F: _Matrix,
    pp1: Tuple[float, float] = (0.0, 0.0),
    pp2: Tuple[float, float] = (0.0, 0.0),
) -> npt.NDArray[np.float64]:
    """Bougnoux's focal lengths (f1, f2) of F or a stack; NaN where none."""

def t_linkage(preferences: npt.ArrayLike, min_cluster_size: int = 8) -> npt.NDArray[np.int32]:
    """T-Linkage of an (N, M) preference matrix; -1 for outliers."""

def sampson_distances(
    F: npt.ArrayLike, x1: _Points, x2: _Points, *, squared: bool = False
) -> npt.NDArray[np.float64]:
    """Sampson distance (Eq. 23) of each match to F, px (px**2 if squared)."""

class _Metrics(TypedDict):
    me: float
    me_all: float
    acc: float
    fnr: float
    pur: float
    ari: float
    nmi: float

def metrics(pred: npt.ArrayLike, gt: npt.ArrayLike) -> _Metrics:
    """ME, ME over all points, ACC, FNR, PUR, ARI, NMI of predicted labels against the ground truth."""

class _Scene(TypedDict):
    name: str
    x1: npt.NDArray[np.float64]
    x2: npt.NDArray[np.float64]
    labels: Optional[npt.NDArray[np.int32]]
    image_size: Tuple[int, int]
    principal_point: npt.NDArray[np.float64]
    true_focal: Optional[float]
    F: npt.NDArray[np.float64]
    images: Optional[Tuple[npt.NDArray[np.uint8], npt.NDArray[np.uint8]]]

def load_adelaidermf(path: Union[str, os.PathLike[str]], *, images: bool = False) -> _Scene:
    """One AdelaideRMF .mat scene as arrays."""

def load_hopef(folder: Union[str, os.PathLike[str]], *, images: bool = False) -> _Scene:
    """One HOPE-F scene folder as arrays."""

class SegmentationWarning(UserWarning):
    """Something suspicious in the input of ``segment``, which was still
    segmented: points far outside the image, an image size given as
    (height, width)."""

_Image = Union[str, os.PathLike, npt.ArrayLike]

def sift_matches(
    img1: _Image, img2: _Image, ratio: float = 0.8
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """SIFT matches (OpenCV) of two images with Lowe's ratio test: (x1, x2),
    each (N, 2) pixels. Needs the ``opencv`` extra."""
