"""``sctl.sift_matches``: the point matches of two images, by OpenCV's SIFT
(Lowe, "Distinctive Image Features from Scale-Invariant Keypoints", IJCV
2004) and Lowe's ratio test, as the (x1, x2) arrays ``sctl.segment`` takes.

OpenCV is an optional dependency: ``pip install "./python[opencv]"``
(opencv-python-headless).
"""

import os

import numpy as np

OPENCV_MISSING = (
    "sctl.sift_matches needs OpenCV: install the package with its opencv extra, "
    '`pip install "./python[opencv]"` from the repository root '
    "(or `pip install opencv-python-headless`)"
)


def _cv2():
    try:
        import cv2
    except ImportError as err:
        raise ImportError(OPENCV_MISSING) from err
    if not hasattr(cv2, "SIFT_create"):
        raise ImportError(f"OpenCV {cv2.__version__} has no SIFT (4.4 or newer needed); " + OPENCV_MISSING)
    return cv2


def _gray(cv2, image, name):
    """An 8-bit grey image from a path or an (H, W[, 3 or 4]) array (RGB(A))."""
    if isinstance(image, (str, bytes, os.PathLike)):
        path = os.fsdecode(image)
        gray = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
        if gray is None:
            if not os.path.exists(path):
                raise FileNotFoundError(f"{name}: no such image file: {path}")
            raise ValueError(f"{name}: OpenCV cannot read {path} as an image")
        return gray
    array = np.asarray(image)
    if array.ndim == 3 and array.shape[2] in (3, 4):
        code = cv2.COLOR_RGB2GRAY if array.shape[2] == 3 else cv2.COLOR_RGBA2GRAY
        array = cv2.cvtColor(np.ascontiguousarray(array), code)
    if array.ndim != 2 or min(array.shape) == 0:
        raise ValueError(f"{name}: expected an image path or an (H, W), (H, W, 3) or (H, W, 4) array, got shape {array.shape}")
    if array.dtype == np.uint8:
        return np.ascontiguousarray(array)
    if array.dtype == bool or not np.issubdtype(array.dtype, np.number):
        raise ValueError(f"{name}: expected a numeric image, got dtype {array.dtype}")
    values = array.astype(np.float64)
    if not np.isfinite(values).all():
        raise ValueError(f"{name}: the image holds non-finite values")
    # Floats in [0, 1] are scaled to [0, 255]; others are clipped.
    if np.issubdtype(array.dtype, np.floating) and values.max() <= 1.0:
        values = values * 255.0
    return np.clip(np.rint(values), 0, 255).astype(np.uint8)


def sift_matches(img1, img2, ratio=0.8):
    """Point matches between two images: SIFT keypoints and descriptors
    (OpenCV), each descriptor of image 1 matched to its nearest neighbour in
    image 2 when that is closer than ``ratio`` times the second nearest
    (Lowe's ratio test).

    Parameters
    ----------
    img1, img2 : str, os.PathLike or array_like
        Image files, or arrays (H, W) grey or (H, W, 3) / (H, W, 4) RGB(A),
        uint8, or floats in [0, 1] (scaled) or [0, 255].
    ratio : float, default 0.8
        Lowe's ratio, in (0, 1].

    Returns
    -------
    x1, x2 : ndarray, shape (N, 2), float64
        The matched keypoints in image 1 and image 2, pixels (x right, y
        down), ready for ``sctl.segment(x1, x2, (W, H))``.

    Raises
    ------
    ImportError
        Without OpenCV, naming the command that installs it.
    FileNotFoundError, ValueError
        For a missing or unreadable file, an array that is not an image, or
        ``ratio`` outside (0, 1].
    """
    if not (isinstance(ratio, (int, float)) and 0.0 < ratio <= 1.0):
        raise ValueError(f"ratio: expected a number in (0, 1], got {ratio!r}")
    cv2 = _cv2()
    a, b = _gray(cv2, img1, "img1"), _gray(cv2, img2, "img2")
    sift = cv2.SIFT_create()
    k1, d1 = sift.detectAndCompute(a, None)
    k2, d2 = sift.detectAndCompute(b, None)
    empty = np.empty((0, 2))
    if d1 is None or d2 is None or len(k2) < 2:
        return empty, empty.copy()
    pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(d1, d2, k=2)
    good = [p[0] for p in pairs if len(p) == 2 and p[0].distance < ratio * p[1].distance]
    x1 = np.array([k1[m.queryIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
    x2 = np.array([k2[m.trainIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
    return x1, x2
