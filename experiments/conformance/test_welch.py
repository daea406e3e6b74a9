#!/usr/bin/env python3
"""Unit tests of the suite's statistics and scene edits (run by ctest as Conformance.Statistics)."""
import math
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

import perturb  # noqa: E402
import welch  # noqa: E402


class StudentT(unittest.TestCase):
    def test_known_quantiles(self):
        # Two-sided 5 % quantiles of Student's t (tables): ν = 1: 12.7062, ν = 10: 2.2281; normal: 1.95996.
        p = welch.student_t_two_sided_p(np.array([12.706205, 2.228139, 1.959964, 0.0]), np.array([1, 10, 1e6, 3]))
        np.testing.assert_allclose(p, [0.05, 0.05, 0.05, 1.0], rtol=1e-5)
        # ν = 1 is the Cauchy distribution: P(|T| ≥ t) = 1 − 2·atan(t)/π.
        t = np.array([0.5, 3.0, 100.0])
        np.testing.assert_allclose(welch.student_t_two_sided_p(t, np.ones(3)), 1 - 2 * np.arctan(t) / math.pi, rtol=1e-9)

    def test_sidak(self):
        self.assertAlmostEqual(welch.sidak_threshold(0.01, 1), 0.01, places=15)
        m = 6912
        self.assertAlmostEqual((1 - welch.sidak_threshold(0.01, m)) ** m, 0.99, places=12)


class WelchTest(unittest.TestCase):
    def simulate(self, shift, n1=64, n2=256, shape=(32, 32, 3), seed=1):
        rng = np.random.default_rng(seed)
        a = rng.exponential(1.0, size=shape + (n1,)) * (1 + shift)   # skewed like radiance samples
        b = rng.exponential(1.0, size=shape + (n2,))
        def stats(x):
            return x.mean(-1), x.var(-1, ddof=1) / x.shape[-1], x.shape[-1]
        return stats(a), stats(b)

    def test_null_rejects_at_the_nominal_rate(self):
        (m1, v1, n1), (m2, v2, n2) = self.simulate(0.0)
        p = welch.welch_p(m1, v1, n1, m2, v2, n2)
        rate = np.mean(p < 0.05)   # 3072 independent tests: σ of the rate ≈ 0.004
        self.assertLess(abs(rate - 0.05), 0.016, rate)
        self.assertTrue(welch.multiscale_test(m1, v1, n1, m2, v2, n2)["passed"])

    def test_two_percent_bias_is_found_by_block_means_not_pixels(self):
        (m1, v1, n1), (m2, v2, n2) = self.simulate(0.02)
        r = welch.multiscale_test(m1, v1, n1, m2, v2, n2)
        self.assertFalse(r["passed"])
        self.assertEqual(r["scale"], 0)          # the whole-image mean detects it ...
        self.assertGreater(r["per_scale"][1].min(), r["threshold"])   # ... no single pixel does

    def test_equal_constant_images_pass_and_different_ones_fail(self):
        z = np.zeros((8, 8, 3))
        one = np.ones((8, 8, 3))
        self.assertTrue(welch.multiscale_test(one, z, 10, one, z, 10)["passed"])
        self.assertFalse(welch.multiscale_test(one, z, 10, 1.001 * one, z, 10)["passed"])


    def test_rare_events_need_the_reference_variance_floor(self):
        # A pixel whose mean is carried by a rare event (probability 0.003 of a sample seeing a
        # bright edge, value 1, over a background of 0.1 with tiny noise): with 868 samples many
        # pixels see no event and report almost no variance, so plain Welch rejects the null at
        # Šidák's level; bounded by the reference's per-sample variance it does not, and a 1 %
        # bias of the background is still found.
        rng = np.random.default_rng(5)
        shape, n1, n2, q = (24, 24, 1), 868, 32000, 0.003
        def pixel_stats(n, scale=1.0):
            events = rng.binomial(n, q, size=shape)
            noise = rng.normal(0.0, 1e-4, size=shape + (2,))
            # Exact moments of n samples: events of value 1, the rest 0.1·scale (+ small noise).
            mean = (events * 1.0 + (n - events) * 0.1 * scale) / n + noise[..., 0] / np.sqrt(n)
            m2 = (events * 1.0 + (n - events) * (0.1 * scale) ** 2) / n + 1e-8
            return mean, np.maximum(m2 - mean ** 2, 0) * n / (n - 1) / n
        m1, v1 = pixel_stats(n1)
        m2, v2 = pixel_stats(n2)
        plain = welch.multiscale_test(m1, v1, n1, m2, v2, n2)
        self.assertFalse(plain["passed"])
        floored = welch.multiscale_test(m1, welch.floor_by_reference(v1, n1, v2, n2), n1, m2, v2, n2)
        self.assertTrue(floored["passed"], floored["p_min"])
        mb, vb = pixel_stats(n1, 1.01)
        self.assertFalse(welch.multiscale_test(mb, welch.floor_by_reference(vb, n1, v2, n2), n1, m2, v2, n2)["passed"])

    def test_mitsuba_z_test_floors_the_variance_and_tolerates_a_quarter_percent_of_pixels(self):
        # Mitsuba's rule (test_renders.py): the reference is exact, its per-sample variance floored
        # at 1e-4, and 99.75 % of the channel tests must pass. Zero-variance images 0.1 % apart pass
        # it (they fail the Welch test above); a 20 % error fails it, and so do more than 0.25 % of
        # the pixels off by a lot.
        one, z = np.ones((48, 48, 3)), np.zeros((48, 48, 3))
        self.assertTrue(welch.mitsuba_z_test(1.001 * one, 868, one, z)[0])
        self.assertFalse(welch.multiscale_test(1.001 * one, z, 868, one, z, 32000)["passed"])
        self.assertFalse(welch.mitsuba_z_test(1.2 * one, 868, one, z)[0])
        bad = one.copy()
        bad[:3, :3] = 2.0          # 9 of 2304 pixels = 0.39 % > 0.25 %
        self.assertFalse(welch.mitsuba_z_test(bad, 868, one, z)[0])
        bad = one.copy()
        bad[:2, :2] = 2.0          # 4 pixels = 0.17 %: tolerated
        self.assertTrue(welch.mitsuba_z_test(bad, 868, one, z)[0])

    def test_block_t_and_ratio(self):
        a, b = np.full((8, 8, 3), 2.0), np.ones((8, 8, 3))
        v = np.full((8, 8, 3), 0.01)
        t, ratio = welch.block_t_and_ratio(a, v, b, v, 4, 1, 0)
        np.testing.assert_allclose(ratio, 2.0)
        np.testing.assert_allclose(t, 1.0 / np.sqrt(2 * 16 * 0.01 / 256))   # block variance Σv/k⁴ each


