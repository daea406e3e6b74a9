"""Exact optics of thin-film stacks (spectral/thin_film_stack.h, docs/thin_film.md), vectorised over
NumPy arrays of wavelength and angle.

Indices of refraction may be numbers, complex numbers n + ik (k ≥ 0 absorbs), arrays that
broadcast with the wavelengths, or names: a dielectric preset ("bk7", "water", ...:
`ior_preset_names()`) or a measured conductor shipped with the renderer ("Au", "Cu", ...:
`conductor_names()`, spectral/data/ior), evaluated at each wavelength.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _iris
from ._arrays import real_array

MODES = ("transfer_matrix", "airy", "truncated", "incoherent")


class StackRT(NamedTuple):
    """Power reflectance and transmittance for s and p polarisation (unpolarised: R, T)."""
    Rs: np.ndarray
    Rp: np.ndarray
    Ts: np.ndarray
    Tp: np.ndarray

    @property
    def R(self) -> np.ndarray:
        return 0.5 * (self.Rs + self.Rp)

    @property
    def T(self) -> np.ndarray:
        return 0.5 * (self.Ts + self.Tp)


class Layer(NamedTuple):
    """One homogeneous layer: index (number, complex, array or name) and thickness in nm."""
    ior: object
    thickness_nm: float


def ior_preset_names() -> list:
    """Names of the dielectric presets (Mitsuba 3's table)."""
    return _iris.ior_preset_names()


def conductor_names() -> list:
    """Names of the measured conductors (η and κ spectra in spectral/data/ior)."""
    return _iris.conductor_names()


def ior(spec, wavelengths_nm) -> np.ndarray:
    """The complex index n + ik of `spec` at the given wavelengths (complex128, their shape)."""
    lam = real_array("wavelengths_nm", wavelengths_nm)
    return _resolve(spec, "ior", np.ravel(lam), lam.shape)


def _resolve(spec, name: str, lam_flat: np.ndarray, shape: tuple) -> np.ndarray:
    """An index spec as a complex array of `shape`, raveled like lam_flat."""
    if isinstance(spec, str):
        return _iris.named_ior(spec, lam_flat).reshape(shape)
    a = np.asarray(spec)
    if a.dtype.kind not in "biufc":
        raise TypeError(f"{name}: expected a number, complex number, array or material name, got {type(spec).__name__}")
    if a.dtype.kind == "c":
        bad = ~(np.isfinite(a.real) & np.isfinite(a.imag))
    else:
        bad = ~np.isfinite(a)
    if np.any(bad):
        raise _iris.Error(f"{name}: contains NaN or infinite values")
    try:
        return np.broadcast_to(a.astype(np.complex128), shape)
    except ValueError:
        raise _iris.Error(f"{name}: shape {a.shape} does not broadcast with the wavelengths/angles shape {shape}") from None


def _shape_of(spec):
    return () if isinstance(spec, str) else np.shape(spec)


def _layers(layers) -> list:
    out = []
    for i, layer in enumerate(layers):
        try:
            ior_spec, d = layer
        except (TypeError, ValueError):
            raise TypeError(f"layers[{i}]: expected (ior, thickness_nm), got {layer!r}") from None
        d = real_array(f"layers[{i}] thickness_nm", d)
        if d.ndim != 0:
            raise _iris.Error(f"layers[{i}] thickness_nm: expected one number, got shape {d.shape}")
        out.append(Layer(ior_spec, float(d)))
    return out


def _stack_call(fn, layers, wavelengths_nm, cos_theta, incident_ior, substrate_ior, mode, K):
    """Broadcasts the arguments of stack_rt / stack_mueller to flat arrays, calls the C++ function
    `fn` on them and returns its result with the broadcast shape."""
    if mode not in MODES:
        raise _iris.Error(f"mode: unknown '{mode}' (expected one of {', '.join(MODES)})")
    ls = _layers(layers)
    lam = real_array("wavelengths_nm", wavelengths_nm)
    cos = real_array("cos_theta", cos_theta)
    n0 = real_array("incident_ior", incident_ior)
    shapes = [lam.shape, cos.shape, n0.shape, _shape_of(substrate_ior)] + [_shape_of(l.ior) for l in ls]
    try:
        shape = np.broadcast_shapes(*shapes)
    except ValueError:
        raise _iris.Error(f"wavelengths_nm, cos_theta and the indices do not broadcast together (shapes {shapes})") from None
    lam_flat = np.ascontiguousarray(np.broadcast_to(lam, shape)).ravel()
    cos_flat = np.ascontiguousarray(np.broadcast_to(cos, shape)).ravel()
    n0_flat = np.ascontiguousarray(np.broadcast_to(n0, shape)).ravel()
    iors = np.array([_resolve(l.ior, f"layers[{i}] ior", lam_flat, shape).ravel() for i, l in enumerate(ls)],
                    dtype=np.complex128).reshape(len(ls), lam_flat.size)
    sub = np.ascontiguousarray(_resolve(substrate_ior, "substrate_ior", lam_flat, shape)).ravel()
    thick = np.array([l.thickness_nm for l in ls], dtype=np.float64)
    k = K
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)):
        raise TypeError(f"K: expected an integer number of round trips, got {K!r}")
    return fn(lam_flat, cos_flat, n0_flat, iors, thick, sub, mode, int(k)), shape


