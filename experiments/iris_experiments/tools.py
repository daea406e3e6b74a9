"""Locating the repository and the built iris executables (render, compare, merge)."""
from __future__ import annotations

import functools
import os
import subprocess
from pathlib import Path

from .errors import ExperimentError

REPO = Path(__file__).resolve().parents[2]


def build_dir(explicit: str | None = None) -> Path:
    """--build-dir, else $IRIS_BUILD_DIR, else <repo>/build."""
    if explicit:
        return Path(explicit).resolve()
    if os.environ.get("IRIS_BUILD_DIR"):
        return Path(os.environ["IRIS_BUILD_DIR"]).resolve()
    return REPO / "build"


def tool(name: str, bdir: Path) -> Path:
    """Path of a built executable, or an ExperimentError saying how to build it."""
    path = Path(bdir) / name
    if not (path.is_file() and os.access(path, os.X_OK)):
        raise ExperimentError(
            f"{path}: executable '{name}' not found; build it with `ninja -C {bdir} {name}` "
            f"or pass --build-dir / set IRIS_BUILD_DIR")
    return path


@functools.lru_cache(maxsize=None)
def render_supports(render: Path, option: str) -> bool:
    """Whether `render --help` lists `option` (experiments leave out configurations that need an
    option this build does not have, and say so in the report)."""
    try:
        proc = subprocess.run([str(render), "--help"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return False
    return option in (proc.stdout + proc.stderr).split() or f"{option} " in proc.stdout