class Perturbation(unittest.TestCase):
    def test_default_fov_of_mitsuba(self):
        # 50 mm on 36x24 mm: 46.79° along the diagonal, 34.02° across a square image.
        self.assertAlmostEqual(perturb.mitsuba_default_fov_x(48, 48), 34.022, places=3)
        self.assertAlmostEqual(perturb.mitsuba_default_fov_x(36, 24),
                               math.degrees(2 * math.atan(18 / 50)), places=6)

    def test_albedo_scales_values_not_wavelengths(self):
        self.assertEqual(perturb.scale_values("400:0.5, 700:1", 2.0), "400:1, 700:2")
        self.assertEqual(perturb.scale_values("0.1, 0.2, 0.3", 2.0), "0.2, 0.4, 0.6")

    def test_copy_changes_only_the_copy_and_rejects_a_no_op(self):
        with tempfile.TemporaryDirectory() as tmp:
            src = Path(tmp) / "src"
            (src / "fragments").mkdir(parents=True)
            scene = src / "test_a_path.xml"
            scene.write_text('<scene version="2.0.0"><path value="../common"/>'
                             '<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>'
                             '<include filename="fragments/f.xml"/></scene>')
            (src / "fragments" / "f.xml").write_text('<scene version="2.0.0"><sensor type="perspective">'
                                                     '<film type="hdrfilm"><integer name="width" value="48"/>'
                                                     '<integer name="height" value="48"/></film></sensor></scene>')
            copy = perturb.perturbed_copy(scene, "albedo=1.02", Path(tmp) / "a")
            self.assertIn('value="0.51"', copy.read_text())
            self.assertIn(str((src / "../common").resolve()), copy.read_text())
            self.assertIn('value="0.5"', scene.read_text())
            fov = perturb.perturbed_copy(scene, "fov=1", Path(tmp) / "b")
            self.assertIn('name="fov" value="35.022', (fov.parent / "fragments" / "f.xml").read_text())
            with self.assertRaises(Exception):   # nothing to scale: an error, not a silent no-op
                perturb.perturbed_copy(src / "fragments" / "f.xml", "albedo=1.02", Path(tmp) / "d")


if __name__ == "__main__":
    unittest.main()
