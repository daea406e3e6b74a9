"""iris.load_file / load_string / render / read / write: a render from Python equals the `render`
executable's image bit for bit (spectral and RGB mode), with the same metadata; the GIL is
released while rendering; Ctrl-C stops the render with the partial image; bad input raises."""
import _thread
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from pathlib import Path

from support import BUILD, REPO, iris, np

SCENE = str(REPO / "scenes" / "default.xml")

TINY = """<scene version="3.0.0">
    <default name="res" value="16"/>
    <default name="material" value="diffuse"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="$material"/></shape>
    <emitter type="constant"/>
</scene>"""
TINY_SHAPE_LINE = 1 + TINY.splitlines().index('    <shape type="sphere"><bsdf type="$material"/></shape>')


def cli_render(tmp, *args):
    out = Path(tmp) / "cli.exr"
    subprocess.run([str(BUILD / "render"), SCENE, "-o", str(out), "--no-png", "--quiet", *args], check=True,
                   capture_output=True)
    return iris.read(out)


class RenderEqualsCLI(unittest.TestCase):
    def compare(self, py_kwargs, cli_args):
        scene = iris.load_file(SCENE, res=24)
        result = iris.render(scene, **py_kwargs)
        with tempfile.TemporaryDirectory() as tmp:
            image, meta = cli_render(tmp, "-D", "res=24", *cli_args)
        self.assertEqual(result.image.dtype, np.float32)
        self.assertEqual(result.image.shape, (24, 24, 3))
        np.testing.assert_array_equal(result.image, image)  # bit for bit
        self.assertGreater(float(result.image.mean()), 0.0)
        for key, value in meta.items():
            if key != "iris.render_time_s":
                self.assertEqual(result.metadata[key], value, key)
        return result

    def test_spectral_render_equals_cli(self):
        r = self.compare(dict(spp=3, seed=5, spectral_samples=8), ["--spp", "3", "--seed", "5", "--spectral-samples", "8"])
        self.assertEqual(r.spp, 3)
        self.assertTrue(np.all(r.sample_count == 3))
        self.assertTrue(np.all(r.variance >= 0))

    def test_independent_wavelengths_equal_cli(self):
        r = self.compare(dict(spp=2, seed=4, wavelength_sampling="independent"),
                         ["--spp", "2", "--seed", "4", "--wavelength-sampling", "independent"])
        self.assertEqual(r.metadata["iris.wavelength_sampling"], "independent")
        with self.assertRaises(iris.Error):
            iris.render(iris.load_file(SCENE, res=8), spp=1, wavelength_sampling="stratified")

    def test_samplers_equal_cli(self):
        for sampler in ("stratified", "multijitter", "sobol", "highdimsobol"):
            r = self.compare(dict(spp=4, seed=2, sampler=sampler), ["--spp", "4", "--seed", "2", "--sampler", sampler])
            self.assertEqual(r.metadata["iris.sampler"], sampler + ("/4" if sampler in ("stratified", "multijitter") else ""))

    def test_rgb_render_equals_cli(self):
        self.compare(dict(spp=2, seed=1, mode="rgb"), ["--spp", "2", "--seed", "1", "--mode", "rgb"])

    def test_other_colorspace_equals_cli(self):
        self.compare(dict(spp=1, colorspace="CIE-XYZ"), ["--spp", "1", "--output-space", "CIE-XYZ"])

    def test_spectral_image_integrates_to_the_xyz_image(self):
        scene = iris.load_file(SCENE, res=16)
        r = iris.render(scene, spp=4, seed=2, colorspace="CIE-XYZ", spectral_bins=47)  # 10 nm bins
        self.assertEqual(r.spectral.shape, (16, 16, 47))
        self.assertEqual(r.spectral_wavelengths[0], 365.0)
        plain = iris.render(scene, spp=4, seed=2, colorspace="CIE-XYZ")
        np.testing.assert_array_equal(r.image, plain.image)  # the spectral image changes nothing else
        # Σ_b S_b x̄(λ_b) Δ / ∫ȳ: the film's XYZ estimator with the CMFs constant over each bin.
        cmf = iris.color.xyz_bar(r.spectral_wavelengths)
        xyz = r.spectral.reshape(-1, 47) @ cmf * 10.0 / iris.color.y_integral()
        np.testing.assert_allclose(xyz.mean(axis=0), r.image.reshape(-1, 3).mean(axis=0), rtol=0.03)
        with self.assertRaisesRegex(iris.Error, "spectral"):
            iris.render(scene, spp=1, mode="rgb", spectral_bins=10)

    def test_different_seed_differs(self):
        scene = iris.load_file(SCENE, res=16)
        a, b = iris.render(scene, spp=1, seed=1), iris.render(scene, spp=1, seed=2)
        self.assertFalse(np.array_equal(a.image, b.image))


