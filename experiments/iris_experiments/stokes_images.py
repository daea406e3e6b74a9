"""Stokes images of polarized renders (docs/polarization.md): the S0-S3 channels the `stokes`
integrator writes (S0.R ... S3.B), checked against a camera behind a linear polarizer, and shown
with a diverging colour map.

Behind an ideal linear polarizer whose axis is the Stokes basis vector (0°) or normal to it (90°),
the camera sees I(0) = (S0 + S1)/2 and I(90) = (S0 - S1)/2 (Collett, "Field Guide to
Polarization", ch. 5; Malus's law), so S1 = I(0) - I(90) and S0 = I(0) + I(90). Unpolarized
transport renders I(0) = I(90) = S0/2: its S1 is 0 everywhere."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import exr


def stokes_of(path: Path) -> np.ndarray:
    """(4, H, W): S0..S3 of a `stokes` render, each the mean of its R, G, B channels."""
    pixels, names, _ = exr.read_exr(str(path))
    missing = [f"S{k}.{c}" for k in range(4) for c in "RGB" if f"S{k}.{c}" not in names]
    if missing:
        raise ValueError(f"{path}: no Stokes channels {', '.join(missing)} (render it with the stokes integrator)")
    return np.stack([np.mean([pixels[:, :, names.index(f"S{k}.{c}")] for c in "RGB"], axis=0) for k in range(4)])


def grey_of(path: Path) -> np.ndarray:
    """(H, W): the mean of an image's colour channels."""
    pixels, names, _ = exr.read_exr(str(path))
    return exr.rgb_of(pixels, names).mean(axis=-1)


def s1_metrics(stokes: np.ndarray, i0: np.ndarray, i90: np.ndarray) -> dict:
    """How polarized the image is, and whether the polarizer pair agrees with the Stokes channels:
    abs_s1_over_s0 = mean |S1| / mean S0 (the share of the image unpolarized transport cannot
    see behind the polarizer), dolp_mean = mean sqrt(S1² + S2²) / mean S0, and of the pair
    S1 = I(0) - I(90): its mean against S1's, its relative L2 distance (noise included) and its
    pixel correlation with S1."""
    s0, s1, s2 = stokes[0], stokes[1], stokes[2]
    pair = i0 - i90
    m0 = float(np.mean(s0))
    corr = float(np.corrcoef(pair.ravel(), s1.ravel())[0, 1]) if np.std(pair) > 0 and np.std(s1) > 0 else float("nan")
    return {"s0_mean": m0, "s1_mean": float(np.mean(s1)),
            "abs_s1_over_s0": float(np.mean(np.abs(s1))) / m0 if m0 > 0 else float("nan"),
            "dolp_mean": float(np.mean(np.hypot(s1, s2))) / m0 if m0 > 0 else float("nan"),
            "pair_s0_mean": float(np.mean(i0 + i90)), "pair_s1_mean": float(np.mean(pair)),
            "pair_s1_rel_l2": float(np.sqrt(np.mean((pair - s1) ** 2) / np.mean(s1 ** 2))) if np.any(s1) else float("nan"),
            "pair_s1_corr": corr}


def s1_figure(panels, out_png: Path, title: str = "") -> Path:
    """panels: [(label, (H, W) array)], the first one S0 (grey scale), the others signed S1-like
    images on one symmetric diverging scale (red: along the basis vector, blue: normal to it)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    signed = [a for _, a in panels[1:]]
    scale = max(float(np.percentile(np.abs(a), 99)) for a in signed) or 1.0
    fig, axes = plt.subplots(1, len(panels), figsize=(2.3 * len(panels) + 0.8, 2.7), squeeze=False)
    for i, (ax, (label, image)) in enumerate(zip(axes[0], panels)):
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(label, fontsize=8)
        if i == 0:
            ax.imshow(np.clip(image / max(float(np.percentile(image, 99)), 1e-9), 0, 1), cmap="gray", interpolation="nearest")
        else:
            im = ax.imshow(image, cmap="RdBu_r", vmin=-scale, vmax=scale, interpolation="nearest")
    fig.colorbar(im, ax=list(axes[0][1:]), shrink=0.8)
    if title:
        fig.suptitle(title, fontsize=9)
    out_png = Path(out_png)
    out_png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out_png, dpi=100)
    plt.close(fig)
    return out_png
