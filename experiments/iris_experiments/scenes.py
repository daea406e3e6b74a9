"""Checks that the scenes, materials and scene parameters an experiment needs exist, so an
experiment fails at once with a clear message instead of after hours of rendering."""
from __future__ import annotations

import re
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


def _scene_text(path: Path) -> str:
    """The scene without comments. Scanned with patterns rather than a strict XML parser, because
    the renderer's parser (pugixml) accepts what strict XML rejects, e.g. "--" inside comments."""
    try:
        text = Path(path).read_text(errors="replace")
    except OSError as e:
        raise ExperimentError(f"{path}: {e.strerror}") from e
    return re.sub(r"<!--.*?-->", "", text, flags=re.S)


def _attr_values(text: str, tag: str, attr: str) -> set:
    values = set()
    for m in re.finditer(rf"<{tag}\b([^>]*)>", text):
        a = re.search(rf"\b{attr}\s*=\s*(\"([^\"]*)\"|'([^']*)')", m.group(1))
        if a:
            values.add(a.group(2) if a.group(2) is not None else a.group(3))
    return values


def scene_defaults(path: Path) -> set:
    """Names of the <default name="..."/> parameters declared by a scene file."""
    return _attr_values(_scene_text(path), "default", "name")


def scene_bsdf_types(path: Path) -> set:
    return _attr_values(_scene_text(path), "bsdf", "type")


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