def stack_rt(layers, wavelengths_nm, cos_theta, incident_ior=1.0, substrate_ior=1.5, mode: str = "transfer_matrix",
             K: int = 1) -> StackRT:
    """Rs, Rp, Ts, Tp of a stack of layers (top → bottom, each (ior, thickness_nm)) on a substrate,
    lit from a real incident medium at cos θ. Arrays broadcast with each other (wavelengths,
    cos θ, the incident index and array-valued layer or substrate indices). Modes:
    "transfer_matrix" (any number of layers, Born & Wolf §1.6), and for exactly one layer "airy"
    (closed-form coherent sum), "truncated" (K round trips) and "incoherent" (phase-averaged).
    Each value is the C++ function's double result (thinFilmStackRT / singleFilmRT)."""
    out, shape = _stack_call(_iris.film_stack_rt, layers, wavelengths_nm, cos_theta, incident_ior, substrate_ior, mode, K)
    return StackRT(*(out[c].reshape(shape) for c in range(4)))


class StackMueller(NamedTuple):
    """Mueller matrices of a stack's reflection and transmission, shape (..., 4, 4)."""
    R: np.ndarray
    T: np.ndarray


def stack_mueller(layers, wavelengths_nm, cos_theta, incident_ior=1.0, substrate_ior=1.5, mode: str = "transfer_matrix",
                  K: int = 1) -> StackMueller:
    """The Mueller matrices of the stack's reflection and transmission (polarized mode,
    docs/polarization.md), arguments and broadcasting as stack_rt; R and T have shape (..., 4, 4)
    for the broadcast shape (...). Both are in the bases whose reference vector is the s axis
    (normal to the plane of incidence) on both sides, in the interface layout of Mitsuba 3's
    mueller::specular_reflection:
        [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]],
    A = (P_s + P_p)/2, B = (P_s − P_p)/2 (P = R or T of stack_rt), C + iD = r_s r_p* for the
    reflection and √(T_s T_p) t_s t_p*/|t_s t_p*| for the transmission (spectral/thin_film_polarization.h).
    So M @ (1, 0, 0, 0) is (R, (Rs − Rp)/2, 0, 0): unpolarized light's response is stack_rt's R.
    In mode "truncated" the powers are clamped as the materials clamp them (R ≤ 1, T ≤ 1 − R),
    unlike stack_rt's raw sums."""
    out, shape = _stack_call(_iris.film_stack_mueller, layers, wavelengths_nm, cos_theta, incident_ior, substrate_ior, mode, K)
    return StackMueller(out[0].reshape(shape + (4, 4)), out[1].reshape(shape + (4, 4)))


def _broadcast_with_rgb(scalars: dict, rgb_name: str, rgb: np.ndarray):
    """Broadcast named arrays with one of R, G, B values (last dimension 3, or one value for all):
    the flat scalars, the (n, 3) RGB values and the broadcast shape; iris.Error naming them."""
    if rgb.ndim == 0:
        rgb = np.full(3, rgb)
    if rgb.shape[-1] != 3:
        raise _iris.Error(f"{rgb_name}: expected one value or R, G, B values (last dimension 3), got shape {rgb.shape}")
    try:
        shape = np.broadcast_shapes(*(a.shape for a in scalars.values()), rgb.shape[:-1])
    except ValueError:
        raise _iris.Error(f"{', '.join(scalars)} and {rgb_name} do not broadcast together") from None
    flat = [np.ascontiguousarray(np.broadcast_to(x, shape)).ravel() for x in scalars.values()]
    return flat, np.ascontiguousarray(np.broadcast_to(rgb, shape + (3,))).reshape(-1, 3), shape


