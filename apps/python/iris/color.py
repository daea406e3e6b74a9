"""Spectra and colour: the CIE 1931 2° colour-matching functions and D65 the renderer uses
(spectral/cie.h), spectrum → XYZ by its 1 nm quadrature (normalised so that a constant spectrum 1
has Y = 1, docs/conventions.md), colour-space conversion and display transforms through
OpenColorIO (the shipped config unless `config` or $OCIO names another), and RGB → reflectance
spectrum upsampling (Jakob & Hanika 2019, spectral/rgb_upsampling.h).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _iris
from ._arrays import real_array

LAMBDA_MIN = _iris.LAMBDA_MIN
LAMBDA_MAX = _iris.LAMBDA_MAX
DEFAULT_RGB_WAVELENGTHS = _iris.DEFAULT_RGB_WAVELENGTHS
XYZ = "CIE-XYZ"
LINEAR_REC709 = "lin_rec709"


def _lambdas(wavelengths_nm):
    a = real_array("wavelengths_nm", wavelengths_nm)
    return a, np.ravel(a).astype(np.float32)


def xyz_bar(wavelengths_nm) -> np.ndarray:
    """(x̄, ȳ, z̄) at each wavelength (0 outside 360–830 nm): shape (..., 3) float32."""
    a, flat = _lambdas(wavelengths_nm)
    return _iris.cie_xyz_bar(flat).reshape(a.shape + (3,))


def d65(wavelengths_nm) -> np.ndarray:
    """CIE standard illuminant D65 (100 at 560 nm)."""
    a, flat = _lambdas(wavelengths_nm)
    return _iris.cie_d65(flat).reshape(a.shape)


def y_integral() -> float:
    """∫ ȳ dλ over the table (nm), the normalisation of Y."""
    return _iris.cie_y_integral()


def visible_wavelength_pdf(wavelengths_nm) -> np.ndarray:
    """The renderer's wavelength-sampling density (1/nm)."""
    a, flat = _lambdas(wavelengths_nm)
    return _iris.visible_wavelength_pdf(flat).reshape(a.shape)


def spectrum_to_xyz(wavelengths_nm, values) -> np.ndarray:
    """XYZ (float64, 3) of a tabulated spectrum (increasing wavelengths, linear interpolation,
    constant outside the table), integrated on 360–830 nm in 1 nm steps as the renderer does."""
    lam = real_array("wavelengths_nm", wavelengths_nm).ravel()
    v = real_array("values", values).ravel()
    return _iris.spectrum_to_xyz(lam.astype(np.float32), v.astype(np.float32))


def color_spaces(config: str | None = None) -> list:
    """Names of the colour spaces of the OCIO config."""
    return _iris.color_spaces(config or "")


def convert(colors, source: str, target: str, config: str | None = None) -> np.ndarray:
    """Colours (..., 3) converted from colour space `source` to `target` (float32 copy)."""
    return _iris.convert_colors(colors, source, target, config or "", False, "")


def xyz_to(xyz, target: str = LINEAR_REC709, config: str | None = None) -> np.ndarray:
    """CIE XYZ (..., 3) → any colour space of the config."""
    return convert(xyz, XYZ, target, config)


def to_display(colors, source: str = LINEAR_REC709, display: str = "", view: str = "",
               config: str | None = None) -> np.ndarray:
    """Display code values (the PNG the `render` executable writes) of colours in `source`."""
    return _iris.convert_colors(colors, source, display, config or "", True, view)


class RGBSpectrum(NamedTuple):
    """A sigmoid-polynomial reflectance s(λ) = S(c0 t² + c1 t + c2), t = (λ − 360)/470 (Jakob &
    Hanika 2019 eqs. 3–4), fitted so that it reproduces an RGB colour under D65."""
    coefficients: tuple
    error: float       # max |RGB(s) − target| component error of the fit
    iterations: int

    def __call__(self, wavelengths_nm) -> np.ndarray:
        a, flat = _lambdas(wavelengths_nm)
        return _iris.eval_sigmoid(list(self.coefficients), flat).reshape(a.shape)

    def rgb(self) -> np.ndarray:
        """Linear Rec.709 RGB of the reflectance under D65 (what the fit matched)."""
        return np.array(_iris.sigmoid_rgb(list(self.coefficients)), dtype=np.float32)


def rgb_to_spectrum(rgb) -> RGBSpectrum:
    """Upsample a linear Rec.709 reflectance colour (components clamped to [0, 1]) to a spectrum."""
    a = real_array("rgb", rgb).ravel()
    if a.size != 3:
        raise _iris.Error(f"rgb: expected 3 components, got {a.size}")
    c, err, it = _iris.fit_rgb([float(x) for x in a])
    return RGBSpectrum(tuple(c), float(err), int(it))


def delta_e2000(test, reference) -> np.ndarray:
    """CIEDE2000 between linear Rec.709 colours (..., 3), as the `compare` tool measures images
    (CIELAB with the RGB white, D65 at Y = 1, as reference white)."""
    a = real_array("test", test)
    b = real_array("reference", reference)
    if a.shape != b.shape or a.shape[-1:] != (3,):
        raise _iris.Error(f"test and reference must have the same shape (..., 3), got {a.shape} and {b.shape}")
    return _iris.color_delta_e2000(a.reshape(-1, 3), b.reshape(-1, 3)).reshape(a.shape[:-1])
