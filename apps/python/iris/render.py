"""Scenes and rendering: the scene loader and the renderer of the `render` executable, in-process.

The render runs on a C++ thread with the GIL released; the calling thread wakes every 50 ms to
deliver signals (Ctrl-C stops the render: `RenderInterrupted`, a KeyboardInterrupt, carries the
partial result) and to call `progress`. Pixels equal the executable's for the same scene, seed,
spp and mode (the same code converts and describes them, render/render_output.h).
"""
from __future__ import annotations

import math
import os
import sys
from dataclasses import dataclass, field

import numpy as np

from . import _iris
from ._arrays import rgb_wavelengths as _rgb_wavelengths


def _defines(defines: dict) -> dict:
    """-D name=value overrides as strings (booleans as the XML's true/false)."""
    out = {}
    for k, v in defines.items():
        out[str(k)] = ("true" if v else "false") if isinstance(v, bool) else str(v)
    return out


def load_file(path, **defines) -> _iris.Scene:
    """Load a Mitsuba XML scene file or a glTF 2.0 file (.gltf, .glb; docs/gltf.md); keyword
    arguments override an XML file's <default> values (like `render -D name=value`) or set a glTF
    file's res, width, height, spp, camera, envmap and rgb_mode. Raises iris.Error
    "file:line: message" (XML) or "file: /json/path: message" (glTF) on bad input."""
    return _iris.load_file(os.fspath(path), _defines(defines))


def load_string(xml: str, base_dir=None, **defines) -> _iris.Scene:
    """Load scene XML held in a string; relative paths resolve against `base_dir` (default: the
    current directory); messages name "<string>:line"."""
    return _iris.load_string(xml, os.fspath(base_dir) if base_dir is not None else os.getcwd(), _defines(defines))


@dataclass
class RenderResult:
    """What a render returns: the image in the chosen colour space, the variance of each pixel's
    mean (in the film's space: CIE XYZ in spectral mode, linear Rec.709 in RGB mode), the samples
    per pixel, the EXR metadata and the render statistics."""
    image: np.ndarray          # (H, W, 3) float32
    variance: np.ndarray       # (H, W, 3) float32
    sample_count: np.ndarray   # (H, W) uint32
    metadata: dict             # the "iris.*" header of the EXR the CLI writes
    stats: dict                # seconds, rays, paths, invalid_samples, spp_min, spp_max, ...
    spectral: np.ndarray | None = None  # (H, W, bins) float32 with spectral_bins > 0, else None
    spectral_wavelengths: np.ndarray | None = None  # bin centres (nm)
    interrupted: bool = False  # stopped before reaching spp (Ctrl-C)
    stokes: np.ndarray | None = None  # (4, H, W, 3) float32: S0..S3 (mode "polarized", stokes integrator)

    @property
    def spp(self) -> int:
        return int(self.stats["spp_min"])

    def write(self, path) -> None:
        """Write the image and its metadata as the `render` executable would (EXR only, no PNG)."""
        from .images import write
        write(path, self.image, self.metadata)


class RenderInterrupted(KeyboardInterrupt):
    """Ctrl-C during iris.render: the render stopped between tiles; `result` holds what was done."""

    def __init__(self, result: RenderResult):
        super().__init__(f"render interrupted after {result.stats['spp_min']} spp")
        self.result = result


