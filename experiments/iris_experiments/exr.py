"""Minimal OpenEXR reader/writer in pure Python + numpy (no OpenEXR bindings on Debian 12).

Reads single-part scanline files with NO, ZIPS or ZIP compression and HALF/FLOAT/UINT channels
(what iris writes: FLOAT + ZIP); writes uncompressed FLOAT files with string metadata (used by the
fake renderer in tests). Format: OpenEXR file layout (openexr.com, "OpenEXR File Layout").
"""
from __future__ import annotations

import os
import struct
import zlib

import numpy as np

MAGIC = 20000630
_PIXEL_TYPES = {0: np.dtype("<u4"), 1: np.dtype("<f2"), 2: np.dtype("<f4")}
_LINES_PER_BLOCK = {0: 1, 2: 1, 3: 16}  # NO_COMPRESSION, ZIPS_COMPRESSION, ZIP_COMPRESSION


class ExrError(Exception):
    """A file that this reader cannot read (message names the file)."""


def _attr(name: str, type_name: str, payload: bytes) -> bytes:
    return name.encode() + b"\0" + type_name.encode() + b"\0" + struct.pack("<i", len(payload)) + payload


def write_exr(path: str, pixels: np.ndarray, channels=("R", "G", "B"), metadata: dict | None = None) -> None:
    """Write an H x W x C float array as an uncompressed FLOAT EXR with string attributes.

    Written to "<path>.tmp-<pid>" and renamed over path, like the C++ writer."""
    pixels = np.asarray(pixels, dtype="<f4")
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    height, width, nch = pixels.shape
    if len(channels) != nch:
        raise ValueError(f"{path}: {nch} channels but {len(channels)} names")
    order = sorted(range(nch), key=lambda c: channels[c])  # EXR stores channels sorted by name
    chlist = b"".join(channels[c].encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in order) + b"\0"
    header = struct.pack("<ii", MAGIC, 2)
    header += _attr("channels", "chlist", chlist)
    header += _attr("compression", "compression", b"\0")
    header += _attr("dataWindow", "box2i", struct.pack("<iiii", 0, 0, width - 1, height - 1))
    header += _attr("displayWindow", "box2i", struct.pack("<iiii", 0, 0, width - 1, height - 1))
    header += _attr("lineOrder", "lineOrder", b"\0")
    header += _attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += _attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
    header += _attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
    for key, value in (metadata or {}).items():
        header += _attr(str(key), "string", str(value).encode())
    header += b"\0"
    line_bytes = width * nch * 4
    first = len(header) + 8 * height
    offsets = [first + y * (8 + line_bytes) for y in range(height)]
    tmp = f"{path}.tmp-{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(header)
        f.write(struct.pack(f"<{height}Q", *offsets))
        for y in range(height):
            f.write(struct.pack("<ii", y, line_bytes))
            f.write(np.ascontiguousarray(pixels[y][:, order].T).tobytes())
    os.replace(tmp, path)


def _read_header(data: bytes, path: str):
    if len(data) < 8 or struct.unpack_from("<i", data, 0)[0] != MAGIC:
        raise ExrError(f"{path}: not an OpenEXR file")
    version = struct.unpack_from("<i", data, 4)[0]
    if version & 0x200 or version & 0x1000 or version & 0x800:
        raise ExrError(f"{path}: tiled, deep or multi-part EXR files are not supported")
    pos, attrs = 8, {}
    while True:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        pos = end + 1
        if not name:
            break
        end = data.index(b"\0", pos)
        type_name = data[pos:end].decode()
        size = struct.unpack_from("<i", data, end + 1)[0]
        pos = end + 5
        attrs[name] = (type_name, data[pos:pos + size])
        pos += size
    return attrs, pos


