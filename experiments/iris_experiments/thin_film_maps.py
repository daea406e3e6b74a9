"""BRDF-level maps for experiments/industry_thin_film.py: the RGB colour of a thin film's Fresnel
reflectance over film thickness × angle, from exact per-wavelength interference (the reference)
and from the RGB approximations, and their CIEDE2000 and relative luminance errors.

The reference is the film's unpolarised Airy reflectance R(λ) (iris.thin_film.stack_rt, mode "airy")
seen under D65, XYZ = Σ R·D65·cmf / Σ D65·ȳ, in linear Rec.709 (iris.color.xyz_to): the colour a
white (D65) light gives in iris's spectral renders. Metallic bases are complex indices by
Gulbrandsen 2014 from the upsampled base colour (edge tint = the colour), as gltf_pbr does."""
from __future__ import annotations

import numpy as np

REC709_Y = np.array([0.2126, 0.7152, 0.0722])
CHANNELS_NM = (645.0, 525.0, 445.0)


def substrate(iris, base, lam):
    """Complex index per wavelength: a real index (dielectric) or Gulbrandsen's from the colour."""
    kind, value = base
    if kind == "dielectric":
        return np.full(np.shape(lam), complex(value))
    r = np.clip(iris.color.rgb_to_spectrum(value)(lam), 0.0, 0.99)
    return iris.thin_film.gulbrandsen_ior(r, r)


def exact_rgb(iris, base, film_ior, thickness, cos, lam):
    """(T, A, 3) linear Rec.709 of the exact film under D65."""
    w = iris.color.d65(lam)[:, None] * iris.color.xyz_bar(lam)
    norm = float(np.sum(iris.color.d65(lam) * iris.color.xyz_bar(lam)[:, 1]))
    sub = substrate(iris, base, lam)
    out = np.zeros((len(thickness), len(cos), 3))
    for i, d in enumerate(thickness):
        r = iris.thin_film.stack_rt([(film_ior, float(d))], lam[None, :], cos[:, None], 1.0, sub[None, :], mode="airy")
        R = 0.5 * (r.Rs + r.Rp)                           # (A, L) unpolarised
        out[i] = iris.color.xyz_to((R @ w) / norm)
    return out


def point_rgb(iris, base, film_ior, thickness, cos):
    """iris's RGB mode ("point"): the exact film at the three channel wavelengths."""
    lam = np.array(CHANNELS_NM)
    sub = substrate(iris, base, lam) if base[0] == "dielectric" else iris.thin_film.gulbrandsen_ior(
        np.clip(np.array(base[1]), 0, 0.99), np.clip(np.array(base[1]), 0, 0.99))
    out = np.zeros((len(thickness), len(cos), 3))
    for i, d in enumerate(thickness):
        r = iris.thin_film.stack_rt([(film_ior, float(d))], lam[None, :], cos[:, None], 1.0, sub[None, :], mode="airy")
        out[i] = 0.5 * (r.Rs + r.Rp)
    return out


def khr_rgb(iris, base, film_ior, thickness, cos):
    """KHR_materials_iridescence's iridescent_fresnel as written (base F0 = 0.04 or the colour)."""
    f0 = np.full(3, ((base[1] - 1) / (base[1] + 1)) ** 2) if base[0] == "dielectric" else np.array(base[1])
    return iris.thin_film.khr_iridescence_rgb(film_ior, thickness[:, None], cos[None, :], np.minimum(f0, 0.999))


def belcour_barla_rgb(iris, base, film_ior, thickness, cos):
    """Belcour & Barla 2017 with exact Fresnel terms (iris's belcour_barla, the form OpenPBR's
    specification recommends); metals as Gulbrandsen indices of the channel colours."""
    if base[0] == "dielectric":
        sub = complex(base[1])
    else:
        c = np.clip(np.array(base[1]), 0, 0.99)
        sub = iris.thin_film.gulbrandsen_ior(c, c)
    return iris.thin_film.belcour_barla_rgb(film_ior, thickness[:, None], cos[None, :], 1.0, sub)


def cycles_4_2_rgb(iris, base, film_ior, thickness, cos):
    """Blender Cycles 4.2's thin film as its source writes it (spectral/thin_film_cycles.h). It has
    no film on metals: None for a metallic base (the model does not apply)."""
    if base[0] != "dielectric":
        return None
    return iris.thin_film.cycles_4_2_rgb(film_ior, thickness[:, None], cos[None, :], base[1])


MODELS = {"khr_iridescence": khr_rgb, "belcour_barla": belcour_barla_rgb, "cycles_4_2": cycles_4_2_rgb, "point": point_rgb}


def errors(iris, test, ref):
    """ΔE00 and relative luminance error maps of test against ref (both (..., 3))."""
    de = iris.color.delta_e2000(np.maximum(test, 0.0), np.maximum(ref, 0.0))
    y_t, y_r = test @ REC709_Y, ref @ REC709_Y
    rel = np.abs(y_t - y_r) / np.maximum(y_r, 1e-4)
    return de, rel
