"""experiments/perf/peers.py (issue 37): the PFM reader, the scene edits, the equal-time interpolation
and a whole side-by-side run with stand-in renderers (a peer not given is skipped, a peer's output is
read back)."""
import json
import os
import stat
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "perf"))
import peers  # noqa: E402

XML = """<scene version="0.6.0">
    <sensor type="perspective">
        <sampler type="independent"><integer name="sampleCount" value="64"/></sampler>
        <film type="hdrfilm"><integer name="width" value="320"/><integer name="height" value="240"/></film>
    </sensor>
    <shape type="obj"><string name="filename" value="../meshes/bunny.obj"/></shape>
</scene>
"""
JSON = '{"primitives": [{"type": "mesh", "file": "../meshes/bunny.obj"}],\n' \
       ' "camera": {"resolution": [\n 320,\n 240\n]}, "renderer": {"spp": 64}}\n'

# A stand-in for Mitsuba 0.6: writes a constant 0.25 PFM to the -o path.
FAKE_MITSUBA = """import sys, numpy as np
out = sys.argv[sys.argv.index("-o") + 1]
img = np.full((4, 6, 3), 0.25, dtype="<f4")
with open(out, "wb") as f:
    f.write(b"PF\\n6 4\\n-1.0\\n")
    f.write(img[::-1].tobytes())
"""


def write_pfm(path, img, little=True):
    with open(path, "wb") as f:
        h, w = img.shape[:2]
        f.write(f"PF\n{w} {h}\n{-1.0 if little else 1.0}\n".encode())
        f.write(img[::-1].astype("<f4" if little else ">f4").tobytes())


def script(path, py_file):
    path.write_text(f"#!/bin/sh\nexec {sys.executable} {py_file} \"$@\"\n")
    path.chmod(path.stat().st_mode | stat.S_IEXEC)
    return path


class PeersTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_pfm_reads_both_byte_orders_top_row_first(self):
        img = np.arange(2 * 3 * 3, dtype=np.float32).reshape(2, 3, 3)
        for little in (True, False):
            write_pfm(self.dir / "a.pfm", img, little)
            np.testing.assert_array_equal(peers.read_pfm(self.dir / "a.pfm"), img)

    def test_not_a_pfm_is_refused(self):
        (self.dir / "b.pfm").write_bytes(b"P6\n2 2\n255\n" + bytes(12))
        with self.assertRaises(ValueError):
            peers.read_pfm(self.dir / "b.pfm")

    def test_scene_edits_and_absolute_mesh_paths(self):
        (self.dir / "mitsuba").mkdir()
        (self.dir / "tungsten").mkdir()
        (self.dir / "mitsuba" / "s.xml").write_text(XML)
        (self.dir / "tungsten" / "s.json").write_text(JSON)
        args = type("A", (), {"scenes": str(self.dir), "meshes": str(self.dir / "m")})()
        work = self.dir / "work"
        work.mkdir()
        files = peers.prepare(args, "s", work, width=80, height=60, spp=16, sampler="stratified")
        xml = files["xml"].read_text()
        self.assertIn('<integer name="width" value="80"', xml)
        self.assertIn('<integer name="height" value="60"', xml)
        self.assertIn('<integer name="sampleCount" value="16"', xml)
        self.assertIn('<sampler type="stratified">', xml)
        self.assertIn(str((self.dir / "m" / "bunny.obj").resolve()), xml)
        self.assertIn('value="pfm"', files["mts_xml"].read_text())
        self.assertNotIn('value="pfm"', xml)
        js = files["json"].read_text()
        self.assertIn('"resolution": [80, 60]', js)
        self.assertIn('"spp": 16', js)
        self.assertIn(str((self.dir / "m" / "bunny.obj").resolve()), js)

    def test_relmse_at_interpolates_log_log_and_never_extrapolates(self):
        rows = [{"seconds": 1.0, "relmse": 0.4}, {"seconds": 4.0, "relmse": 0.1}]
        self.assertAlmostEqual(peers.relmse_at(rows, 2.0), 0.2)
        self.assertIsNone(peers.relmse_at(rows, 0.5))
        self.assertIsNone(peers.relmse_at(rows, 8.0))

    def test_lowest_error_is_named_only_where_every_renderer_has_a_value(self):
        per = {"iris": {"rows": [{"seconds": 0.5, "relmse": 0.4}, {"seconds": 4.0, "relmse": 0.05}]},
               "slow": {"rows": [{"seconds": 1.0, "relmse": 0.1}, {"seconds": 8.0, "relmse": 0.01}]}}
        line = peers.lowest_error_line(per, [0.5, 1.0, 2.0, 4.0, 8.0])
        # At 1 s iris (interpolated 0.2) loses to slow (0.1); at 0.5 s and 8 s one has no value, so
        # "slow" must not be named the winner at 8 s.
        self.assertIn("1s: slow", line)
        self.assertNotIn("8s: slow", line)
        self.assertIn("not named at 0.5s, 8s", line)

    def test_side_by_side_with_stand_ins_skips_peers_not_given(self):
        (self.dir / "mitsuba").mkdir()
        (self.dir / "tungsten").mkdir()
        (self.dir / "mitsuba" / "s.xml").write_text(XML)
        (self.dir / "tungsten" / "s.json").write_text(JSON)
        (self.dir / "fake_mitsuba.py").write_text(FAKE_MITSUBA)
        iris = script(self.dir / "iris", HERE / "fake_render.py")
        mts = script(self.dir / "mitsuba06", self.dir / "fake_mitsuba.py")
        out = self.dir / "out"
        r = subprocess.run([sys.executable, str(HERE.parent / "perf" / "peers.py"), "--iris", str(iris),
                            "--mitsuba-rgb", str(mts), "--tungsten", str(self.dir / "no_such_tungsten"),
                            "--scenes", str(self.dir), "--meshes", str(self.dir), "--scene-list", "s",
                            "--rounds", "2", "--out", str(out)], capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("Tungsten not given or not executable", r.stderr)
        data = json.loads((out / "peers.json").read_text())
        sbs = data["side_by_side"]["s"]
        self.assertEqual(sorted(sbs["times"]), ["iris-rgb", "iris-s16", "iris-s4", "mts-rgb"])
        self.assertTrue(all(len(t) == 2 for t in sbs["times"].values()))
        self.assertAlmostEqual(sbs["mean_luminance"]["mts-rgb"], 0.25, places=6)
        self.assertAlmostEqual(sbs["mean_luminance"]["iris-s4"], 0.5, places=1)
        md = (out / "peers.md").read_text()
        self.assertIn("÷ Mitsuba 0.6 RGB", md)
        self.assertNotIn("÷ Tungsten", md)

    def test_executables_given_by_relative_paths_still_run(self):
        # The renderers run in a scratch folder; a path relative to the caller's folder (as in
        # `--peers-bin ../shared/peers/bin`) must still name the same executable there.
        (self.dir / "mitsuba").mkdir()
        (self.dir / "tungsten").mkdir()
        (self.dir / "bin").mkdir()
        (self.dir / "mitsuba" / "s.xml").write_text(XML)
        (self.dir / "tungsten" / "s.json").write_text(JSON)
        (self.dir / "fake_mitsuba.py").write_text(FAKE_MITSUBA)
        script(self.dir / "bin" / "iris", HERE / "fake_render.py")
        script(self.dir / "bin" / "mitsuba06", self.dir / "fake_mitsuba.py")
        r = subprocess.run([sys.executable, str(HERE.parent / "perf" / "peers.py"), "--iris", "bin/iris",
                            "--mitsuba-rgb", "bin/mitsuba06", "--scenes", ".", "--meshes", ".", "--scene-list", "s",
                            "--rounds", "1", "--out", "out"], capture_output=True, text=True, timeout=120, cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        times = json.loads((self.dir / "out" / "peers.json").read_text())["side_by_side"]["s"]["times"]
        self.assertEqual(sorted(times), ["iris-rgb", "iris-s16", "iris-s4", "mts-rgb"])

    def test_equal_time_runs_iris_with_both_sobol_samplers(self):
        (self.dir / "mitsuba").mkdir()
        (self.dir / "mitsuba" / "s.xml").write_text(XML)
        (self.dir / "tungsten").mkdir()
        (self.dir / "tungsten" / "s.json").write_text(JSON)
        iris = script(self.dir / "iris", HERE / "fake_render.py")
        out = self.dir / "out"
        r = subprocess.run([sys.executable, str(HERE.parent / "perf" / "peers.py"), "--iris", str(iris),
                            "--scenes", str(self.dir), "--meshes", str(self.dir), "--scene-list", "s",
                            "--no-timing", "--equal-time", "--et-spp", "4,16", "--ref-spp", "64", "--out", str(out)],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        et = json.loads((out / "peers.json").read_text())["equal_time"]["s"]
        self.assertEqual(sorted(et), ["iris-rgb", "iris-rgb-highdim", "iris-s4", "iris-s4-highdim", "iris-s4-volpath"])
        # The stand-in's noise is 0.4 (highdimsobol) against 0.5 (sobol) of the same draws: the
        # padded variant's relMSE must come out (0.5 / 0.4)² times higher, so each ran its sampler.
        for a, b in zip(et["iris-s4"]["rows"], et["iris-s4-highdim"]["rows"]):
            self.assertGreater(a["relmse"], 1.2 * b["relmse"])


if __name__ == "__main__":
    unittest.main()