class _TextProgress:
    """A tqdm-style bar on stderr (tqdm itself when it is installed)."""

    def __init__(self):
        try:
            from tqdm import tqdm  # optional
            self._bar = tqdm(total=1000, unit="‰", leave=False)
        except ImportError:
            self._bar = None
        self._last = -1

    def __call__(self, fraction: float) -> None:
        permille = int(1000 * fraction)
        if self._bar is not None:
            self._bar.update(max(0, permille - self._bar.n))
            if fraction >= 1:
                self._bar.close()
        elif permille // 10 != self._last:
            self._last = permille // 10
            bar = "#" * (permille // 25)
            sys.stderr.write(f"\r[{bar:<40}] {permille / 10:5.1f}%" + ("\n" if fraction >= 1 else ""))
            sys.stderr.flush()


def _count(name: str, value, lo: int, hi: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an integer, got {value!r}")
    if value < lo or (hi is not None and value > hi):
        raise _iris.Error(f"{name}: {value} is outside [{lo}, {hi if hi is not None else '∞'}]")
    return int(value)


def render(scene: _iris.Scene, spp: int | None = None, mode: str = "spectral", spectral_samples: int = 4,
           seed: int = 0, threads: int = 0, time_limit: float | None = None, sampler: str | None = None,
           colorspace: str = "lin_rec709", rgb_wavelengths=None, uniform_wavelengths: bool = False,
           progress=None, ocio_config: str | None = None, spectral_bins: int = 0,
           wavelength_sampling: str = "hero") -> RenderResult:
    """Render `scene` (from load_file / load_string). The options are the `render` executable's:
    spp (None: the scene's sampler sample_count; 0 with time_limit: render until the time is up),
    mode "spectral" (spectral_samples wavelengths per path), "rgb" or "polarized" (spectral with a
    Stokes vector per wavelength, docs/polarization.md; the image is S0, and a scene whose integrator
    is Mitsuba 3's `stokes` also returns `stokes`: S0..S3 in the camera's reference basis, shape
    (4, H, W, 3) in `colorspace`, S1..S3 signed), seed, threads (0: all cores),
    time_limit (seconds), colorspace (any colour space of the OCIO config, default lin_rec709),
    rgb_wavelengths (R, G, B in nm), uniform_wavelengths, wavelength_sampling ("hero", the default,
    or "independent": render --wavelength-sampling), sampler (None: the scene's <sampler>; or
    "independent", "stratified", "multijitter", "sobol", "highdimsobol": render --sampler; an spp given is also the
    pattern size of stratified and multijitter, as --spp is). `progress`: a
    callable receiving the fraction done, or True for a bar on stderr. `spectral_bins` > 0 (spectral
    mode) also returns `spectral`: per pixel the spectral radiance averaged over that many equal
    wavelength bins on 360–830 nm (render/spectral_film.h), estimated from the same samples."""
    if not isinstance(scene, _iris.Scene):
        raise TypeError(f"scene: expected an iris.Scene (from iris.load_file or iris.load_string), got {type(scene).__name__}")
    if mode not in ("spectral", "rgb", "polarized"):
        raise _iris.Error(f"mode: unknown '{mode}' (expected spectral, rgb or polarized)")
    if wavelength_sampling not in ("hero", "independent"):
        raise _iris.Error(f"wavelength_sampling: unknown '{wavelength_sampling}' (expected hero or independent)")
    if sampler not in (None, "independent", "stratified", "multijitter", "sobol", "highdimsobol"):
        raise _iris.Error(f"sampler: unknown sampler '{sampler}' (supported: independent, stratified, multijitter, sobol, highdimsobol)")
    spp = -1 if spp is None else _count("spp", spp, 0)
    limit = 0.0
    if time_limit is not None:
        limit = float(time_limit)
        if not math.isfinite(limit) or limit <= 0:
            raise _iris.Error(f"time_limit: must be > 0 seconds, got {time_limit!r}")
    bins = _count("spectral_bins", spectral_bins, 0, 470)
    if bins and mode == "rgb":
        raise _iris.Error("spectral_bins: a spectral image needs mode='spectral'")
    if spp == 0 and limit == 0:
        raise _iris.Error("spp = 0 renders until time_limit: give time_limit too")
    callback = _TextProgress() if progress is True else (progress or None)
    if callback is not None and not callable(callback):
        raise TypeError("progress: expected a callable taking the fraction done, or True")
    d = _iris.render(scene, spp, limit, _count("seed", seed, 0, 2**63 - 1), _count("threads", threads, 0),
                     mode == "rgb", mode == "polarized", _count("spectral_samples", spectral_samples, 1, 32),
                     _rgb_wavelengths(rgb_wavelengths), bool(uniform_wavelengths),
                     wavelength_sampling == "independent", sampler or "", bins, colorspace, ocio_config or "",
                     callback)
    result = RenderResult(d["image"], d["variance"], d["sample_count"], d["metadata"], d["stats"],
                          spectral=d.get("spectral"), spectral_wavelengths=d.get("spectral_wavelengths"),
                          interrupted=bool(d["stats"]["interrupted"]))
    if "stokes" in d:
        h, w = d["image"].shape[:2]
        result.stokes = np.moveaxis(d["stokes"].reshape(h, w, 4, 3), 2, 0)
    if d["keyboard_interrupt"]:
        raise RenderInterrupted(result)
    return result
