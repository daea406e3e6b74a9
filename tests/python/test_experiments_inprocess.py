"""experiments/iris_experiments/inprocess.py: jobs rendered through the module in-process give
the same EXR pixels and metadata as the same jobs run by the CLI (runner.run_local)."""
import sys
import tempfile
import unittest
from pathlib import Path

from support import BUILD, REPO, iris, np

sys.path.insert(0, str(REPO / "experiments"))
from iris_experiments import inprocess, runner  # noqa: E402
from iris_experiments.sweep import Sweep  # noqa: E402


class InProcessRunner(unittest.TestCase):
    def jobs(self, out):
        sweep = Sweep("s", {"default": "scenes/default.xml"}, axes={"seed": [1, 2], "mode": ["spectral", "rgb"]},
                      fixed={"spp": 2, "res": 16, "spectral_samples": 4})
        return sweep.jobs(Path(out), BUILD / "render")

    def test_in_process_equals_cli(self):
        with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
            cli = runner.run_local(self.jobs(a), log=lambda *_: None)
            mine = inprocess.run_inprocess(self.jobs(b), BUILD, log=lambda *_: None)
            self.assertTrue(all(r.ok for r in cli + mine), [r.message for r in cli + mine])
            for ja, jb in zip(self.jobs(a), self.jobs(b)):
                (pa, ma), (pb, mb) = iris.read(ja.output), iris.read(jb.output)
                np.testing.assert_array_equal(pa, pb)
                for key in ("iris.mode", "iris.seed", "iris.spp", "iris.rays", "iris.spectral_samples"):
                    self.assertEqual(ma[key], mb[key], key)
            again = inprocess.run_inprocess(self.jobs(b), BUILD, log=lambda *_: None)
            self.assertTrue(all(r.skipped for r in again))  # resume keeps existing outputs

    def test_a_bad_job_fails_with_the_message(self):
        sweep = Sweep("bad", {"default": "scenes/default.xml"}, fixed={"spp": 1, "res": 8, "spectral_samples": 99})
        with tempfile.TemporaryDirectory() as out:
            [r] = inprocess.run_inprocess(sweep.jobs(Path(out), BUILD / "render"), BUILD, log=lambda *_: None)
        self.assertFalse(r.ok)
        self.assertIn("spectral_samples", r.message)


if __name__ == "__main__":
    unittest.main()
