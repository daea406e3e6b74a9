#!/usr/bin/env python3
"""Write the glTF test assets of tests/data/gltf/ (docs/gltf.md, "Test assets").

Every file is made here from code: meshes (quads, boxes, UV spheres), tiny PNGs, the materials of
each Khronos extension iris reads, normal-mapped assets (one with mirrored UVs), a KHR_materials_volume slab, the iridescent sphere grids of experiments/industry_thin_film.py
(after Khronos's IridescenceDielectricSpheres / IridescenceMetallicSpheres sample models, which
sweep film thickness and IOR), and hostile files for the importer's error tests. Valid files pass
the Khronos glTF-Validator (tests/gltf/validate.mjs); hostile ones are named bad_*.

    python3 tests/gltf/make_assets.py [OUT_DIR]      # default tests/data/gltf
"""
import base64
import json
import math
import struct
import sys
import zlib
from pathlib import Path


class Builder:
    """A glTF document and its one binary buffer, grown accessor by accessor."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "iris tests/gltf/make_assets.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": [], "buffers": []}
        self.bin = bytearray()
        self.used = set()
        self.shared = {}

    def view(self, data: bytes, target=None) -> int:
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.bin += data
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def floats(self, rows, kind: str) -> int:
        flat = [x for r in rows for x in r]
        view = self.view(struct.pack(f"<{len(flat)}f", *flat), 34962)
        acc = {"bufferView": view, "componentType": 5126, "count": len(rows), "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(r[i] for r in rows) for i in range(3)]
            acc["max"] = [max(r[i] for r in rows) for i in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def indices(self, idx) -> int:
        view = self.view(struct.pack(f"<{len(idx)}I", *idx), 34963)
        self.doc["accessors"].append({"bufferView": view, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        return len(self.doc["accessors"]) - 1

    def mesh(self, geom, material=None, mode=None, extra=None) -> int:
        pos, nrm, uv, idx = geom
        key = id(geom)
        if key not in self.shared:  # meshes of one geometry share its accessors
            self.shared[key] = (geom, {"POSITION": self.floats(pos, "VEC3"), "NORMAL": self.floats(nrm, "VEC3"),
                                 "TEXCOORD_0": self.floats(uv, "VEC2")}, self.indices(idx) if idx is not None else None)
        attrs, indices = dict(self.shared[key][1]), self.shared[key][2]  # [0] keeps geom alive, so its id stays unique
        attrs.update(extra or {})
        prim = {"attributes": attrs}
        if indices is not None:
            prim["indices"] = indices
        if material is not None:
            prim["material"] = material
        if mode is not None:
            prim["mode"] = mode
        self.doc["meshes"].append({"primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def material(self, m: dict) -> int:
        for name in m.get("extensions", {}):
            self.used.add(name)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def node(self, n: dict, root=True) -> int:
        self.doc["nodes"].append(n)
        i = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(i)
        return i

    def camera(self, translation, yfov=0.7, aspect=1.0, name="main"):
        self.doc.setdefault("cameras", []).append({"type": "perspective", "name": name,
                                                   "perspective": {"yfov": yfov, "aspectRatio": aspect, "znear": 0.01}})
        return self.node({"camera": len(self.doc["cameras"]) - 1, "translation": translation, "name": name + "_node"})

    def light(self, light: dict, node: dict):
        self.used.add("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(light)
        node = dict(node, extensions={"KHR_lights_punctual": {"light": len(lights) - 1}})
        return self.node(node)

    def finish(self):
        if self.used:
            self.doc["extensionsUsed"] = sorted(self.used)
        for k in [k for k, v in self.doc.items() if v == []]:
            del self.doc[k]

    def write_gltf(self, path: Path, embed=True):
        self.finish()
        if embed:
            uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
        else:
            uri = path.stem + ".bin"
            (path.parent / uri).write_bytes(bytes(self.bin))
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
        path.write_text(json.dumps(self.doc, indent=1) + "\n")

    def write_glb(self, path: Path):
        self.finish()
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        js = json.dumps(self.doc).encode()
        js += b" " * (-len(js) % 4)
        binary = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        total = 12 + 8 + len(js) + 8 + len(binary)
        path.write_bytes(struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<I4s", len(js), b"JSON") + js +
                         struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def quad(size=1.0, y=0.0):
    """A square in the xz plane facing +y (two triangles)."""
    s = size
    pos = [(-s, y, -s), (s, y, -s), (s, y, s), (-s, y, s)]
    return pos, [(0, 1, 0)] * 4, [(0, 0), (1, 0), (1, 1), (0, 1)], [0, 2, 1, 0, 3, 2]


def sphere(radius=1.0, rings=24, segments=48):
    pos, nrm, uv, idx = [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            pos.append(tuple(radius * c for c in n))
            nrm.append(n)
            uv.append((j / segments, i / rings))
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, uv, idx


def box(lo, hi):
    """A closed box, 4 vertices per face, faces wound counter-clockwise seen from outside (§3.7.2.1)."""
    c = [(lo[i] + hi[i]) / 2 for i in range(3)]
    r = [(hi[i] - lo[i]) / 2 for i in range(3)]
    pos, nrm, uv, idx = [], [], [], []
    # (normal axis, sign, a axis, b axis) with a × b = the outward normal
    for axis, sign, a, b in [(0, 1, 1, 2), (0, -1, 2, 1), (1, 1, 2, 0), (1, -1, 0, 2), (2, 1, 0, 1), (2, -1, 1, 0)]:
        base = len(pos)
        for sa, sb in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
            p = list(c)
            p[axis] += sign * r[axis]
            p[a] += sa * r[a]
            p[b] += sb * r[b]
            pos.append(tuple(p))
            n = [0.0, 0.0, 0.0]
            n[axis] = float(sign)
            nrm.append(tuple(n))
            uv.append(((sa + 1) / 2, (sb + 1) / 2))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def png(width, height, rgba_rows) -> bytes:
    """An 8-bit RGBA PNG (ISO/IEC 15948: signature, IHDR, one IDAT, IEND)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(row) for row in rgba_rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def basic(b: Builder):
    floor = b.material({"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0.0}})
    ball = b.material({"name": "ball", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.2, 0.1, 1], "metallicFactor": 0.0,
                                                               "roughnessFactor": 0.4}})
    b.node({"mesh": b.mesh(quad(3.0), floor), "name": "floor"})
    b.node({"mesh": b.mesh(sphere(1.0), ball), "translation": [0, 1, 0], "name": "ball"})
    b.camera([0, 1.5, 6], yfov=0.8, aspect=1.5)
    b.light({"type": "point", "color": [1, 1, 1], "intensity": 20}, {"translation": [2, 4, 2]})
    b.light({"type": "directional", "intensity": 1}, {"rotation": [-0.3826834, 0, 0, 0.9238795]})


