"""Reading the header and sample counts of an iris film state (render --checkpoint FILE), to tell
finished shards of a split render from interrupted or missing ones without loading the sums.

Layout (render/film.cpp, version 4): 8-byte magic "IRISCKP4", uint64 header length, header text
(line 1: settings key, line 2: "samples=A:B"), int32 width, int32 height, 3·w·h int128 sums,
3·w·h float64 sums of squares, w·h uint32 sample counts, uint32 CRC-32 (zlib) of all bytes
before it; little-endian.
"""
from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

MAGIC = b"IRISCKP4"


@dataclass
class FilmState:
    path: Path
    key: str
    begin: int
    end: int | None          # None: rendered with a time limit
    width: int
    height: int
    min_count: int
    max_count: int

    @property
    def complete(self) -> bool:
        return self.end is not None and self.min_count == self.max_count == self.end - self.begin


def read_film_state(path) -> FilmState:
    """Header and counts of a film state; ValueError naming the file if it is not a whole one."""
    path = Path(path)
    data = path.read_bytes()
    if data[:8] != MAGIC or len(data) < 16:
        raise ValueError(f"{path}: not an iris film state (version 4)")
    (hlen,) = struct.unpack_from("<Q", data, 8)
    header = data[16:16 + hlen].decode()
    width, height = struct.unpack_from("<ii", data, 16 + hlen)
    pixels = width * height
    body = 16 + hlen + 8
    expected = body + pixels * (3 * 16 + 3 * 8 + 4) + 4
    if width <= 0 or height <= 0 or len(data) != expected:
        raise ValueError(f"{path}: film state is truncated or has trailing data ({len(data)} bytes, expected {expected})")
    if zlib.crc32(data[:-4]) != struct.unpack_from("<I", data, len(data) - 4)[0]:
        raise ValueError(f"{path}: film state is corrupted (CRC-32 mismatch)")
    counts = np.frombuffer(data, dtype="<u4", count=pixels, offset=expected - 4 - 4 * pixels)
    key, _, rng = header.partition("\n")
    if not rng.startswith("samples=") or ":" not in rng:
        raise ValueError(f"{path}: film state records no sample range")
    a, _, b = rng[len("samples="):].partition(":")
    return FilmState(path, key, int(a), int(b) if b else None, width, height, int(counts.min()), int(counts.max()))
