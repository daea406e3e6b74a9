"""Temporary copies of a test scene, optionally with a deliberate error, to show that the suite can
fail (and, by hand, to diagnose a failure). The copy holds the scene file and its fragments/ with
`<path>` made absolute; the original files are never changed and the suite's own table always uses
them as written.

Perturbations (`kind=value`):
  albedo=F  multiply every reflectance / diffuse_reflectance / base_color value (rgb, spectrum,
            float; the value of each `λ:value` pair) by F
  fov=D     give the sensor an explicit `fov` of Mitsuba's default plus D degrees (Mitsuba: a
            50 mm focal length on a 36x24 mm film, measured along the diagonal); fov=0 is the
            diagnosis of a front end without `focal_length`, never part of the suite's verdicts
"""
from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

from iris_experiments.errors import ExperimentError

ALBEDO_PARAMS = ("reflectance", "diffuse_reflectance", "base_color")
_ALBEDO = re.compile(r'(<(?:rgb|spectrum|float)\s+name="(?:' + "|".join(ALBEDO_PARAMS) + r')"\s+value=")([^"]*)(")')
_NUMBER = re.compile(r"(?<![:\w.])([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)(?![\w.:])")


def scale_values(value: str, factor: float) -> str:
    """Scale every number of an attribute value except the wavelengths of `λ:value` pairs."""
    def pair(m):
        return f"{m.group(1)}:{float(m.group(2)) * factor:.9g}"
    if ":" in value:
        return re.sub(r"([-+]?\d*\.?\d+)\s*:\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)", pair, value)
    return _NUMBER.sub(lambda m: f"{float(m.group(1)) * factor:.9g}", value)


def mitsuba_default_fov_x(width: int, height: int, focal_length_mm: float = 50.0) -> float:
    """Horizontal field of view (degrees) of Mitsuba's default sensor: the 50 mm focal length gives a
    diagonal FOV on the 36x24 mm full frame, 2·atan(√(36²+24²) / (2 f)), applied to the image diagonal."""
    half_diag = math.tan(math.atan(math.hypot(36.0, 24.0) / (2.0 * focal_length_mm)))
    return math.degrees(2.0 * math.atan(half_diag * width / math.hypot(width, height)))


def _film_size(text: str) -> tuple[int, int]:
    w = re.search(r'<integer\s+name="width"\s+value="(\d+)"', text)
    h = re.search(r'<integer\s+name="height"\s+value="(\d+)"', text)
    return (int(w.group(1)) if w else 768, int(h.group(1)) if h else 576)   # Mitsuba's hdrfilm defaults


def _apply(text: str, kind: str, value: float) -> tuple[str, int]:
    if kind == "albedo":
        return _ALBEDO.subn(lambda m: m.group(1) + scale_values(m.group(2), value) + m.group(3), text)
    if kind == "fov":
        if "<sensor" not in text:
            return text, 0
        if re.search(r'name="fov"', text):
            raise ExperimentError("perturbation fov: the scene already sets fov")
        fov = mitsuba_default_fov_x(*_film_size(text)) + value
        return re.subn(r'(<sensor\s+type="perspective"\s*>)',
                       lambda m: f'{m.group(1)}<float name="fov" value="{fov:.6f}"/><string name="fov_axis" value="x"/>',
                       text)
    raise ExperimentError(f"unknown perturbation '{kind}' (known: albedo=F, fov=D)")


def parse(spec: str) -> tuple[str, float]:
    kind, _, value = spec.partition("=")
    try:
        return kind.strip(), float(value)
    except ValueError:
        raise ExperimentError(f"perturbation '{spec}': expected kind=number, e.g. albedo=1.02 or fov=1") from None


def neutral(spec: str) -> str:
    """The perturbation of the same kind that changes nothing physically (albedo=1, fov=0)."""
    kind, _ = parse(spec)
    return f"{kind}=1" if kind == "albedo" else f"{kind}=0"


def perturbed_copy(scene: Path, spec: str | None, workdir: Path) -> Path:
    """Copy `scene` (and fragments/) into workdir with `spec` applied; returns the copy's path."""
    workdir.mkdir(parents=True, exist_ok=True)
    files = [scene] + sorted((scene.parent / "fragments").glob("*.xml"))
    kind, value = parse(spec) if spec else (None, 0.0)
    edits = 0
    for src in files:
        dst = workdir / src.relative_to(scene.parent)
        dst.parent.mkdir(parents=True, exist_ok=True)
        text = src.read_text()
        text = re.sub(r'(<path\s+value=")([^"]*)(")',
                      lambda m: m.group(1) + str((src.parent / m.group(2)).resolve()) + m.group(3), text)
        if kind:
            text, n = _apply(text, kind, value)
            edits += n
        dst.write_text(text)
    if kind and edits == 0:
        raise ExperimentError(f"{scene}: perturbation '{spec}' changes nothing in this scene")
    return workdir / scene.name


def remove(workdir: Path) -> None:
    shutil.rmtree(workdir, ignore_errors=True)