def instanced(b: Builder):
    m = b.mesh(sphere(0.5, 12, 24), b.material({"pbrMetallicRoughness": {"metallicFactor": 0.0}}))
    parent = b.node({"translation": [0, 0.5, 0], "children": []})
    for i, x in enumerate((-1.5, 0.0, 1.5)):
        c = b.node({"mesh": m, "translation": [x, 0, 0], "scale": [1, 1 + 0.5 * i, 1]}, root=False)
        b.doc["nodes"][parent]["children"].append(c)
    b.node({"mesh": m, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1]})
    b.camera([0, 1, 6])


def strips_fans(b: Builder):
    mat = b.material({"pbrMetallicRoughness": {"metallicFactor": 0.0}})
    pos, nrm, uv, _ = quad(1.0)
    b.node({"mesh": b.mesh((pos, nrm, uv, [0, 3, 1, 2]), mat, mode=5), "translation": [-1.2, 0, 0]})  # strip
    b.node({"mesh": b.mesh((pos, nrm, uv, [0, 3, 2, 1]), mat, mode=6), "translation": [1.2, 0, 0]})   # fan
    b.camera([0, 4, 0.01], yfov=1.0)


def textured(b: Builder):
    rows = [[255, 0, 0, 255, 0, 0, 255, 40], [0, 255, 0, 255, 255, 255, 255, 255]]
    data = png(2, 2, rows)
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(data).decode()}]
    b.doc["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}]
    b.used.add("KHR_texture_transform")
    mat = b.material({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
        "KHR_texture_transform": {"offset": [0.0, 0.0], "scale": [2.0, 2.0], "rotation": 0.0}}}, "metallicFactor": 0.0},
        "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True})
    b.node({"mesh": b.mesh(quad(1.0), mat)})
    b.camera([0, 3, 0.01], yfov=0.9)


