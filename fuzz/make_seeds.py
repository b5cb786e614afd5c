"""Seed corpora for the fuzz targets: small MAT v5 files in the AdelaideRMF
format (compressed and not, RGB and grayscale) written by scipy, small .npz
archives in the HOPE-F format written by numpy, and the shared fixtures.
Usage: python3 make_seeds.py  (from fuzz/; needs numpy and scipy)"""
import glob, os, shutil
import numpy as np
import scipy.io

here = os.path.dirname(os.path.abspath(__file__))
shared = os.path.join(here, "..", "..", "shared")
mat_dir = os.path.join(here, "corpus", "mat")
npz_dir = os.path.join(here, "corpus", "npz")
os.makedirs(mat_dir, exist_ok=True)
os.makedirs(npz_dir, exist_ok=True)
rng = np.random.default_rng(0)

n = 10
data = np.vstack([rng.uniform(0, 5, (2, n)), np.ones((1, n)), rng.uniform(0, 5, (2, n)), np.ones((1, n))])
label = rng.integers(0, 3, (1, n)).astype(np.uint8)
rgb = rng.integers(0, 255, (6, 5, 3)).astype(np.uint8)
gray = rng.integers(0, 255, (6, 5)).astype(np.uint8)
for name, img, compress in [("rgb", rgb, True), ("rgb_plain", rgb, False), ("gray", gray, True), ("gray_plain", gray, False)]:
    scipy.io.savemat(os.path.join(mat_dir, name + ".mat"),
                     {"data": data, "label": label, "img1": img, "img2": img, "score": rng.uniform(0, 1, (1, n))},
                     do_compression=compress)

pts1 = np.c_[rng.uniform(0, 100, (n, 2)), np.ones(n)]
pts2 = np.c_[rng.uniform(0, 100, (n, 2)), np.ones(n)]
np.savez(os.path.join(npz_dir, "features.npz"), F=rng.normal(size=(2, 3, 3)), labels=rng.integers(0, 3, n),
         points1=pts1, points2=pts2, ratios=rng.uniform(0, 1, n))
np.savez_compressed(os.path.join(npz_dir, "features_deflate.npz"), F=rng.normal(size=(1, 3, 3)),
                    labels=rng.integers(0, 2, n), points1=pts1, points2=np.asfortranarray(pts2))
np.savez(os.path.join(npz_dir, "camera.npz"), K=np.array([[800.0, 0, 320], [0, 800, 240], [0, 0, 1]]),
         R=np.eye(3), t=np.zeros(3))
np.save(os.path.join(npz_dir, "array.npy"), np.arange(12, dtype=np.int32).reshape(3, 4))
for f in glob.glob(os.path.join(shared, "fixtures", "hopef-layout", "good", "1", "0000", "*.npz")):
    shutil.copy(f, os.path.join(npz_dir, "fixture_" + os.path.basename(f)))
