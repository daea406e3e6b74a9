"""Render jobs in this process through the Python module `iris` (docs/python.md) instead of one
`render` process per job: each scene is loaded and its Embree scene built once for every job
with the same scene parameters (-D values), and no process is started per render. The image and
its metadata are written exactly as the CLI writes them (same pixels, same `iris.*` header), so
analysis, resuming and --collect-only are unchanged.

Use it (--in-process) where only the image matters; keep the CLI (the default) where a separate
process is the point: render times of the timing experiments (the module's scene load is shared
between jobs and the interpreter shares the machine) and Slurm arrays."""
from __future__ import annotations

import sys
import time

from .runner import JobResult
from .sweep import RENDER_OPTIONS, VARIANT_AXES, format_value
from .tools import REPO


def import_iris(build_dir):
    """The module from the build folder (build/python), or ImportError saying how to build it."""
    path = str(build_dir / "python")
    if path not in sys.path:
        sys.path.insert(0, path)
    try:
        import iris
    except ImportError as e:
        raise ImportError(f"--in-process needs the Python module in {path} (built by the README's first "
                          f"command; -DIRIS_PYTHON=ON): {e}") from e
    return iris


def render_kwargs(settings: dict) -> tuple:
    """(render keyword arguments, scene defines) of a job's settings (sweep.render_command's split)."""
    kwargs, defines = {}, {}
    for key, value in settings.items():
        if key.startswith("_") or key in VARIANT_AXES or value is None:
            continue
        if key == "wavelength_sampling":
            raise ValueError("wavelength_sampling is not a render option yet")
        if key in RENDER_OPTIONS:
            kwargs[key] = value
        else:
            defines[key] = format_value(value)
    if kwargs.get("rgb_wavelengths") is not None and isinstance(kwargs["rgb_wavelengths"], str):
        kwargs["rgb_wavelengths"] = [float(x) for x in kwargs["rgb_wavelengths"].split(",")]
    return kwargs, defines


def run_inprocess(jobs, build_dir, force: bool = False, log=print) -> list:
    """Render every job with iris.render; JobResults in job order (existing outputs are kept)."""
    iris = import_iris(build_dir)
    scenes = {}
    results = []
    for i, job in enumerate(jobs):
        if job.output.exists() and not force:
            results.append(JobResult(job, 0, 0.0, skipped=True))
            log(f"[{i + 1}/{len(jobs)}] {job.output.name} {job.label}: skip (exists)")
            continue
        start = time.monotonic()
        try:
            kwargs, defines = render_kwargs(job.settings)
            key = (job.scene, tuple(sorted(defines.items())))
            if key not in scenes:
                scenes[key] = iris.load_file(str(REPO / job.scene) if not str(job.scene).startswith("/") else job.scene,
                                             **defines)
            job.output.parent.mkdir(parents=True, exist_ok=True)
            iris.render(scenes[key], **kwargs).write(job.output)
            r = JobResult(job, 0, time.monotonic() - start)
        except (iris.Error, ValueError, TypeError) as e:
            r = JobResult(job, 1, time.monotonic() - start, message=str(e))
        results.append(r)
        status = "ok" if r.ok else f"FAILED: {r.message}"
        log(f"[{i + 1}/{len(jobs)}] {job.output.name} {job.label}: {status} {r.seconds:.1f} s (in-process)")
    return results
