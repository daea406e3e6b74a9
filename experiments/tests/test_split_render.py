"""Split renders and Slurm submission without Slurm (the real-Slurm tests are slurm_cluster_test.py,
run by .ci/slurm-test): the array script of a split render, run task by task by hand as Slurm
would, renders shards that merge to the unsplit image bit for bit (real render and merge); a
finished task is not rendered again; --status finds missing and wrong shards; --slurm --submit /
--resubmit call sbatch (a recording fake on PATH) with an array plus an afterok collect job and
resubmit only tasks without a valid image."""
from __future__ import annotations

import io
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from iris_experiments import exr, runner, split_render  # noqa: E402
from iris_experiments.experiment import run  # noqa: E402
from iris_experiments.film_state import read_film_state  # noqa: E402
from iris_experiments.tools import REPO, build_dir  # noqa: E402

BUILD = build_dir()
SCENE = REPO / "scenes" / "default.xml"
HAVE_TOOLS = (BUILD / "render").exists() and (BUILD / "merge").exists()

FAKE_SBATCH = """#!/bin/sh
# Records its arguments, answers like `sbatch --parsable`.
echo "$*" >> "$(dirname "$0")/calls.txt"
n=$(wc -l < "$(dirname "$0")/calls.txt")
echo "$((100 + n))"
"""


