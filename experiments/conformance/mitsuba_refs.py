"""Mitsuba 3's bsdf_spheres and participating_media test scenes and their reference images
(../shared/conformance/mitsuba3).

The references were written by Mitsuba's test_renders.py (`render_ref_images`, default --spp 32000;
mitsuba-renderer/mitsuba3 src/render/tests/test_renders.py): the `moment` integrator's mean and
second moment m2 in CIE XYZ, stored as RGB through Mitsuba's linear XYZ→sRGB matrix, the variance
image being `xyz_to_rgb(m2 − mean²)`, i.e. the same linear map applied to the per-sample variance.
Applying the inverse map (sRGB→XYZ) therefore recovers the XYZ mean and per-sample XYZ variance
exactly. The files are PIZ-compressed, which the pure-Python EXR reader does not read, so they are
converted once with OpenImageIO's oiiotool (Debian package openimageio-tools).
"""
from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from iris_experiments.errors import ExperimentError  # noqa: E402
from iris_experiments.exr import read_exr  # noqa: E402
from iris_experiments.tools import REPO  # noqa: E402

SUITE_DIR = REPO.parent / "shared" / "conformance" / "mitsuba3"
SCENE_DIR = SUITE_DIR / "tests" / "scenes" / "bsdf_spheres"
MEDIA_DIR = SUITE_DIR / "tests" / "scenes" / "participating_media"
# The suites the conformance run covers by default: Mitsuba 3's bsdf_spheres and
# participating_media test scenes (test_renders.py renders both with the same budget and rule).
SUITES = (SCENE_DIR, MEDIA_DIR)
REFERENCE_SPP = 32000   # test_renders.py: render_ref_images(--spp, default 32000)
TEST_SAMPLE_BUDGET = 2_000_000   # test_renders.py: spp = 2e6 // pixel count (868 at 48x48)

# Linear sRGB (Rec. 709 primaries, D65) → CIE XYZ, the matrix of Mitsuba's Bitmap conversions
# (the standard sRGB matrix, IEC 61966-2-1).
SRGB_TO_XYZ = np.array([[0.412453, 0.357580, 0.180423],
                        [0.212671, 0.715160, 0.072169],
                        [0.019334, 0.119193, 0.950227]])


def scene_names(scene_dir: Path | None = SCENE_DIR) -> list[str]:
    """Test names (`test_envmap` for test_envmap_path.xml) of one suite folder, or of every suite
    (scene_dir None), sorted within each suite."""
    dirs = SUITES if scene_dir is None else (scene_dir,)
    return [n for d in dirs for n in sorted(p.stem.rsplit("_", 1)[0] for p in d.glob("test_*_*.xml"))]


def scene_dir_of(name: str) -> Path:
    """The suite folder holding test `name`."""
    for d in SUITES:
        if any(p.stem.rsplit("_", 1)[0] == name for p in d.glob(f"{name}_*.xml")):
            return d
    raise ExperimentError(f"{SUITE_DIR}: no suite holds a scene file {name}_<integrator>.xml")


def scene_path(name: str, scene_dir: Path = SCENE_DIR) -> Path:
    matches = sorted(p for p in scene_dir.glob(f"{name}_*.xml") if p.stem.rsplit("_", 1)[0] == name)
    if not matches:
        raise ExperimentError(f"{scene_dir}: no scene file {name}_<integrator>.xml")
    return matches[0]


def _readable_copy(src: Path, cache: Path) -> Path:
    """An uncompressed-or-ZIP float copy of src in cache (converted by oiiotool once)."""
    dst = cache / src.name
    if dst.exists() and dst.stat().st_mtime >= src.stat().st_mtime:
        return dst
    oiiotool = shutil.which("oiiotool")
    if not oiiotool:
        raise ExperimentError("oiiotool not found (install openimageio-tools): needed to read the PIZ-compressed references")
    cache.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run([oiiotool, str(src), "-d", "float", "--compression", "zip", "-o", str(dst)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise ExperimentError(f"{src}: oiiotool could not convert it: {proc.stderr.strip()}")
    return dst


def rgb_channels(path: Path) -> np.ndarray:
    """The R, G, B channels of an EXR file as float64, in that order."""
    pixels, names, _ = read_exr(str(path))
    index = {n: i for i, n in enumerate(names)}
    if not all(c in index for c in "RGB"):
        raise ExperimentError(f"{path}: expected channels R, G, B, found {names}")
    return pixels[:, :, [index["R"], index["G"], index["B"]]].astype(np.float64)


def to_xyz(rgb: np.ndarray) -> np.ndarray:
    return rgb @ SRGB_TO_XYZ.T


# iris's mode → the Mitsuba variant of its reference (the polarized references are the S0 of
# `scalar_spectral_polarized`, stored like the others).
REFERENCE_VARIANT = {"spectral": "spectral", "rgb": "rgb", "polarized": "spectral_polarized"}


def has_reference(name: str, mode: str, scene_dir: Path = SCENE_DIR) -> bool:
    """Whether Mitsuba's reference of test `name` exists in `mode` (the participating_media suite
    has no polarized references)."""
    base = scene_dir / "refs" / f"{name}_ref_{REFERENCE_VARIANT[mode]}"
    return Path(f"{base}.exr").exists() and Path(f"{base}_var.exr").exists()


def reference(name: str, mode: str, cache: Path, scene_dir: Path = SCENE_DIR):
    """(XYZ mean, XYZ per-sample variance) of the reference of test `name` in mode
    spectral|rgb|polarized."""
    base = scene_dir / "refs" / f"{name}_ref_{REFERENCE_VARIANT[mode]}"
    mean_file, var_file = Path(f"{base}.exr"), Path(f"{base}_var.exr")
    for f in (mean_file, var_file):
        if not f.exists():
            raise ExperimentError(f"{f}: reference missing")
    mean = to_xyz(rgb_channels(_readable_copy(mean_file, cache)))
    var = np.maximum(to_xyz(rgb_channels(_readable_copy(var_file, cache))), 0.0)
    return mean, var
