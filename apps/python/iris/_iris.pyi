# The C++ extension (apps/python/*.cpp); use the package's wrappers instead.
from typing import Any

import numpy as np

version: str
LAMBDA_MIN: float
LAMBDA_MAX: float
DEFAULT_RGB_WAVELENGTHS: tuple[float, float, float]
BSDF_REFLECTION: int
BSDF_TRANSMISSION: int
BSDF_DIFFUSE: int
BSDF_GLOSSY: int
BSDF_SPECULAR: int
BSDF_NULL: int

class Error(ValueError): ...

class Scene:
    path: str
    width: int
    height: int
    spp: int
    integrator: str
    max_depth: int
    triangle_count: int
    light_count: int

class Material:
    type: str
    def __init__(self, xml: str, base_dir: str) -> None: ...
    def eval(self, wo: np.ndarray, wi: np.ndarray, wavelengths_nm: Any, rgb_wavelengths: list[float], transport: str) -> np.ndarray: ...
    def pdf(self, wo: np.ndarray, wi: np.ndarray, wavelengths_nm: Any, rgb_wavelengths: list[float], transport: str) -> np.ndarray: ...
    def sample(self, wo: np.ndarray, uc: np.ndarray, u: np.ndarray, wavelengths_nm: Any, rgb_wavelengths: list[float], transport: str) -> dict[str, np.ndarray]: ...
    def flags(self, wavelengths_nm: Any, rgb_wavelengths: list[float]) -> int: ...

def __getattr__(name: str) -> Any: ...
