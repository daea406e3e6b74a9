#!/usr/bin/env python3
"""Writes the seed inputs of the fuzz targets (tests/fuzz/corpus/<target>/seed-*; docs/testing.md).
The seeds are committed; rerun this only to change them. Inputs found by fuzzing (crash-*, slow-*,
oom-*) are added by hand beside them and are never rewritten here.

    python3 tests/fuzz/make_seeds.py            # needs oiiotool for the image seeds
"""
import os
import sys
import struct
import subprocess
import tempfile
import zlib

ROOT = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(ROOT, 'corpus')


def put(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, 'seed-' + name), 'wb') as f:
        f.write(data.encode() if isinstance(data, str) else data)


def ply_seeds():
    head = ('ply\nformat {fmt} 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\n'
            'property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n'
            'property float v\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n')
    verts = [(0, 0, 0, 0, 0, 1, 0, 0), (1, 0, 0, 0, 0, 1, 1, 0), (1, 1, 0, 0, 0, 1, 1, 1), (0, 1, 0, 0, 0, 1, 0, 1)]
    faces = [(0, 1, 2), (0, 2, 3)]
    text = head.format(fmt='ascii') + ''.join(' '.join(map(str, v)) + '\n' for v in verts)
    text += ''.join('3 ' + ' '.join(map(str, f)) + '\n' for f in faces)
    put('ply', 'ascii.ply', text)
    for fmt, e in (('binary_little_endian', '<'), ('binary_big_endian', '>')):
        body = b''.join(struct.pack(e + '8f', *v) for v in verts)
        body += b''.join(struct.pack(e + 'B3i', 3, *f) for f in faces)
        put('ply', fmt + '.ply', head.format(fmt=fmt).encode() + body)
    # A quad (fan triangulation), vertex_index, ushort indices and an extra element that is skipped.
    put('ply', 'quad_extra.ply',
        'ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n'
        'property uchar red\nelement face 1\nproperty list uchar ushort vertex_index\nelement edge 1\n'
        'property int vertex1\nproperty int vertex2\nend_header\n0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n0 1\n')
    # Mesh attributes: uchar vertex colours, a postfixed group, a lone scalar; colours on a quad face.
    put('ply', 'attributes.ply',
        'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n'
        'property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float w_0\nproperty float w_1\n'
        'property float quality\nelement face 1\nproperty list uchar int vertex_indices\nproperty uchar r\n'
        'property uchar g\nproperty uchar b\nproperty float weight\nend_header\n'
        '0 0 0 255 0 0 1 2 0.5\n1 0 0 0 255 0 3 4 1\n1 1 0 0 0 255 5 6 2\n0 1 0 9 9 9 7 8 3\n4 0 1 2 3 10 20 30 0.25\n')


