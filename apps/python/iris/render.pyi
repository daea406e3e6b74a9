from collections.abc import Callable
from os import PathLike
from typing import Any

import numpy as np

from ._iris import Scene

def load_file(path: str | PathLike[str], **defines: Any) -> Scene: ...
def load_string(xml: str, base_dir: str | PathLike[str] | None = ..., **defines: Any) -> Scene: ...

class RenderResult:
    image: np.ndarray
    variance: np.ndarray
    sample_count: np.ndarray
    metadata: dict[str, str]
    stats: dict[str, Any]
    spectral: np.ndarray | None
    spectral_wavelengths: np.ndarray | None
    interrupted: bool
    stokes: np.ndarray | None
    @property
    def spp(self) -> int: ...
    def write(self, path: str | PathLike[str]) -> None: ...

class RenderInterrupted(KeyboardInterrupt):
    result: RenderResult
    def __init__(self, result: RenderResult) -> None: ...

def render(scene: Scene, spp: int | None = ..., mode: str = ..., spectral_samples: int = ..., seed: int = ...,
           threads: int = ..., time_limit: float | None = ..., sampler: str | None = ..., colorspace: str = ...,
           rgb_wavelengths: Any = ..., uniform_wavelengths: bool = ...,
           progress: Callable[[float], object] | bool | None = ..., ocio_config: str | None = ...,
           spectral_bins: int = ..., wavelength_sampling: str = ...) -> RenderResult: ...
