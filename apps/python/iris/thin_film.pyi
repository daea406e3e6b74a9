from typing import Any, NamedTuple

import numpy as np

MODES: tuple[str, ...]

class StackRT(NamedTuple):
    Rs: np.ndarray
    Rp: np.ndarray
    Ts: np.ndarray
    Tp: np.ndarray
    @property
    def R(self) -> np.ndarray: ...
    @property
    def T(self) -> np.ndarray: ...

class Layer(NamedTuple):
    ior: Any
    thickness_nm: float

def ior_preset_names() -> list[str]: ...
def conductor_names() -> list[str]: ...
def ior(spec: Any, wavelengths_nm: Any) -> np.ndarray: ...
def stack_rt(layers: Any, wavelengths_nm: Any, cos_theta: Any, incident_ior: Any = ..., substrate_ior: Any = ...,
             mode: str = ..., K: int = ...) -> StackRT: ...
class StackMueller(NamedTuple):
    R: np.ndarray
    T: np.ndarray

def stack_mueller(layers: Any, wavelengths_nm: Any, cos_theta: Any, incident_ior: Any = ..., substrate_ior: Any = ...,
                  mode: str = ..., K: int = ...) -> StackMueller: ...
def belcour_barla_rgb(film_ior: Any, thickness_nm: Any, cos_theta: Any, incident_ior: Any = ...,
                      substrate_ior: Any = ...) -> np.ndarray: ...
def khr_iridescence_rgb(film_ior: Any, thickness_nm: Any, cos_theta: Any, base_f0: Any, outside_ior: Any = ...) -> np.ndarray: ...
def gulbrandsen_ior(reflectivity: Any, edge_tint: Any) -> np.ndarray: ...
