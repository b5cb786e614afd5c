#!/usr/bin/env python3
"""SIFT matches of the 19 AdelaideRMF fundamental-matrix scenes, labelled by
transfer from the dataset's annotated matches (datasets/real-sift/README.md).

Usage: python3 scripts/make_real_sift.py [ADELAIDERMF_F_DIR [OUT_DIR]]
       (defaults: datasets/adelaidermf/F and datasets/real-sift)

For each scene `<scene>.mat` (variables `img1`, `img2`, `data`, `label`; see
crates/datasets/src/adelaidermf.rs):

1. Detection: OpenCV SIFT on the grayscale images with OpenCV's defaults
   (nfeatures 0, 3 octave layers, contrast threshold 0.04, edge threshold 10,
   sigma 1.6) and `enable_precise_upscale=True` (without it the keypoints of
   the doubled first octave are biased by +0.25 px), one OpenCV thread.
2. Matching: brute-force L2 nearest two neighbours of each image-1
   descriptor in image 2, kept when d1 < 0.8 d2 (Lowe's ratio test); a match
   whose four coordinates repeat an earlier one (SIFT's second orientation at
   the same keypoint) is dropped.
3. Coordinates: AdelaideRMF's own convention, 1-based pixel centres (MATLAB):
   OpenCV's 0-based keypoint + 1. (On these images the precise-upscale
   keypoints lie at the annotated points minus exactly 1.00 px, median over
   the annotated points within 2 px of a keypoint.)
4. Labels: a match takes the label of the annotated match j minimising
   max(|p1 - a1_j|, |p2 - a2_j|) (the larger of the two pixel distances,
   image 1 and image 2), when that maximum is at most 10 px; else `unknown`.
   Ties go to the lowest j.

Writes `<scene>.csv` (`x1,y1,x2,y2,label`, 4 decimals) and `<scene>.toml`
(width, height, name) per scene, and prints one summary line per scene
(matches, known, unknown, per label) for the README. Needs numpy, scipy and
opencv-python-headless; deterministic: same input, same bytes.
"""
import os
import sys
from collections import Counter

import cv2
import numpy as np
import scipy.io

SCENES = [
    "biscuit", "biscuitbook", "biscuitbookbox", "boardgame", "book",
    "breadcartoychips", "breadcube", "breadcubechips", "breadtoy",
    "breadtoycar", "carchipscube", "cube", "cubebreadtoychips", "cubechips",
    "cubetoy", "dinobooks", "game", "gamebiscuit", "toycubecar",
]
RATIO = 0.8
TRANSFER_PX = 10.0
UNKNOWN = "unknown"


def gray(image):
    """RGB (H x W x 3) or grayscale (H x W) uint8 to grayscale."""
    if image.ndim == 3:
        return cv2.cvtColor(image, cv2.COLOR_RGB2GRAY)
    return image


def sift_matches(img1, img2):
    """N x 4 array (x1, y1, x2, y2), 0-based OpenCV pixel coordinates."""
    sift = cv2.SIFT_create(enable_precise_upscale=True)
    kp1, des1 = sift.detectAndCompute(gray(img1), None)
    kp2, des2 = sift.detectAndCompute(gray(img2), None)
    pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(des1, des2, k=2)
    rows, seen = [], set()
    for pair in pairs:
        if len(pair) < 2 or not pair[0].distance < RATIO * pair[1].distance:
            continue
        m = pair[0]
        row = kp1[m.queryIdx].pt + kp2[m.trainIdx].pt
        if row in seen:
            continue
        seen.add(row)
        rows.append(row)
    return np.array(rows, dtype=np.float64).reshape(-1, 4)


def transfer_labels(matches, annotated, labels):
    """Label of the annotated match nearest in both images (max of the two
    pixel distances) within TRANSFER_PX, else None; all in one convention."""
    d1 = np.linalg.norm(matches[:, None, 0:2] - annotated[None, :, 0:2], axis=2)
    d2 = np.linalg.norm(matches[:, None, 2:4] - annotated[None, :, 2:4], axis=2)
    dist = np.maximum(d1, d2)
    nearest = np.argmin(dist, axis=1)
    best = dist[np.arange(len(matches)), nearest]
    return [int(labels[j]) if d <= TRANSFER_PX else None for j, d in zip(nearest, best)]


def load(path):
    mat = scipy.io.loadmat(path)
    data = mat["data"].astype(np.float64)
    if not np.all(data[2] == 1) or not np.all(data[5] == 1):
        raise ValueError(f"{path}: `data` rows 3 and 6 are not all 1")
    annotated = np.stack([data[0], data[1], data[3], data[4]], axis=1)
    return mat["img1"], mat["img2"], annotated, mat["label"].ravel()


def write_scene(out_dir, scene, size, matches, labels):
    with open(os.path.join(out_dir, f"{scene}.csv"), "w", newline="\n") as f:
        f.write("x1,y1,x2,y2,label\n")
        for (x1, y1, x2, y2), label in zip(matches, labels):
            text = UNKNOWN if label is None else str(label)
            f.write(f"{x1:.4f},{y1:.4f},{x2:.4f},{y2:.4f},{text}\n")
    width, height = size
    with open(os.path.join(out_dir, f"{scene}.toml"), "w", newline="\n") as f:
        f.write(f'width = {width}\nheight = {height}\nname = "{scene}"\n')


def main(argv):
    src = argv[1] if len(argv) > 1 else "datasets/adelaidermf/F"
    out_dir = argv[2] if len(argv) > 2 else "datasets/real-sift"
    cv2.setNumThreads(1)
    os.makedirs(out_dir, exist_ok=True)
    print(f"opencv {cv2.__version__}, numpy {np.__version__}, scipy {scipy.__version__}")
    print("scene | matches | known | unknown | per label (0 = outlier)")
    for scene in SCENES:
        img1, img2, annotated, gt = load(os.path.join(src, f"{scene}.mat"))
        if img1.shape[:2] != img2.shape[:2]:
            raise ValueError(f"{scene}: image sizes {img1.shape} and {img2.shape} differ")
        # OpenCV's 0-based keypoints to AdelaideRMF's 1-based pixels.
        matches = sift_matches(img1, img2) + 1.0
        labels = transfer_labels(matches, annotated, gt)
        write_scene(out_dir, scene, (img1.shape[1], img1.shape[0]), matches, labels)
        counts = Counter(l for l in labels if l is not None)
        known = sum(counts.values())
        per_label = ", ".join(f"{k}: {counts[k]}" for k in sorted(counts))
        print(f"{scene} | {len(labels)} | {known} | {len(labels) - known} | {per_label}")


if __name__ == "__main__":
    main(sys.argv)