class RenderBehaviour(unittest.TestCase):
    def test_gil_is_released_while_rendering(self):
        scene = iris.load_file(SCENE, res=48)
        counter = [0]
        stop = threading.Event()

        def count():
            while not stop.is_set():
                counter[0] += 1

        t = threading.Thread(target=count)
        t.start()
        try:
            time.sleep(0.05)
            before = counter[0]
            r = iris.render(scene, spp=0, time_limit=0.5, threads=1)  # renders for half a second
            during = counter[0] - before
        finally:
            stop.set()
            t.join()
        self.assertGreater(r.spp, 0)
        self.assertTrue(r.stats["time_limited"])
        # With the GIL held for the whole render the counting thread could not run at all
        # (a pure-Python loop counts millions per second).
        self.assertGreater(during, 10000)

    def test_keyboard_interrupt_returns_the_partial_image(self):
        scene = iris.load_file(SCENE, res=32)
        timer = threading.Timer(0.5, _thread.interrupt_main)
        timer.start()
        with self.assertRaises(iris.RenderInterrupted) as ctx:
            iris.render(scene, spp=100000, threads=1)
        timer.cancel()
        result = ctx.exception.result
        self.assertIsInstance(ctx.exception, KeyboardInterrupt)
        self.assertTrue(result.interrupted)
        self.assertEqual(result.metadata["iris.interrupted"], "1")
        self.assertLess(result.spp, 100000)
        self.assertTrue(np.all(np.isfinite(result.image)))

    def test_sigint_in_a_subprocess_stops_the_render(self):
        script = (
            "import iris, sys\n"
            f"scene = iris.load_file({SCENE!r}, res=32)\n"
            "started = False\n"
            "def progress(f):\n"
            "    global started\n"
            "    if not started:\n"
            "        started = True; print('started', flush=True)\n"
            "try:\n"
            "    iris.render(scene, spp=100000, threads=1, progress=progress)\n"
            "except iris.RenderInterrupted as e:\n"
            "    print('interrupted', e.result.spp, flush=True)\n")
        env = dict(os.environ, PYTHONPATH=str(BUILD / "python"))
        p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
        self.assertEqual(p.stdout.readline().strip(), "started")
        time.sleep(0.3)
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 0)
        self.assertTrue(out.startswith("interrupted"), out)

    def test_progress_callback_reaches_one(self):
        seen = []
        iris.render(iris.load_file(SCENE, res=16), spp=2, progress=seen.append)
        self.assertGreater(len(seen), 0)
        self.assertEqual(seen[-1], 1.0)
        self.assertEqual(seen, sorted(seen))

    def test_error_in_progress_callback_propagates(self):
        def fail(f):
            raise RuntimeError("stop here")
        with self.assertRaisesRegex(RuntimeError, "stop here"):
            iris.render(iris.load_file(SCENE, res=16), spp=2, progress=fail)

    def test_load_string_and_defines(self):
        scene = iris.load_string(TINY, material="diffuse", res=8)
        self.assertEqual((scene.width, scene.height, scene.spp), (8, 8, 4))
        r = iris.render(scene, seed=0)
        self.assertEqual(r.image.shape, (8, 8, 3))
        self.assertEqual(r.spp, 4)

    def test_unknown_plugin_names_file_and_line(self):
        with self.assertRaisesRegex(iris.Error, rf"<string>:{TINY_SHAPE_LINE}: .*bsdf type 'nosuchbsdf'.*supported: .*diffuse"):
            iris.load_string(TINY, material="nosuchbsdf")

    def test_missing_file_is_named(self):
        with self.assertRaisesRegex(iris.Error, "no_such_scene.xml"):
            iris.load_file("no_such_scene.xml")

    def test_bad_options_are_rejected(self):
        scene = iris.load_string(TINY, material="diffuse")
        with self.assertRaisesRegex(iris.Error, "mode"):
            iris.render(scene, mode="grey")
        with self.assertRaisesRegex(iris.Error, "spectral_samples"):
            iris.render(scene, spectral_samples=33)
        with self.assertRaisesRegex(iris.Error, "colour space 'nope'|'nope' is not in"):
            iris.render(scene, colorspace="nope")
        with self.assertRaisesRegex(iris.Error, "unknown sampler 'halton'"):
            iris.render(scene, sampler="halton")
        with self.assertRaises(TypeError):
            iris.render(scene, spp=1.5)
        with self.assertRaises(TypeError):
            iris.render("scene.xml")


