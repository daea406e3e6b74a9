"""Image grids (matplotlib, Agg backend): rows × columns of renders with labels."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import exr


def srgb_encode(linear: np.ndarray) -> np.ndarray:
    """Display encoding for figures: clamp to [0,1], sRGB OETF (IEC 61966-2-1)."""
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def display_image(path: Path, exposure: float = 0.0) -> np.ndarray:
    """An EXR for display: the renderer's PNG beside it when present (its OCIO display transform),
    else the EXR's linear Rec.709 values clamped and sRGB-encoded (with exposure in stops)."""
    path = Path(path)
    png = path.with_suffix(".png")
    if png.exists() and exposure == 0.0:
        import matplotlib.image as mpimg
        return np.asarray(mpimg.imread(str(png)))[:, :, :3]
    pixels, names, _ = exr.read_exr(str(path))
    return srgb_encode(exr.rgb_of(pixels, names) * 2.0 ** exposure)


def image_grid(cells, out_png: Path, row_labels=(), col_labels=(), title: str = "", cell_inches: float = 1.8,
               exposure: float = 0.0) -> Path:
    """cells: list of rows, each a list of EXR paths (None = empty cell). A .jpg output (quality 85)
    keeps grids of noisy renders small enough to commit; .png is lossless."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    nrows, ncols = len(cells), max(len(r) for r in cells)
    fig, axes = plt.subplots(nrows, ncols, figsize=(cell_inches * ncols + 0.8, cell_inches * nrows + 0.6),
                             squeeze=False)
    for i in range(nrows):
        for j in range(ncols):
            ax = axes[i][j]
            ax.set_xticks([])
            ax.set_yticks([])
            path = cells[i][j] if j < len(cells[i]) else None
            if path is not None and Path(path).exists():
                ax.imshow(display_image(path, exposure), interpolation="nearest")
            else:
                ax.text(0.5, 0.5, "missing", ha="center", va="center", transform=ax.transAxes, fontsize=8)
            if i == 0 and j < len(col_labels):
                ax.set_title(str(col_labels[j]), fontsize=8)
            if j == 0 and i < len(row_labels):
                ax.set_ylabel(str(row_labels[i]), fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    out_png = Path(out_png)
    out_png.parent.mkdir(parents=True, exist_ok=True)
    if out_png.suffix.lower() in (".jpg", ".jpeg"):
        fig.savefig(out_png, dpi=100, pil_kwargs={"quality": 85})
    else:
        fig.savefig(out_png, dpi=100)
    plt.close(fig)
    return out_png


def line_plot(series, out_png: Path, xlabel: str, ylabel: str, title: str = "", logx=False, logy=False) -> Path:
    """series: {label: (xs, ys)}."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.5))
    for label, (xs, ys) in series.items():
        ax.plot(xs, ys, marker="o", label=str(label))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if logx:
        ax.set_xscale("log", base=2)
    if logy:
        ax.set_yscale("log")
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out_png = Path(out_png)
    out_png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out_png, dpi=100)
    plt.close(fig)
    return out_png
