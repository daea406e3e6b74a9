"""Materials: any registered BSDF (`material_types()`), created from a dict or a <bsdf> XML
fragment and evaluated for arrays of directions in the local shading frame (normal +z; wo and wi
both point away from the surface, materials/bsdf.h), at chosen wavelengths (spectral mode) or in
RGB mode (wavelengths_nm=None: the three channels at rgb_wavelengths, default 645, 525, 445 nm).

    m = iris.Material({"type": "roughconductor", "material": "Au", "alpha": 0.2})
    f = m.eval(wo, wi, wavelengths_nm=[450, 550, 650])   # (..., 3) values of f (no cosine)
"""
from __future__ import annotations

import os
from xml.sax.saxutils import quoteattr

import numpy as np

from . import _iris
from ._arrays import direction_array, real_array, wavelength_array
from ._arrays import rgb_wavelengths as _rgb_list

REFLECTION = _iris.BSDF_REFLECTION
TRANSMISSION = _iris.BSDF_TRANSMISSION
DIFFUSE = _iris.BSDF_DIFFUSE
GLOSSY = _iris.BSDF_GLOSSY
SPECULAR = _iris.BSDF_SPECULAR
NULL = _iris.BSDF_NULL  # the pass-through of `mask` and `null` (with TRANSMISSION | SPECULAR)


def material_types() -> list:
    """Every <bsdf type="..."> the renderer knows."""
    return _iris.material_types()


def texture_types() -> list:
    """Every <texture type="..."> the renderer knows."""
    return _iris.texture_types()


def _value_xml(name: str, value, indent: str) -> str:
    n = quoteattr(name)
    if isinstance(value, dict):
        if "type" not in value:
            raise _iris.Error(f"{name}: a nested object needs a 'type' key, got {sorted(value)}")
        if value["type"] in ("spectrum", "rgb", "srgb"):  # <spectrum/rgb name=... value=.../>
            if set(value) != {"type", "value"}:
                raise _iris.Error(f"{name}: a {value['type']} takes exactly a 'value' key")
            return f"{indent}<{value['type']} name={n} value={quoteattr(str(value['value']))}/>\n"
        textures = set(texture_types()) - set(material_types())
        tag = "texture" if value["type"] in textures else "bsdf"
        return to_xml(value, tag, name, indent)
    if isinstance(value, bool):
        return f"{indent}<boolean name={n} value=\"{'true' if value else 'false'}\"/>\n"
    if isinstance(value, (int, np.integer)):
        return f"{indent}<integer name={n} value=\"{int(value)}\"/>\n"
    if isinstance(value, (float, np.floating)):
        return f"{indent}<float name={n} value=\"{float(value)!r}\"/>\n"
    if isinstance(value, str):
        return f"{indent}<string name={n} value={quoteattr(value)}/>\n"
    a = np.asarray(value)
    if a.dtype.kind in "biuf" and a.shape == (3,):
        return f"{indent}<rgb name={n} value=\"{', '.join(repr(float(x)) for x in a)}\"/>\n"
    raise TypeError(f"{name}: cannot express {value!r} as a scene parameter (number, bool, string, RGB triple or "
                    "nested dict with 'type')")


def to_xml(spec: dict, tag: str = "bsdf", name: str | None = None, indent: str = "") -> str:
    """The XML fragment of a dict {"type": ..., parameter: value, ...}: numbers become <float> or
    <integer>, bools <boolean>, strings <string>, 3-sequences <rgb>, {"type": "spectrum", "value":
    "400:0.1, 700:0.9"} a <spectrum>, and nested dicts <bsdf> or <texture> elements."""
    if not isinstance(spec, dict) or "type" not in spec:
        raise _iris.Error("a material dict needs a 'type' key, e.g. {'type': 'diffuse'}")
    attrs = f" type={quoteattr(str(spec['type']))}"
    if name is not None:
        attrs += f" name={quoteattr(name)}"
    body = "".join(_value_xml(str(k), v, indent + "  ") for k, v in spec.items() if k != "type")
    return f"{indent}<{tag}{attrs}>\n{body}{indent}</{tag}>\n"


class Material:
    """A BSDF of the renderer, from a dict (see `to_xml`) or a <bsdf> XML fragment (relative file
    names resolve against base_dir, default the current directory). Bad input raises iris.Error
    with the fragment's line ("<string>:2: unknown parameter ...")."""

    def __init__(self, spec, base_dir=None):
        xml = to_xml(spec) if isinstance(spec, dict) else spec
        if not isinstance(xml, str):
            raise TypeError(f"Material: expected a dict or an XML string, got {type(spec).__name__}")
        self.xml = xml
        self._m = _iris.Material(xml, os.fspath(base_dir) if base_dir is not None else os.getcwd())

    @property
    def type(self) -> str:
        return self._m.type

    def __repr__(self) -> str:
        return f"<iris.Material {self.type}>"

    @staticmethod
    def _pairs(wo, wi):
        wo, wi = direction_array("wo", wo), direction_array("wi", wi)
        shape = np.broadcast_shapes(wo.shape, wi.shape)
        flat = lambda a: np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1, 3)
        return flat(wo), flat(wi), shape[:-1]

    def eval(self, wo, wi, wavelengths_nm=None, rgb_wavelengths=None, transport: str = "radiance") -> np.ndarray:
        """f(wo, wi) without the cosine, shape (..., M) for M wavelengths (3 in RGB mode)."""
        a, b, shape = self._pairs(wo, wi)
        f = self._m.eval(a, b, wavelength_array(wavelengths_nm), _rgb_list(rgb_wavelengths), transport)
        return f.reshape(shape + (f.shape[-1],))

    def pdf(self, wo, wi, wavelengths_nm=None, rgb_wavelengths=None, transport: str = "radiance") -> np.ndarray:
        """Solid-angle density of sample() choosing wi, shape (...)."""
        a, b, shape = self._pairs(wo, wi)
        return self._m.pdf(a, b, wavelength_array(wavelengths_nm), _rgb_list(rgb_wavelengths),
                           transport).reshape(shape)

    def sample(self, wo, uc, u, wavelengths_nm=None, rgb_wavelengths=None, transport: str = "radiance") -> dict:
        """Sample wi for each wo with the 1D lobe sample uc (...) and 2D sample u (..., 2), in [0, 1).
        Returns a dict of arrays: wi (..., 3), f (..., M), pdf, flags, eta, valid (...)."""
        wo = direction_array("wo", wo)
        uc, u = real_array("uc", uc), real_array("u", u)
        if u.ndim < 1 or u.shape[-1] != 2:
            raise _iris.Error(f"u: expected 2D samples (shape (..., 2)), got shape {u.shape}")
        shape = np.broadcast_shapes(wo.shape[:-1], uc.shape, u.shape[:-1])
        d = self._m.sample(np.ascontiguousarray(np.broadcast_to(wo, shape + (3,))).reshape(-1, 3),
                           np.ascontiguousarray(np.broadcast_to(uc, shape)).ravel().astype(np.float32),
                           np.ascontiguousarray(np.broadcast_to(u, shape + (2,))).reshape(-1, 2).astype(np.float32),
                           wavelength_array(wavelengths_nm), _rgb_list(rgb_wavelengths), transport)
        return {k: v.reshape(shape + v.shape[1:]) for k, v in d.items()}

    def flags(self, wavelengths_nm=None) -> int:
        """The BSDF's lobes (REFLECTION | TRANSMISSION | DIFFUSE | GLOSSY | SPECULAR)."""
        return self._m.flags(wavelength_array(wavelengths_nm), [])