def extensions(b: Builder):
    """One sphere per extension, in a row; each material uses only its extension."""
    mats = [
        {"name": "ior", "extensions": {"KHR_materials_ior": {"ior": 1.8}}},
        {"name": "specular", "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.2]}}},
        {"name": "transmission", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.8}}},
        {"name": "clearcoat", "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}}},
        {"name": "sheen", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.3, 0.6], "sheenRoughnessFactor": 0.5}}},
        {"name": "iridescence", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.8,
                                                                             "iridescenceThicknessMaximum": 500}}},
        {"name": "emissive", "emissiveFactor": [1, 0.8, 0.6], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}},
    ]
    for i, m in enumerate(mats):
        m.setdefault("pbrMetallicRoughness", {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0.0, "roughnessFactor": 0.3})
        b.node({"mesh": b.mesh(sphere(0.45, 12, 24), b.material(m)), "translation": [i - 3.0, 0, 0], "name": m["name"]})
    b.camera([0, 0, 9], yfov=0.8, aspect=2.0)
    b.light({"type": "directional", "intensity": 2}, {"rotation": [-0.3826834, 0, 0, 0.9238795]})


# volume_slab.gltf: KHR_materials_volume's slab seen at normal incidence against an emitting quad.
SLAB_THICKNESS = 0.5
SLAB_VOLUME = {"thicknessFactor": SLAB_THICKNESS, "attenuationDistance": 1.0, "attenuationColor": [0.8, 0.5, 0.2]}


def volume_slab(b: Builder):
    """A glass slab (ior 1.5, smooth, clear base) of thickness SLAB_THICKNESS along z bounding an
    absorbing volume, in front of a black emitting quad (radiance 1, no specular reflection), seen
    along −z by a camera of 0.02 rad field of view: every camera ray crosses the slab at normal
    incidence (tests/render/test_gltf_volume.cpp's closed form)."""
    glass = b.material({"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0,
                                                                  "roughnessFactor": 0.0},
                        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                       "KHR_materials_ior": {"ior": 1.5}, "KHR_materials_volume": dict(SLAB_VOLUME)}})
    lamp = b.material({"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                       "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
    h = SLAB_THICKNESS / 2
    b.node({"mesh": b.mesh(box((-2, -2, -h), (2, 2, h)), glass), "name": "slab"})
    pos = [(-4, -4, -1), (4, -4, -1), (4, 4, -1), (-4, 4, -1)]
    b.node({"mesh": b.mesh((pos, [(0, 0, 1)] * 4, [(0, 0), (1, 0), (1, 1), (0, 1)], [0, 1, 2, 0, 2, 3]), lamp), "name": "lamp"})
    b.camera([0, 0, 5], yfov=0.02)


# normal_mapped.gltf: the one texel of its normal texture (8-bit RGBA, linear) and the scale.
NORMAL_TEXEL = [191, 90, 223, 255]
NORMAL_SCALE = 0.5


def normal_mapped(b: Builder):
    """Two flat quads facing +y with one constant normal texture: the left one with a TANGENT
    attribute (0, 0, 1, w = −1) and turned 90° about y, the middle one without (tangents from its UVs); a third, with the
    normal texture at scale 0, for the geometric normal."""
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png(1, 1, [NORMAL_TEXEL])).decode()}]
    b.doc["textures"] = [{"source": 0}]
    mapped = b.material({"name": "mapped", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.5},
                         "normalTexture": {"index": 0, "scale": NORMAL_SCALE}})
    flat = b.material({"name": "scale0", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.5},
                       "normalTexture": {"index": 0, "scale": 0.0}})
    with_tangent = quad(1.0)
    tangent = b.floats([(0.0, 0.0, 1.0, -1.0)] * 4, "VEC4")
    b.node({"mesh": b.mesh(with_tangent, mapped, extra={"TANGENT": tangent}), "translation": [-2.2, 0, 0],
            "rotation": [0, 0.7071068, 0, 0.7071068], "name": "tangent"})  # 90° about y: the tangent turns to +x
    b.node({"mesh": b.mesh(quad(1.0), mapped), "name": "computed"})
    b.node({"mesh": b.mesh(quad(1.0), flat), "translation": [2.2, 0, 0], "name": "scale0"})
    cam = b.camera([0, 6, 0], yfov=0.8, aspect=2.5)
    b.doc["nodes"][cam]["rotation"] = [-0.7071068, 0, 0, 0.7071068]  # −90° about x: looking down −y
    b.light({"type": "directional", "intensity": 2}, {"rotation": [-0.3826834, 0, 0, 0.9238795]})


