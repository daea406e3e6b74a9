"""Checks that the scenes, materials and scene parameters an experiment needs exist, so an
experiment fails at once with a clear message instead of after hours of rendering."""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from .errors import ExperimentError
from .tools import REPO

_REGISTER = re.compile(r'IRIS_REGISTER\(\s*(\w+)\s*,\s*"([^"]+)"')


@dataclass
class SceneSpec:
    """A scene an experiment renders: its path (relative to the repo), the material plugins it must
    use, and the <default> parameters it must declare (the experiment sets them with -D)."""
    path: str
    materials: tuple = ()
    params: tuple = ()
    optional_params: tuple = ()   # set only when the scene declares them (e.g. width/height in quick mode)
    note: str = ""
    declared: set = field(default_factory=set)


def registered_plugins(repo: Path = REPO) -> dict:
    """{registry name: {plugin names}} from the IRIS_REGISTER lines in the sources."""
    found = {}
    for folder in ("core", "spectral", "materials", "integrators"):
        for src in (Path(repo) / folder).rglob("*.cpp"):
            for reg, name in _REGISTER.findall(src.read_text(errors="replace")):
                found.setdefault(reg, set()).add(name)
    return found


def scene_defaults(path: Path) -> set:
    """Names of the <default name="..."/> parameters declared by a scene file."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise ExperimentError(f"{path}: not valid XML ({e})") from e
    return {el.get("name") for el in root.iter("default") if el.get("name")}


def scene_bsdf_types(path: Path) -> set:
    root = ET.parse(path).getroot()
    return {el.get("type") for el in root.iter("bsdf") if el.get("type")}


def check_scenes(specs, repo: Path = REPO, plugins: dict | None = None) -> None:
    """Raise one ExperimentError listing every missing scene, material or parameter."""
    plugins = registered_plugins(repo) if plugins is None else plugins
    materials = plugins.get("MaterialRegistry", set())
    problems = []
    for spec in specs:
        path = Path(repo) / spec.path
        for m in spec.materials:
            if m not in materials:
                problems.append(f"material '{m}' is not available yet (no IRIS_REGISTER(MaterialRegistry, \"{m}\", ...) "
                                f"in the sources); needed by {spec.path}")
        if not path.is_file():
            problems.append(f"{spec.path}: scene not available yet" + (f" ({spec.note})" if spec.note else ""))
            continue
        declared = scene_defaults(path)
        spec.declared = declared
        missing = [p for p in spec.params if p not in declared]
        if missing:
            problems.append(f"{spec.path}: the scene must declare " +
                            ", ".join(f'<default name="{p}" value="..."/>' for p in missing) +
                            " (the experiment sets them with -D)")
        for t in sorted(scene_bsdf_types(path)):
            if t not in materials and t not in ("twosided",):
                problems.append(f"{spec.path}: uses bsdf type '{t}', which is not registered in this build")
    if problems:
        raise ExperimentError("cannot run this experiment yet:\n  " + "\n  ".join(problems))
