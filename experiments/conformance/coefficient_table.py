#!/usr/bin/env python3
"""How far interpolating sigmoid coefficients moves a colour (docs/conformance.md, the
homo_emitter_inside_medium exception).

iris turns a reflectance RGB into the sigmoid spectrum whose RGB is exactly that colour (its own
Levenberg-Marquardt fit, spectral/rgb_spectrum.h). Mitsuba 3 looks the coefficients up in a table
of Jakob & Hanika 2019 (rgb2spec: 3 × 64³ entries, indexed by the largest channel, that channel's
value on the grid smoothstep(smoothstep(k/63)), and the other two relative to it) and interpolates
the *coefficients* trilinearly. This script builds such a table's nodes with iris's own exact fits
(Mitsuba's table is generated when Mitsuba is compiled and is not available here) and reports, for
a few colours, the RGB of the interpolated spectrum and its mean absorption 1 − s(λ) over
380–780 nm against the exact fit's.

    PYTHONPATH=build/python /usr/bin/python3 experiments/conformance/coefficient_table.py [r,g,b ...]
"""
from __future__ import annotations

import sys
from functools import lru_cache

import numpy as np

from iris import _iris

RES = 64
DEFAULT_COLOURS = [(0.99, 0.99, 0.999), (0.99, 0.7, 0.99), (0.99, 0.5, 0.5), (0.99, 0.7, 0.7)]


def _smoothstep(x: float) -> float:
    return x * x * (3 - 2 * x)


SCALE = np.array([_smoothstep(_smoothstep(k / (RES - 1))) for k in range(RES)])


@lru_cache(maxsize=None)
def exact_coefficients(rgb: tuple[float, float, float]) -> np.ndarray:
    return np.array(_iris.fit_rgb([float(c) for c in rgb])[0])


def node_colour(i: int, zi: int, yi: int, xi: int) -> tuple[float, float, float]:
    """The colour at table node (largest channel i, its value index zi, the others' xi, yi)."""
    z = SCALE[zi]
    c = [0.0, 0.0, 0.0]
    c[i], c[(i + 1) % 3], c[(i + 2) % 3] = z, xi / (RES - 1) * z, yi / (RES - 1) * z
    return tuple(round(v, 7) for v in c)


def table_coefficients(rgb) -> np.ndarray:
    """Trilinear interpolation of the node coefficients, indexed as rgb2spec_fetch does (ties of
    the largest channel go to the later one)."""
    i = 0
    for j in (1, 2):
        if rgb[j] >= rgb[i]:
            i = j
    z = rgb[i]
    x, y = rgb[(i + 1) % 3] * (RES - 1) / z, rgb[(i + 2) % 3] * (RES - 1) / z
    xi, yi = min(int(x), RES - 2), min(int(y), RES - 2)
    zi = int(np.clip(np.searchsorted(SCALE, z, side="right") - 1, 0, RES - 2))
    fx, fy, fz = x - xi, y - yi, (z - SCALE[zi]) / (SCALE[zi + 1] - SCALE[zi])
    out = np.zeros(3)
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                w = (fx if dx else 1 - fx) * (fy if dy else 1 - fy) * (fz if dz else 1 - fz)
                if w:
                    out += w * exact_coefficients(node_colour(i, zi + dz, yi + dy, xi + dx))
    return out


def main(argv: list[str]) -> int:
    colours = [tuple(float(v) for v in a.split(",")) for a in argv] or DEFAULT_COLOURS
    lam = np.linspace(380.0, 780.0, 81)
    print("colour | RGB of the interpolated coefficients | mean 1 - s(λ), exact fit | mean 1 - s(λ), interpolated")
    for rgb in colours:
        exact = exact_coefficients(tuple(rgb))
        table = table_coefficients(rgb)
        s_exact = np.array(_iris.eval_sigmoid(list(map(float, exact)), lam))
        s_table = np.array(_iris.eval_sigmoid(list(map(float, table)), lam))
        got = np.array(_iris.sigmoid_rgb(list(map(float, table))))
        print(f"{rgb} | {np.round(got, 4).tolist()} | {np.mean(1 - s_exact):.5f} | {np.mean(1 - s_table):.5f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