def obj_seeds():
    put('obj', 'tri.obj', 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n')
    put('obj', 'quad_negative.obj', 'o quad\ng g1\ns 1\nusemtl m\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n')
    put('obj', 'mixed.obj', '# comment\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nvt 0.5 0.5\nf 1/1 2/1 3/1\n')


def serialized_shape(version, name, normals, uvs, double):
    verts = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    flags = (0x1 if normals else 0) | (0x2 if uvs else 0) | (0x2000 if double else 0x1000)
    fl = 'd' if double else 'f'
    body = struct.pack('<I', flags)
    if version == 4:
        body += name.encode() + b'\0'
    body += struct.pack('<QQ', 3, 1)
    body += b''.join(struct.pack('<3' + fl, *v) for v in verts)
    if normals:
        body += b''.join(struct.pack('<3' + fl, 0, 0, 1) for _ in verts)
    if uvs:
        body += b''.join(struct.pack('<2' + fl, v[0], v[1]) for v in verts)
    body += struct.pack('<3I', 0, 1, 2)
    return struct.pack('<HH', 0x041C, version) + zlib.compress(body)


def serialized_file(version, shapes):
    data, offsets = b'', []
    for s in shapes:
        offsets.append(len(data))
        data += s
    off = b''.join(struct.pack('<Q' if version == 4 else '<I', o) for o in offsets)
    return data + off + struct.pack('<I', len(shapes))


def serialized_seeds():
    put('serialized', 'v4_two_shapes.serialized',
        serialized_file(4, [serialized_shape(4, 'a', True, True, False), serialized_shape(4, 'b', False, False, True)]))
    put('serialized', 'v3.serialized', serialized_file(3, [serialized_shape(3, '', True, False, False)]))


def spd_seeds():
    put('spd', 'reflectance.spd', '# lambda value\n400 0.1\n500 0.5\n600 0.9\n700 0.3\n')
    put('spd', 'micrometres.spd', '0.38 1.5\n0.5 1.45\n0.78 1.4\n')
    put('spd', 'crlf.spd', '400 1\r\n700 2\r\n\r\n# end\r\n')


def image_seeds():
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra in (('rgb.exr', []), ('rgba_half.exr', ['-d', 'half']), ('tiled.exr', ['--tile', '2', '2']),
                            ('rgb.png', []), ('grey.jpg', []), ('rgb.hdr', []), ('rgb16.tif', ['-d', 'uint16'])):
            out = os.path.join(tmp, name)
            channels = '4' if 'rgba' in name else ('1' if 'grey' in name else '3')
            subprocess.run(['oiiotool', '--pattern', 'checker:width=2:height=2', '4x4', channels] + extra + ['-o', out],
                           check=True)
            with open(out, 'rb') as f:
                put('image', name, f.read())


def spectral_image_seed():
    # A 2x2 spectral EXR in the layout of Fichet et al. 2021 (render --spectral-output): three
    # S0.<nm>nm channels, through the experiments' uncompressed EXR writer.
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'experiments'))
    import numpy as np
    from iris_experiments import exr
    px = np.linspace(0.1, 0.9, 12, dtype=np.float32).reshape(2, 2, 3)
    os.makedirs(os.path.join(CORPUS, 'image'), exist_ok=True)
    exr.write_exr(os.path.join(CORPUS, 'image', 'seed-spectral.exr'), px,
                  channels=('S0.450,000000nm', 'S0.550,000000nm', 'S0.650,000000nm'),
                  metadata={'spectralLayoutVersion': '1.0', 'emissiveUnits': 'W.m^-2.sr^-1'})


def checkpoint_seeds():
    # Film::save's format 4 (render/film.cpp) for a 4x3 film and the header "fuzz\nsamples=0:2":
    # int128 fixed-point sums (48 fraction bits), double sums of squares, counts, CRC-32.
    w, h, header = 4, 3, b'fuzz\nsamples=0:2'
    n = w * h
    body = b'IRISCKP4' + struct.pack('<Q', len(header)) + header + struct.pack('<ii', w, h)
    body += b''.join(int(0.5 * i * 2 ** 48).to_bytes(16, 'little', signed=True) for i in range(3 * n))
    body += struct.pack('<%dd' % (3 * n), *[0.25 * i for i in range(3 * n)])
    body += struct.pack('<%dI' % n, *([2] * n))
    put('checkpoint', 'film4x3.ckpt', body + struct.pack('<I', zlib.crc32(body)))