def read_exr(path: str):
    """Return (pixels H x W x C float32, channel names, string metadata dict)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise ExrError(f"{path}: {e.strerror}") from e
    try:
        attrs, pos = _read_header(data, path)
        chl = attrs["channels"][1]
        names, types, p = [], [], 0
        while chl[p] != 0:
            end = chl.index(b"\0", p)
            names.append(chl[p:end].decode())
            types.append(_PIXEL_TYPES[struct.unpack_from("<i", chl, end + 1)[0]])
            p = end + 1 + 16
        comp = attrs["compression"][1][0]
        if comp not in _LINES_PER_BLOCK:
            raise ExrError(f"{path}: unsupported EXR compression {comp}")
        xmin, ymin, xmax, ymax = struct.unpack("<iiii", attrs["dataWindow"][1])
        width, height = xmax - xmin + 1, ymax - ymin + 1
        lines = _LINES_PER_BLOCK[comp]
        nblocks = (height + lines - 1) // lines
        offsets = struct.unpack_from(f"<{nblocks}Q", data, pos)
        out = np.zeros((height, width, len(names)), dtype=np.float32)
        for offset in offsets:
            y, size = struct.unpack_from("<ii", data, offset)
            raw = data[offset + 8: offset + 8 + size]
            if len(raw) != size:
                raise ExrError(f"{path}: truncated pixel data")
            nl = min(lines, ymax + 1 - y)
            expected = sum(t.itemsize for t in types) * width * nl
            if comp != 0 and size < expected:
                raw = _unzip(raw)
            if len(raw) != expected:
                raise ExrError(f"{path}: corrupt block at line {y}")
            p = 0
            for line in range(nl):
                for c, t in enumerate(types):
                    n = width * t.itemsize
                    out[y - ymin + line, :, c] = np.frombuffer(raw, dtype=t, count=width, offset=p)
                    p += n
        meta = {k: v[1].decode("utf-8", "replace") for k, v in attrs.items() if v[0] == "string"}
        return out, names, meta
    except ExrError:
        raise
    except (KeyError, IndexError, ValueError, struct.error, zlib.error) as e:
        raise ExrError(f"{path}: corrupt or truncated EXR ({e})") from e


def _header_attributes(path: str) -> dict:
    """The attributes of an EXR header, read from the file's first MiB."""
    try:
        with open(path, "rb") as f:
            data = f.read(1 << 20)
    except OSError as e:
        raise ExrError(f"{path}: {e.strerror}") from e
    try:
        attrs, _ = _read_header(data, path)
    except (IndexError, ValueError, struct.error) as e:
        raise ExrError(f"{path}: corrupt EXR header ({e})") from e
    return attrs


def read_exr_metadata(path: str) -> dict:
    """String attributes of an EXR header."""
    return {k: v[1].decode("utf-8", "replace") for k, v in _header_attributes(path).items() if v[0] == "string"}


def exr_size(path: str) -> tuple[int, int]:
    """(width, height) of an EXR's data window, from its header alone."""
    window = _header_attributes(path).get("dataWindow")
    if window is None or len(window[1]) != 16:
        raise ExrError(f"{path}: no data window in the EXR header")
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", window[1])
    return xmax - xmin + 1, ymax - ymin + 1


def _unzip(raw: bytes) -> bytes:
    """Undo EXR ZIP: zlib, then the byte predictor, then the two-halves interleave."""
    t = np.frombuffer(zlib.decompress(raw), dtype=np.uint8).astype(np.int64)
    if t.size == 0:
        return b""
    t[1:] -= 128
    t = (np.cumsum(t) & 0xFF).astype(np.uint8)
    half = (t.size + 1) // 2
    out = np.empty_like(t)
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def rgb_of(pixels: np.ndarray, names) -> np.ndarray:
    """H x W x 3 colour image from named channels (R,G,B, else the first channel as grey)."""
    if all(c in names for c in ("R", "G", "B")):
        return np.stack([pixels[:, :, names.index(c)] for c in ("R", "G", "B")], axis=-1)
    return np.repeat(pixels[:, :, :1], 3, axis=-1)