class TempDir(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="iris_split_test_"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def fake_sbatch(self) -> Path:
        bindir = self.tmp / "bin"
        bindir.mkdir(exist_ok=True)
        (bindir / "sbatch").write_text(FAKE_SBATCH)
        (bindir / "sbatch").chmod(0o755)
        return bindir


@unittest.skipUnless(HAVE_TOOLS, "render/merge not built")
class SplitRenderByHandTest(TempDir):
    ARGS = ("--seed", "5", "-D", "res=24", "--threads", "1")

    def plan(self, spp=10, tasks=3):
        return split_render.SplitPlan(SCENE, spp, tasks, self.tmp / "split", BUILD / "render", BUILD / "merge", self.ARGS)

    def test_ranges_cover_every_sample_once(self):
        self.assertEqual(self.plan(10, 3).ranges(), [(0, 3), (3, 6), (6, 10)])
        self.assertEqual(self.plan(4, 4).ranges(), [(0, 1), (1, 2), (2, 3), (3, 4)])
        with self.assertRaises(Exception):
            self.plan(3, 4).ranges()

    def test_tasks_run_by_hand_merge_to_the_unsplit_render(self):
        plan = self.plan()
        array, merge = split_render.write_scripts(plan, time="00:05:00", cpus_per_task=1)
        text = array.read_text()
        self.assertIn("#SBATCH --array=0-2\n", text)
        self.assertIn(f"#SBATCH --output={plan.log_dir}/shard_%a.%A.out\n", text)
        self.assertEqual([s for s, _ in split_render.shard_status(plan)], ["missing"] * 3)
        for i in (2, 0, 1):
            r = subprocess.run(["bash", str(array)], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(i)},
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual([s for s, _ in split_render.shard_status(plan)], ["complete"] * 3)
        st = read_film_state(plan.shard(2))
        self.assertEqual((st.begin, st.end, st.min_count, st.width), (6, 10, 4, 24))
        # A finished task is not rendered again.
        before = plan.shard(1).stat().st_mtime_ns
        r = subprocess.run(["bash", str(array)], env={**os.environ, "SLURM_ARRAY_TASK_ID": "1"},
                           capture_output=True, text=True)
        self.assertIn("shard 1 is already complete", r.stdout)
        self.assertEqual(plan.shard(1).stat().st_mtime_ns, before)
        self.assertEqual(subprocess.run(["bash", str(merge)], capture_output=True, text=True).returncode, 0)
        full = self.tmp / "full.exr"
        subprocess.run([str(BUILD / "render"), str(SCENE), "--spp", "10", "-o", str(full), "--no-png", "--quiet",
                        *self.ARGS], check=True, capture_output=True)
        self.assertTrue((exr.read_exr(str(plan.image))[0] == exr.read_exr(str(full))[0]).all())
        # A shard of the wrong range is found, and the merge refuses it.
        plan.shard(2).unlink()
        shutil.copy(plan.shard(1), plan.shard(2))
        status = split_render.shard_status(plan)
        self.assertEqual(status[2][0], "invalid")
        self.assertIn("holds samples 3:6, task 2 renders 6:10", status[2][1])
        r = subprocess.run(["bash", str(merge)], capture_output=True, text=True)
        self.assertEqual(r.returncode, 1)
        self.assertIn("overlap", r.stderr)

    def test_submit_and_resubmit_call_sbatch_with_afterok(self):
        bindir = self.fake_sbatch()
        env = {**os.environ, "PATH": f"{bindir}:{os.environ['PATH']}", "IRIS_BUILD_DIR": str(BUILD)}
        cmd = [sys.executable, str(REPO / "experiments" / "split_render.py"), str(SCENE), "--spp", "10", "--tasks", "3",
               "--out", str(self.tmp / "split"), "--slurm-account", "proj7"]
        r = subprocess.run(cmd + ["--submit", "--", *self.ARGS], env=env, capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        calls = (bindir / "calls.txt").read_text().splitlines()
        self.assertEqual(len(calls), 2)
        self.assertTrue(calls[0].endswith("split_render.sh"), calls)
        self.assertIn("--dependency=afterok:101", calls[1])
        self.assertIn("#SBATCH --account=proj7", (self.tmp / "split" / "split_render.sh").read_text())
        # Task 1 is done by hand; the resubmission submits tasks 0 and 2 only.
        subprocess.run(["bash", str(self.tmp / "split" / "split_render.sh")], env={**env, "SLURM_ARRAY_TASK_ID": "1"},
                       check=True, capture_output=True)
        r = subprocess.run(cmd + ["--resubmit", "--", *self.ARGS], env=env, capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("task 0 0:3: missing", r.stdout)
        calls = (bindir / "calls.txt").read_text().splitlines()
        self.assertIn("--array=0,2", calls[2])
        self.assertIn("--dependency=afterok:103", calls[3])


class ExperimentSubmitTest(TempDir):
    def fake_build(self) -> Path:
        bdir = self.tmp / "build"
        bdir.mkdir()
        (bdir / "render").write_text(f"#!/bin/sh\nexec {sys.executable} {HERE / 'fake_render.py'} \"$@\"\n")
        (bdir / "render").chmod(0o755)
        return bdir

    def run_experiment(self, extra):
        sys.path.insert(0, str(REPO / "experiments"))
        import thesis_reproduction
        out = self.tmp / "out"
        argv = ["--quick", "--build-dir", str(self.fake_build() if not (self.tmp / "build").exists() else self.tmp / "build"),
                "--out", str(out), "--slurm", *extra]
        stdout, stderr = io.StringIO(), io.StringIO()
        with redirect_stdout(stdout), redirect_stderr(stderr):
            code = run(thesis_reproduction.ThesisReproduction(), argv)
        self.assertEqual(code, 0, stderr.getvalue())
        return out, stdout.getvalue()

    def test_submit_is_an_array_plus_an_afterok_collect_job_and_resubmit_skips_valid_images(self):
        bindir = self.fake_sbatch()
        old = os.environ["PATH"]
        os.environ["PATH"] = f"{bindir}:{old}"
        try:
            out, stdout = self.run_experiment(["--submit", "--slurm-account", "proj7"])
            calls = (bindir / "calls.txt").read_text().splitlines()
            self.assertEqual(len(calls), 2, calls)
            n = int(stdout.split("(")[1].split(" of ")[1].split()[0])
            self.assertIn(f"--array={','.join(str(i) for i in range(n))}", calls[0])
            self.assertIn("--dependency=afterok:101 --kill-on-invalid-dep=yes", calls[1])
            self.assertIn("--collect-only", calls[1])
            self.assertIn("--account=proj7", calls[1])
            # Task 1 finished, task 2 was interrupted (a partial image), the rest never ran.
            script = next(out.glob("slurm_*.sh"))
            images = {}
            for task in (1, 2):
                before = set(out.rglob("*.exr"))
                subprocess.run(["bash", str(script)], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(task)}, check=True,
                               capture_output=True)
                (images[task],) = set(out.rglob("*.exr")) - before
            pixels = exr.read_exr(str(images[2]))[0]
            exr.write_exr(str(images[2]), pixels[..., :3], metadata={"iris.interrupted": "1"})
            _, stdout = self.run_experiment(["--resubmit"])
            calls = (bindir / "calls.txt").read_text().splitlines()
            resubmitted = calls[2].split("--array=")[1].split()[0].split(",")
            self.assertEqual(resubmitted, [str(i) for i in range(n) if i != 1])
            self.assertIn("task 2", stdout)
            self.assertIn("interrupted or unreadable image", stdout)
            self.assertIn("--dependency=afterok:103", calls[3])
        finally:
            os.environ["PATH"] = old


class OutputCheckTest(TempDir):
    def test_interrupted_or_truncated_images_do_not_count(self):
        class Job:
            pass
        job = Job()
        job.output = self.tmp / "a.exr"
        self.assertFalse(runner.output_ok(job))
        exr.write_exr(str(job.output), __import__("numpy").zeros((2, 2, 3), "float32"), metadata={"iris.interrupted": "0"})
        self.assertTrue(runner.output_ok(job))
        exr.write_exr(str(job.output), __import__("numpy").zeros((2, 2, 3), "float32"), metadata={"iris.interrupted": "1"})
        self.assertFalse(runner.output_ok(job))
        job.output.write_bytes(job.output.read_bytes()[:20])
        self.assertFalse(runner.output_ok(job))


if __name__ == "__main__":
    unittest.main()