def normal_mirrored(b: Builder):
    """A mirrored pair of quads facing +y with normal_mapped.gltf's constant normal texture and no
    TANGENT (tangents generated at import): u runs along +x on the left half (x in [−2, 0]) and
    along −x on the right one (x in [0, 2]), mirrored about the seam x = 0 whose two vertices both
    halves share; v runs along +z on both."""
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png(1, 1, [NORMAL_TEXEL])).decode()}]
    b.doc["textures"] = [{"source": 0}]
    mapped = b.material({"name": "mapped", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.5},
                         "normalTexture": {"index": 0, "scale": NORMAL_SCALE}})
    pos = [(-2, 0, -1), (0, 0, -1), (2, 0, -1), (-2, 0, 1), (0, 0, 1), (2, 0, 1)]
    uv = [(0, 0), (1, 0), (0, 0), (0, 1), (1, 1), (0, 1)]
    idx = [0, 4, 1, 0, 3, 4, 1, 5, 2, 1, 4, 5]  # each half wound as quad(): counter-clockwise seen from +y
    b.node({"mesh": b.mesh((pos, [(0, 1, 0)] * 6, uv, idx), mapped), "name": "mirrored"})
    cam = b.camera([0, 6, 0], yfov=0.8, aspect=2.0)
    b.doc["nodes"][cam]["rotation"] = [-0.7071068, 0, 0, 0.7071068]  # −90° about x: looking down −y
    b.light({"type": "directional", "intensity": 2}, {"rotation": [-0.3826834, 0, 0, 0.9238795]})


def iridescent_spheres(b: Builder, metallic: bool):
    """Khronos-style sweep: columns over film thickness, rows over film IOR (dielectric base) or
    base colour (metallic base, film IOR 1.5); sphere centres 1.1 apart."""
    thickness = [100, 250, 400, 550, 700, 850, 1000]
    rows = [[0.97, 0.96, 0.91], [0.91, 0.92, 0.92], [1.0, 0.71, 0.29], [0.95, 0.64, 0.54]] if metallic else [1.2, 1.5, 1.8, 2.1]
    geom = sphere(0.5, 16, 32)
    for r, row in enumerate(rows):
        for c, t in enumerate(thickness):
            pbr = {"baseColorFactor": (row if metallic else [0.05, 0.05, 0.05]) + [1], "metallicFactor": 1.0 if metallic else 0.0,
                   "roughnessFactor": 0.15}
            ext = {"iridescenceFactor": 1.0, "iridescenceIor": 1.5 if metallic else row,
                   "iridescenceThicknessMinimum": t, "iridescenceThicknessMaximum": t}
            m = b.material({"name": f"d{t}_{r}", "pbrMetallicRoughness": pbr, "extensions": {"KHR_materials_iridescence": ext}})
            b.node({"mesh": b.mesh(geom, m), "translation": [1.1 * (c - 3), 1.1 * (1.5 - r), 0]})
    b.camera([0, 0, 9.5], yfov=0.75, aspect=1.6)


