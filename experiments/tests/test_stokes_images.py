"""experiments/iris_experiments/stokes_images.py: the Stokes channels of a stokes render are read
per component, and the polarizer-pair check (S1 = I(0) - I(90), Malus's law) accepts a consistent
pair and rejects a swapped one."""
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from iris_experiments import exr, stokes_images  # noqa: E402


def stokes_exr(path, s):
    """A render with R, G, B = S0 and the 12 channels S0.R ... S3.B of the Stokes vector s (4, H, W)."""
    names = ["R", "G", "B"] + [f"S{k}.{c}" for k in range(4) for c in "RGB"]
    planes = [s[0]] * 3 + [s[k] for k in range(4) for _ in "RGB"]
    exr.write_exr(str(path), np.stack(planes, axis=-1).astype(np.float32), channels=names)


class StokesImages(unittest.TestCase):
    def setUp(self):
        rng = np.random.default_rng(3)
        s0 = rng.uniform(0.5, 1.0, (6, 5))
        s1 = rng.uniform(-0.4, 0.4, (6, 5))
        self.s = np.stack([s0, s1, 0.1 * s1, np.zeros_like(s0)])
        self.tmp = Path(tempfile.mkdtemp())

    def test_reads_each_component(self):
        stokes_exr(self.tmp / "s.exr", self.s)
        np.testing.assert_allclose(stokes_images.stokes_of(self.tmp / "s.exr"), self.s, rtol=1e-6)

    def test_a_plain_render_has_no_stokes_channels(self):
        exr.write_exr(str(self.tmp / "plain.exr"), np.ones((2, 2, 3), np.float32))
        with self.assertRaises(ValueError):
            stokes_images.stokes_of(self.tmp / "plain.exr")

    def test_polarizer_pair_agrees_and_a_swapped_pair_does_not(self):
        i0, i90 = (self.s[0] + self.s[1]) / 2, (self.s[0] - self.s[1]) / 2   # Malus: (S0 ± S1)/2
        m = stokes_images.s1_metrics(self.s, i0, i90)
        self.assertAlmostEqual(m["pair_s1_rel_l2"], 0.0, places=6)
        self.assertAlmostEqual(m["pair_s1_corr"], 1.0, places=6)
        self.assertAlmostEqual(m["pair_s0_mean"], m["s0_mean"], places=6)
        self.assertAlmostEqual(m["abs_s1_over_s0"], np.abs(self.s[1]).mean() / self.s[0].mean(), places=6)
        swapped = stokes_images.s1_metrics(self.s, i90, i0)
        self.assertAlmostEqual(swapped["pair_s1_corr"], -1.0, places=6)
        self.assertGreater(swapped["pair_s1_rel_l2"], 1.9)

    def test_figure_is_written(self):
        out = stokes_images.s1_figure([("S0", self.s[0]), ("S1", self.s[1]), ("zero", np.zeros((6, 5)))],
                                      self.tmp / "f.png")
        self.assertTrue(out.exists())


if __name__ == "__main__":
    unittest.main()