def belcour_barla_rgb(film_ior, thickness_nm, cos_theta, incident_ior=1.0, substrate_ior=1.5) -> np.ndarray:
    """Belcour & Barla 2017's spectrally integrated RGB (linear Rec.709) reflectance of one
    dielectric film on a base (spectral/belcour_barla.h): shape (..., 3) for the broadcast shape
    of the real arguments. `substrate_ior` is one index for all channels, a name (evaluated at the
    default channel wavelengths) or an array whose last dimension holds R, G, B indices."""
    cos = real_array("cos_theta", cos_theta)
    n0 = real_array("incident_ior", incident_ior)
    eta = real_array("film_ior", film_ior)
    d = real_array("thickness_nm", thickness_nm)
    if isinstance(substrate_ior, str):
        sub = _iris.named_ior(substrate_ior, np.array(_iris.DEFAULT_RGB_WAVELENGTHS, dtype=np.float64))
    else:
        sub = np.asarray(substrate_ior)
        if sub.dtype.kind not in "biufc":
            raise TypeError(f"substrate_ior: expected a number, complex number, array or name, got {type(substrate_ior).__name__}")
        sub = sub.astype(np.complex128)
    flat, sub_flat, shape = _broadcast_with_rgb({"cos_theta": cos, "incident_ior": n0, "film_ior": eta, "thickness_nm": d},
                                                "substrate_ior", sub)
    return _iris.film_belcour_barla(*flat, sub_flat).reshape(shape + (3,))


def khr_iridescence_rgb(film_ior, thickness_nm, cos_theta, base_f0, outside_ior=1.0) -> np.ndarray:
    """KHR_materials_iridescence's iridescent_fresnel as the extension's README writes it (Schlick
    interfaces, phase 0 or π, two harmonics of the Gaussian CIE fit, sRGB matrix;
    spectral/thin_film_industry.h): linear Rec.709, shape (..., 3). `base_f0` is the base's
    normal-incidence reflectance, one value or R, G, B (last dimension 3), in [0, 1)."""
    cos = real_array("cos_theta", cos_theta)
    n0 = real_array("outside_ior", outside_ior)
    eta = real_array("film_ior", film_ior)
    d = real_array("thickness_nm", thickness_nm)
    f0 = real_array("base_f0", base_f0)
    flat, f0_flat, shape = _broadcast_with_rgb({"cos_theta": cos, "outside_ior": n0, "film_ior": eta, "thickness_nm": d},
                                               "base_f0", f0)
    return _iris.thin_film_khr_rgb(*flat, f0_flat).reshape(shape + (3,))


def cycles_4_2_rgb(film_ior, thickness_nm, cos_theta, base_ior=1.5, outside_ior=1.0) -> np.ndarray:
    """Blender Cycles 4.2's thin-film Fresnel (the Principled BSDF's Thin Film) as its source writes
    it (spectral/thin_film_cycles.h): Belcour & Barla with exact polarised dielectric Fresnel terms,
    three harmonics of the Gaussian CIE fit in XYZ, the film index blended towards the outside
    below 30 nm, XYZ multiplied by the Rec.709 white and clamped to [0, 1]. Dielectric bases only:
    `base_ior` is a real index. Linear Rec.709, shape (..., 3) for the broadcast shape."""
    args = {"cos_theta": real_array("cos_theta", cos_theta), "outside_ior": real_array("outside_ior", outside_ior),
            "film_ior": real_array("film_ior", film_ior), "thickness_nm": real_array("thickness_nm", thickness_nm),
            "base_ior": real_array("base_ior", base_ior)}
    try:
        shape = np.broadcast_shapes(*(a.shape for a in args.values()))
    except ValueError:
        raise _iris.Error(f"{', '.join(args)} do not broadcast together") from None
    flat = [np.ascontiguousarray(np.broadcast_to(a, shape)).ravel() for a in args.values()]
    return _iris.thin_film_cycles_4_2_rgb(*flat).reshape(shape + (3,))


def gulbrandsen_ior(reflectivity, edge_tint) -> np.ndarray:
    """Gulbrandsen 2014 ("Artist Friendly Metallic Fresnel", JCGT 3(4)): the complex index n + ik
    of a metal whose normal-incidence reflectivity is `reflectivity` and edge tint `edge_tint`
    (both in [0, 1]; reflectivity is clamped to 0.99, as in spectral/thin_film_industry.h),
    broadcast together."""
    r = real_array("reflectivity", reflectivity)
    g = real_array("edge_tint", edge_tint)
    try:
        shape = np.broadcast_shapes(r.shape, g.shape)
    except ValueError:
        raise _iris.Error("reflectivity and edge_tint do not broadcast together") from None
    flat = [np.ascontiguousarray(np.broadcast_to(x, shape)).ravel() for x in (r, g)]
    return _iris.gulbrandsen_ior(*flat).reshape(shape)