class Images(unittest.TestCase):
    def test_write_read_round_trip(self):
        img = np.random.default_rng(1).random((5, 7, 4), dtype=np.float32)
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "a.exr"
            iris.write(path, img, {"note": "hello"})
            back, meta, names = iris.read(path, with_channel_names=True)
        np.testing.assert_array_equal(back, img)
        self.assertEqual(meta["note"], "hello")
        self.assertEqual(names, ["R", "G", "B", "A"])

    def test_result_write_equals_cli_file(self):
        r = iris.render(iris.load_file(SCENE, res=16), spp=1)
        with tempfile.TemporaryDirectory() as tmp:
            r.write(Path(tmp) / "py.exr")
            back, meta = iris.read(Path(tmp) / "py.exr")
        np.testing.assert_array_equal(back, r.image)
        self.assertEqual(meta["iris.spp"], "1")

    def test_bad_images_are_rejected(self):
        with self.assertRaisesRegex(iris.Error, "shape"):
            iris.write("x.exr", np.zeros(5))
        with self.assertRaises(TypeError):
            iris.write("x.exr", np.array([["a"]]))
        with self.assertRaisesRegex(iris.Error, "not_there.exr"):
            iris.read("not_there.exr")


LIGHT_TRACING = """<scene version="3.0.0">
    <default name="integrator" value="path"/>
    <default name="reflectance" value="0.5"/>
    <integrator type="$integrator"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"><float name="reflectance" value="$reflectance"/></bsdf></shape>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="90"/><translate y="3"/></transform>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter>
    </shape>
    <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
</scene>"""


class LightTracing(unittest.TestCase):
    """ptracer and bdpt from Python: the render equals the CLI's bit for bit, and its image mean
    agrees with path's within the statistical error (a perturbed reflectance is rejected)."""

    @staticmethod
    def mean_and_variance(r):
        """Whole-image mean per channel and its variance: the pixels' variances of their means
        (film space, linear Rec.709 in RGB mode), summed and divided by the pixel count squared."""
        n = r.image.shape[0] * r.image.shape[1]
        return r.image.reshape(-1, 3).astype(np.float64).mean(0), r.variance.reshape(-1, 3).astype(np.float64).sum(0) / n**2

    def z(self, a, b):
        (ma, va), (mb, vb) = self.mean_and_variance(a), self.mean_and_variance(b)
        return np.abs(ma - mb) / np.sqrt(va + vb)

    def render(self, integrator, seed, spp, reflectance="0.5"):
        scene = iris.load_string(LIGHT_TRACING, integrator=integrator, reflectance=reflectance)
        self.assertEqual(scene.integrator, integrator)
        return iris.render(scene, spp=spp, seed=seed, mode="rgb", colorspace="lin_rec709")

    def test_render_equals_cli(self):
        for integrator in ("ptracer", "bdpt"):
            with self.subTest(integrator=integrator), tempfile.TemporaryDirectory() as tmp:
                scene_file = Path(tmp) / "scene.xml"
                scene_file.write_text(LIGHT_TRACING)
                r = iris.render(iris.load_file(scene_file, integrator=integrator), spp=3, seed=7, threads=2)
                out = Path(tmp) / "cli.exr"
                subprocess.run([str(BUILD / "render"), str(scene_file), "-o", str(out), "--no-png", "--quiet", "--spp", "3",
                                "--seed", "7", "--threads", "1", "-D", f"integrator={integrator}"], check=True, capture_output=True)
                image, _ = iris.read(out)
                np.testing.assert_array_equal(r.image, image)  # bit for bit, and for any thread count
                self.assertGreater(float(r.image.mean()), 0.0)

    def test_agrees_with_path(self):
        # Fixed seeds; |z| of the whole-image mean per channel, < 4 (p ≈ 6e-5 per channel).
        path = self.render("path", 1, 64)
        for integrator in ("ptracer", "bdpt"):
            with self.subTest(integrator=integrator):
                z = self.z(self.render(integrator, 2, 64), path)
                self.assertTrue(np.all(z < 4), f"{integrator} vs path: |z| = {z}")
        # The test can fail: 0.6 instead of 0.5 for the sphere's reflectance is found.
        z = self.z(self.render("bdpt", 3, 64, reflectance="0.6"), path)
        self.assertTrue(np.all(z > 4), f"perturbed bdpt vs path: |z| = {z}")


if __name__ == "__main__":
    unittest.main()
