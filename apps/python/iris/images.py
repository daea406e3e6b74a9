"""OpenEXR files: the renderer's own writer and reader (core/io/image.h)."""
from __future__ import annotations

import os

import numpy as np

from . import _iris


def write(path, image, metadata: dict | None = None, channels: list | None = None) -> None:
    """Write `image` ((H, W) or (H, W, C) floats, stored as float32) to an EXR file, with
    `metadata` (str → str) as header attributes and optional channel names (default R, G, B, ...)."""
    a = np.asarray(image)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"image: expected real numbers, got an array of dtype {a.dtype}")
    if a.ndim not in (2, 3):
        raise _iris.Error(f"image: expected shape (H, W) or (H, W, C), got {a.shape}")
    meta = [(str(k), str(v)) for k, v in (metadata or {}).items()]
    _iris.write_exr(os.fspath(path), a, meta, list(channels or []))


def read(path, with_channel_names: bool = False):
    """(pixels (H, W, C) float32, metadata dict) of an image file (EXR through OpenEXR, other
    formats through OpenImageIO); with `with_channel_names`, also the list of channel names."""
    pixels, meta, names = _iris.read_exr(os.fspath(path))
    return (pixels, meta, names) if with_channel_names else (pixels, meta)