SCENE_SEEDS = {
    'small.xml': '''<scene version="3.0.0">
    <default name="spp" value="4"/>
    <default name="res" value="16"/>
    <include filename="part.xml"/>
    <integrator type="path"><integer name="max_depth" value="5"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 1, -5" target="0, 1, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/>
            <rfilter type="gaussian"><float name="stddev" value="0.5"/></rfilter></film>
    </sensor>
    <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
    <texture type="checkerboard" id="checks">
        <rgb name="color0" value="0.4"/><srgb name="color1" value="#336699"/>
        <transform name="to_uv"><scale x="4" y="4"/></transform>
    </texture>
    <emitter type="area" id="lamp"><blackbody name="radiance" temperature="3000" scale="2"/></emitter>
    <shape type="obj"><string name="filename" value="tri.obj"/>
        <transform name="to_world"><translate x="1" y="2" z="3"/><rotate y="1" angle="30"/><scale value="2"/>
            <matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/></transform>
        <ref id="white"/></shape>
    <shape type="ply"><string name="filename" value="tri.ply"/><ref id="lamp"/><ref id="inc"/></shape>
    <shape type="rectangle"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf>
        <boolean name="flip_normals" value="true"/></shape>
    <shape type="sphere"><point name="center" x="0" y="1" z="0"/><float name="radius" value="0.5"/>
        <emitter type="area"><spectrum name="radiance" value="400:1, 500:2, 700:3"/></emitter></shape>
    <shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" filename="flat.spd"/></bsdf></shape>
    <shape type="disk"><transform name="to_world"><rotate value="1 0 0" angle="90"/></transform></shape>
</scene>
''',
    'mitsuba06.xml': '''<?xml version="1.0"?>
<scene version="0.6.0">
    <integrator type="direct"/>
    <sensor type="perspective"><float name="fov" value="30"/>
        <transform name="toWorld"><lookAt origin="0 0 -4" target="0 0 0" up="0 1 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    <bsdf type="roughplastic" id="p"><float name="alpha" value="0.2"/><spectrum name="diffuseReflectance" value="0.5"/></bsdf>
    <bsdf type="conductor" id="c"><string name="material" value="Au"/></bsdf>
    <shape type="sphere"><ref id="p"/></shape>
    <shape type="sphere"><transform name="toWorld"><translate x="1"/></transform><ref id="c"/></shape>
    <emitter type="constant"><spectrum name="radiance" value="1"/></emitter>
    <emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="5"/></emitter>
</scene>
''',
    'materials.xml': '''<scene version="3.0.0">
    <bsdf type="dielectric" id="glass"><float name="int_ior" value="1.5"/></bsdf>
    <bsdf type="thinfilm" id="tf"><float name="thickness" value="300"/></bsdf>
    <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>
    <bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.2, 0.4, 0.6"/></bsdf>
    <shape type="sphere"><ref id="glass"/></shape>
    <emitter type="directional"><vector name="direction" x="0" y="-1" z="0"/><rgb name="irradiance" value="1, 2, 3"/></emitter>
</scene>
''',
    # Images through the bitmap texture and the envmap (the renderer's entry point, readImage), and
    # the hostile names of the scene folder: zero (a link to /dev/zero), fifo (a FIFO), dir (a folder),
    # refused by core/input_file.h before any reader sees them (issue 38).
    'images.xml': '''<scene version="3.0.0">
    <emitter type="envmap"><string name="filename" value="env.exr"/><float name="scale" value="0.5"/></emitter>
    <shape type="sphere"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="tex.png"/><string name="filter_type" value="nearest"/></texture></bsdf></shape>
</scene>
''',
    'hostile_include.xml': '''<scene version="3.0.0">
    <include filename="fifo"/>
</scene>
''',
    'hostile_folder.xml': '''<scene version="3.0.0">
    <shape type="sphere"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="dir"/></texture></bsdf></shape>
</scene>
''',
    'hostile_names.xml': '''<scene version="3.0.0">
    <emitter type="envmap"><string name="filename" value="zero"/></emitter>
    <shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" filename="/dev/zero"/></bsdf></shape>
    <shape type="ply"><string name="filename" value="fifo"/></shape>
</scene>
''',
}


def vol_seeds():
    """Mitsuba .vol grids (core/io/vol_reader.h): float32 with 1 and 3 channels, uint8."""
    def vol(encoding, res, channels, values):
        head = b'VOL\x03' + struct.pack('<5i', encoding, *res, channels) + struct.pack('<6f', 0, 0, 0, 1, 1, 1)
        body = struct.pack('<%df' % len(values), *values) if encoding == 1 else bytes(values)
        return head + body
    put('vol', 'float1.vol', vol(1, (2, 2, 2), 1, [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5]))
    put('vol', 'float3.vol', vol(1, (2, 1, 1), 3, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]))
    put('vol', 'uint8.vol', vol(3, (3, 1, 1), 1, [0, 128, 255]))


def gltf_seeds():
    """glTF 2.0 (render/loader/gltf_*): the small assets of tests/gltf/make_assets.py, valid and hostile."""
    import sys
    import tempfile
    sys.path.insert(0, os.path.join(ROOT, '..', 'gltf'))
    import make_assets
    with tempfile.TemporaryDirectory() as tmp:
        make_assets.main_into(tmp)
        for name in sorted(os.listdir(tmp)):
            data = open(os.path.join(tmp, name), 'rb').read()
            if len(data) <= 16384 and not name.endswith('.bin'):  # .ci/fuzz-run's -max_len
                put('gltf', name, data)


def scene_seeds():
    for name, text in SCENE_SEEDS.items():
        put('scene', name, text)


if __name__ == '__main__':
    ply_seeds()
    obj_seeds()
    serialized_seeds()
    spd_seeds()
    image_seeds()
    spectral_image_seed()
    checkpoint_seeds()
    scene_seeds()
    vol_seeds()
    gltf_seeds()
