"""Tests against a real Slurm (run by .ci/slurm-test, which starts slurmctld + slurmd on this machine
and sets SLURM_CONF): jobs go through sbatch, are waited for with squeue/scontrol (bounded), and
their results are read back.

- a split render (3 array tasks + a merge job with afterok) equals the unsplit render bit for bit;
- a task killed mid-render (scancel) is reported with its log, and --resubmit reruns only that task,
  which resumes from its film state; the merge then equals the unsplit render;
- an experiment submitted with --slurm --submit (array + collect job) renders the same images as the
  local runner, bit for bit, and its report's results table equals the local one (but for paths
  and measured times).
Not part of the ctest suite (needs the daemons); the Slurm-free parts are in test_split_render.py.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
import time
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from iris_experiments import collect, exr, slurm  # noqa: E402
from iris_experiments.tools import REPO, build_dir  # noqa: E402

BUILD = build_dir()
WORK = Path(os.environ.get("IRIS_SLURM_WORK", "/tmp")) / "tests"
SCENE = REPO / "scenes" / "default.xml"
PY = sys.executable
WAIT = 300  # seconds: the bound of every wait


def run(cmd, **kw):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)


def pixels(path):
    return exr.read_exr(str(path))[0]


def submitted_ids(stdout: str) -> list:
    return re.findall(r"job (\d+)", stdout)


def split(out: Path, spp: int, tasks: int, *extra, render_args=()):
    return run([PY, REPO / "experiments" / "split_render.py", SCENE, "--spp", spp, "--tasks", tasks, "--out", out,
                "--build-dir", BUILD, "--slurm-cpus", 1, "--slurm-mem", "500M", "--slurm-time", "00:10:00", *extra,
                "--", *render_args])


def unsplit(out: Path, spp: int, render_args) -> Path:
    path = out / "unsplit.exr"
    r = run([BUILD / "render", SCENE, "--spp", spp, "-o", path, "--no-png", "--quiet", *render_args])
    assert r.returncode == 0, r.stderr
    return path


class SlurmClusterTest(unittest.TestCase):
    def test_0_sbatch_runs_a_job(self):
        out = WORK / "hello.out"
        out.parent.mkdir(parents=True, exist_ok=True)
        jid = slurm.sbatch(None, wrap="echo hello from $SLURM_JOB_ID", options=[f"--output={out}"])
        states = slurm.wait([jid], WAIT)
        self.assertEqual(states[jid], "COMPLETED", states)
        self.assertEqual(out.read_text().strip(), f"hello from {jid}")

    def test_1_split_render_merges_to_the_unsplit_image(self):
        out = WORK / "split"
        args = ("--seed", "7", "-D", "res=40", "--threads", "1")
        r = split(out, 24, 3, "--submit", render_args=args)
        self.assertEqual(r.returncode, 0, r.stderr)
        ids = submitted_ids(r.stdout)
        self.assertEqual(len(ids), 2, r.stdout)
        states = slurm.wait(ids, WAIT)
        self.assertEqual(sorted(states), sorted([f"{ids[0]}_{i}" for i in range(3)] + [ids[1]]), states)
        self.assertTrue(all(s == "COMPLETED" for s in states.values()), states)
        self.assertTrue((pixels(out / "merged.exr") == pixels(unsplit(out, 24, args))).all())
        self.assertEqual(exr.read_exr_metadata(str(out / "merged.exr"))["iris.spp"], "24")

    def test_2_killed_task_is_recovered_by_resubmission(self):
        out = WORK / "killed"
        # ~5 s per task on one thread: long enough to be killed mid-render after its first save.
        args = ("--seed", "3", "-D", "res=48", "--threads", "1")
        spp, tasks = 1800, 3
        r = split(out, spp, tasks, "--submit", "--checkpoint-every", "0.5", render_args=args)
        self.assertEqual(r.returncode, 0, r.stderr)
        array, merge = submitted_ids(r.stdout)
        deadline = time.monotonic() + WAIT
        while not (out / "shard_1.state").exists():   # task 1 is running and has saved a pass
            self.assertLess(time.monotonic(), deadline, slurm.job_states(array))
            time.sleep(0.1)
        self.assertEqual(run(["scancel", f"{array}_1"]).returncode, 0)
        states = slurm.wait([array, merge], WAIT)
        self.assertEqual(states[f"{array}_1"], "CANCELLED", states)
        self.assertEqual(states[f"{array}_0"], "COMPLETED", states)
        self.assertEqual(states[f"{array}_2"], "COMPLETED", states)
        self.assertEqual(states[merge], "CANCELLED", states)      # afterok can never be met
        self.assertFalse((out / "merged.exr").exists())

        status = split(out, spp, tasks, "--status", render_args=args)
        self.assertEqual(status.returncode, 1, status.stdout)
        self.assertRegex(status.stdout, r"task 1 600:1200: incomplete \(\d+ of 600 samples per pixel\); log .*shard_1\.")
        self.assertIn("task 0 0:600: complete", status.stdout)
        finished = {i: (out / f"shard_{i}.state").stat().st_mtime_ns for i in (0, 2)}

        again = split(out, spp, tasks, "--resubmit", render_args=args)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("(tasks 1)", again.stdout)
        array2, merge2 = submitted_ids(again.stdout)
        states = slurm.wait([array2, merge2], WAIT)
        self.assertEqual(states, {f"{array2}_1": "COMPLETED", merge2: "COMPLETED"})
        # Finished shards were not rendered again; the killed one resumed from its film state.
        self.assertEqual({i: (out / f"shard_{i}.state").stat().st_mtime_ns for i in (0, 2)}, finished)
        log = (out / "logs" / f"shard_1.{array2}.out").read_text()
        self.assertIn("--resume", log)
        self.assertTrue((pixels(out / "merged.exr") == pixels(unsplit(out, spp, args))).all())

    def test_3_experiment_submitted_to_slurm_equals_the_local_run(self):
        exp = "thesis_reproduction"   # every image deterministic but its time-limited equal-time renders
        local, cluster = WORK / "exp-local", WORK / "exp-slurm"
        common = ["--quick", "--threads", "1", "--build-dir", BUILD, "--force"]
        r = run([PY, REPO / "experiments" / f"{exp}.py", *common, "--out", local])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run([PY, REPO / "experiments" / f"{exp}.py", *common, "--out", cluster, "--slurm", "--submit",
                 "--slurm-cpus", "1", "--slurm-mem", "500M", "--slurm-time", "00:10:00"])
        self.assertEqual(r.returncode, 0, r.stderr)
        ids = submitted_ids(r.stdout)
        states = slurm.wait(ids, WAIT)
        self.assertTrue(all(s == "COMPLETED" for s in states.values()), (states, r.stdout))
        self.assertTrue((cluster / "report.md").exists())
        images = sorted(p.relative_to(local) for p in local.rglob("*.exr"))
        self.assertEqual(images, sorted(p.relative_to(cluster) for p in cluster.rglob("*.exr")))
        self.assertGreater(len(images), 0)
        # Bit for bit, except the renders stopped by --time-limit (the convergence study's
        # "*_equal_time" sweep), whose sample counts depend on the machine's speed at that moment.
        deterministic = [rel for rel in images if not any(part.endswith("_equal_time") for part in rel.parts)]
        self.assertGreater(len(deterministic), len(images) // 2)
        for rel in deterministic:
            self.assertTrue((pixels(local / rel) == pixels(cluster / rel)).all(), rel)
        # The report's results equal the local run's, except paths and measured times.
        def results(folder):
            rows = collect.read_csv(folder / "results.csv")
            return [{k: v for k, v in r.items() if k != "output" and "time" not in k} for r in rows]
        self.assertEqual(results(local), results(cluster))


if __name__ == "__main__":
    unittest.main()
