"""Sweep definitions: a cartesian product of render settings and scene parameters, expanded into
render jobs with deterministic output paths (the same sweep always gives the same paths, so runs
can resume and Slurm array tasks can find their job by index)."""
from __future__ import annotations

import itertools
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

# Settings that map to render command-line options; any other axis name is a scene parameter
# passed as `-D name=value` (a <default name="..."/> of the scene).
RENDER_OPTIONS = {
    "spp": "--spp",
    "time_limit": "--time-limit",
    "seed": "--seed",
    "threads": "--threads",
    "mode": "--mode",
    "spectral_samples": "--spectral-samples",
    "rgb_wavelengths": "--rgb-wavelengths",
    "wavelength_sampling": "--wavelength-sampling",   # not in render yet: see tools.render_supports
    "sampler": "--sampler",
}


# Axis names that only label a group of settings (see Sweep) and are not passed to render.
VARIANT_AXES = {"variant"}


def format_value(value) -> str:
    """Text form of a setting: lists/tuples as comma-separated values, floats without noise."""
    if isinstance(value, (list, tuple)):
        return ",".join(format_value(v) for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def slug(text: str) -> str:
    """File-name-safe form of a value: letters, digits, '.', '-' and '_' only."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("_") or "x"


@dataclass
class Job:
    index: int
    sweep: str
    scene: str                 # scene path as given (relative to the repository root)
    label: str                 # short scene label used in paths and tables
    settings: dict             # every axis and fixed value of this point (raw values)
    output: Path               # the EXR this job writes
    command: list = field(default_factory=list)

    def shell(self) -> str:
        return shlex.join(str(a) for a in self.command)


@dataclass
class Sweep:
    """`axes` values are swept (cartesian product, in insertion order); `fixed` apply to every job.
    An axis value may be a dict {"name": label, setting: value, ...}: its settings are applied
    together and the axis itself records the label (a "variant" axis, not passed to render).

    scenes: {label: scene path}. Output: <out_dir>/renders/<sweep>/<label>/<axis=value>_... .exr"""
    name: str
    scenes: dict
    axes: dict = field(default_factory=dict)
    fixed: dict = field(default_factory=dict)
    per_scene: dict = field(default_factory=dict)   # {label: {setting: value}} added for that scene only
    linked: dict = field(default_factory=dict)      # {source: target}: target takes the source's value

    def points(self):
        keys = list(self.axes)
        for values in itertools.product(*(self.axes[k] for k in keys)):
            yield dict(zip(keys, values))

    def jobs(self, out_dir: Path, render: Path, first_index: int = 0, quiet: bool = True) -> list:
        out = []
        index = first_index
        for label, scene in self.scenes.items():
            for point in self.points():
                settings = dict(self.fixed)
                settings.update(self.per_scene.get(label, {}))
                for key, value in point.items():
                    if isinstance(value, dict):  # a named group of settings: {"name": ..., setting: value}
                        settings.update({k: v for k, v in value.items() if k != "name"})
                        settings[key] = value["name"]
                    else:
                        settings[key] = value
                for src, dst in self.linked.items():
                    settings[dst] = settings[src]
                stem = "_".join(f"{slug(k)}={slug(format_value(settings[k]))}" for k in point) or "default"
                output = Path(out_dir) / "renders" / slug(self.name) / slug(label) / f"{stem}.exr"
                out.append(Job(index, self.name, scene, label, settings, output,
                               render_command(render, scene, output, settings, quiet)))
                index += 1
        return out


def render_command(render: Path, scene: str, output: Path, settings: dict, quiet: bool = True) -> list:
    """The render command line for one job (see apps/render.cpp --help)."""
    cmd = [str(render), str(scene), "-o", str(output)]
    for key, value in settings.items():
        if key.startswith("_") or key in VARIANT_AXES or value is None:
            continue  # private annotations and unset options
        if key in RENDER_OPTIONS:
            cmd += [RENDER_OPTIONS[key], format_value(value)]
        else:
            cmd += ["-D", f"{key}={format_value(value)}"]
    if quiet:
        cmd.append("--quiet")
    return cmd


def expand(sweeps, out_dir: Path, render: Path) -> list:
    """Jobs of several sweeps with consecutive indices (the Slurm array index)."""
    jobs = []
    for s in sweeps:
        jobs += s.jobs(out_dir, render, first_index=len(jobs))
    paths = [j.output for j in jobs]
    if len(set(paths)) != len(paths):
        dup = sorted({str(p) for p in paths if paths.count(p) > 1})
        raise ValueError(f"sweeps produce the same output path twice: {dup[:3]}")
    return jobs
