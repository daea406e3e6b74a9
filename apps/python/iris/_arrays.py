"""Validation and broadcasting of array arguments shared by the package's modules."""
from __future__ import annotations

import numpy as np

from . import _iris


def real_array(name: str, value) -> np.ndarray:
    """`value` as a float64 array; TypeError for non-numeric or complex input, iris.Error for NaN."""
    a = np.asarray(value)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name}: expected real numbers, got an array of dtype {a.dtype}")
    a = a.astype(np.float64, copy=False)
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise _iris.Error(f"{name}: entry {int(bad[0])} is {a.ravel()[bad[0]]} (expected a finite number)")
    return a


def direction_array(name: str, value) -> np.ndarray:
    """(..., 3) float32 directions."""
    a = real_array(name, value)
    if a.ndim < 1 or a.shape[-1] != 3:
        raise _iris.Error(f"{name}: expected an array of 3-vectors (shape (..., 3)), got shape {a.shape}")
    return a.astype(np.float32)


def wavelength_array(value) -> np.ndarray | None:
    """1D float32 wavelengths in nm (None stays None: RGB mode)."""
    if value is None:
        return None
    a = np.atleast_1d(real_array("wavelengths_nm", value))
    if a.ndim != 1:
        raise _iris.Error(f"wavelengths_nm: expected a 1D array, got shape {a.shape}")
    return a.astype(np.float32)


def rgb_wavelengths(value) -> list:
    """[] (the default channel wavelengths) or three wavelengths in nm."""
    if value is None:
        return []
    a = real_array("rgb_wavelengths", value).ravel()
    if a.size != 3:
        raise _iris.Error(f"rgb_wavelengths: expected 3 wavelengths (R, G, B) in nm, got {a.size}")
    return [float(x) for x in a]