def hostile(out: Path):
    """Files the importer must refuse with a message naming the file and the JSON path."""
    b = Builder()
    basic(b)
    b.write_glb(out / "bad_truncated.glb")
    data = (out / "bad_truncated.glb").read_bytes()
    (out / "bad_truncated.glb").write_bytes(data[: len(data) // 2])

    def variant(name, change):
        v = Builder()
        strips_fans(v)
        v.write_gltf(out / name)
        doc = json.loads((out / name).read_text())
        change(doc)
        (out / name).write_text(json.dumps(doc, indent=1) + "\n")

    variant("bad_accessor_range.gltf", lambda d: d["accessors"][0].update(count=100000))
    variant("bad_buffer_view.gltf", lambda d: d["bufferViews"][0].update(byteLength=10 ** 6))
    variant("bad_huge_count.gltf", lambda d: d["accessors"][0].update(count=4294967295))
    variant("bad_uri.gltf", lambda d: d["buffers"][0].update(uri="does/not/exist.bin"))
    variant("bad_index.gltf", lambda d: d["meshes"][0]["primitives"][0].update(indices=99))
    variant("required_unsupported.gltf", lambda d: d.update(extensionsUsed=["KHR_draco_mesh_compression"],
                                                    extensionsRequired=["KHR_draco_mesh_compression"]))
    variant("warn_used.gltf", lambda d: d.update(extensionsUsed=["EXT_lights_ies", "KHR_materials_anisotropy"]))
    variant("bad_cycle.gltf", lambda d: d["nodes"][0].update(children=[0]))

    def bad_normal_texture(d):
        d["materials"][0]["normalTexture"] = {"index": 5}
    variant("bad_normal_texture.gltf", bad_normal_texture)

    def volume_variant(name, change):
        v = Builder()
        volume_slab(v)
        v.write_gltf(out / name)
        doc = json.loads((out / name).read_text())
        change(doc["materials"][0]["extensions"]["KHR_materials_volume"])
        (out / name).write_text(json.dumps(doc, indent=1) + "\n")

    volume_variant("bad_volume_distance.gltf", lambda e: e.update(attenuationDistance=0))
    volume_variant("bad_volume_color.gltf", lambda e: e.update(attenuationColor=[0.5, 1.5, 0.5]))

    def missing_texture(d):
        d["images"] = [{"uri": "missing.png"}]
        d["textures"] = [{"source": 0}]
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    variant("bad_missing_texture.gltf", missing_texture)


def main():
    main_into(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1] / "data" / "gltf")


def main_into(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for name, make in [("basic", basic), ("instanced", instanced), ("strips_fans", strips_fans), ("textured", textured),
                       ("extensions", extensions), ("volume_slab", volume_slab), ("normal_mapped", normal_mapped),
                       ("normal_mirrored", normal_mirrored)]:
        b = Builder()
        make(b)
        b.write_gltf(out / f"{name}.gltf")
    b = Builder()
    basic(b)
    b.write_glb(out / "basic.glb")
    b = Builder()
    basic(b)
    b.write_gltf(out / "basic_external.gltf", embed=False)
    for metallic in (False, True):
        b = Builder()
        iridescent_spheres(b, metallic)
        b.write_gltf(out / ("iridescence_metallic_spheres.gltf" if metallic else "iridescence_dielectric_spheres.gltf"))
    hostile(out)


if __name__ == "__main__":
    main()
