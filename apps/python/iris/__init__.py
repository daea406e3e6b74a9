"""iris: a spectral Monte Carlo renderer for thin-film iridescence research, from Python.

    import iris
    scene = iris.load_file("scenes/default.xml", res=64)
    result = iris.render(scene, spp=16, seed=1)      # result.image: (H, W, 3) float32
    iris.thin_film.stack_rt([(1.33, 300.0)], wavelengths_nm, cos_theta, 1.0, 1.5)

Scenes and rendering live here (`load_file`, `load_string`, `render`, `read`, `write`), thin-film optics
in `iris.thin_film` (`iris.film` is its deprecated alias), materials in `iris.materials` (`iris.Material`), spectra and colour in
`iris.color`. docs/python.md documents every function with an example.
"""
from __future__ import annotations

from . import _iris
from ._iris import Error, Scene
from .render import RenderInterrupted, RenderResult, load_file, load_string, render
from .images import read, write
from .materials import Material
from . import color, film, materials, thin_film

__version__ = _iris.version

__all__ = ["Error", "Scene", "RenderInterrupted", "RenderResult", "load_file", "load_string", "render", "read",
           "write", "Material", "color", "film", "materials", "source_path", "thin_film"]


def source_path(relative: str) -> str:
    """Absolute path of a file of the iris checkout this module was built from (e.g. a scene)."""
    return _iris.source_path(relative)
