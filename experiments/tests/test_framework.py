"""Tests of the experiment framework (run by ctest through tests/experiments/test_experiments_scripts.cpp, or
directly: IRIS_BUILD_DIR=build python3 -m unittest discover -s experiments/tests).

Uses a fake renderer (fake_render.py) and the real compare / merge tools from $IRIS_BUILD_DIR."""
import csv
import io
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from iris_experiments import collect, exr, report, runner, scenes, slurm  # noqa: E402
from iris_experiments.errors import ExperimentError  # noqa: E402
from iris_experiments.experiment import run  # noqa: E402
from iris_experiments.sweep import Sweep, expand  # noqa: E402
from iris_experiments.tools import REPO  # noqa: E402

BUILD = Path(os.environ.get("IRIS_BUILD_DIR", REPO / "build")).resolve()
HAVE_TOOLS = (BUILD / "compare").exists() and (BUILD / "merge").exists()

SCENE_XML = """<?xml version="1.0"?>
<scene version="3.0.0">
    <default name="res" value="16"/>
    <default name="thickness" value="76"/>
    <default name="offset" value="0"/>
    <bsdf type="diffuse"/>
</scene>
"""


class TempDirTest(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="iris_exp_test_"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def fake_build(self):
        """A build folder with the fake render and links to the real compare / merge."""
        bdir = self.tmp / "build"
        if bdir.exists():
            return bdir
        bdir.mkdir()
        render = bdir / "render"
        render.write_text(f"#!/bin/sh\nexec {sys.executable} {HERE / 'fake_render.py'} \"$@\"\n")
        render.chmod(0o755)
        for tool in ("compare", "merge"):
            if (BUILD / tool).exists():
                (bdir / tool).symlink_to(BUILD / tool)
        return bdir

    def scene(self, text=SCENE_XML, name="scene.xml"):
        path = self.tmp / name
        path.write_text(text)
        return path


class SweepTest(TempDirTest):
    def test_paths_are_deterministic_and_commands_complete(self):
        s = Sweep("spectral", {"tf": "scenes/a.xml", "other": "scenes/b.xml"},
                  axes={"spectral_samples": [1, 4], "thickness": [76, 200.5]},
                  fixed={"mode": "spectral", "spp": 8, "seed": 3}, per_scene={"tf": {"res": 32}})
        jobs = s.jobs(self.tmp, Path("/x/render"))
        again = s.jobs(self.tmp, Path("/x/render"))
        self.assertEqual([j.output for j in jobs], [j.output for j in again])
        self.assertEqual(len(jobs), 8)
        self.assertEqual([j.index for j in jobs], list(range(8)))
        self.assertEqual(jobs[1].output, self.tmp / "renders/spectral/tf/spectral_samples=1_thickness=200.5.exr")
        self.assertEqual(jobs[0].command,
                         ["/x/render", "scenes/a.xml", "-o", str(jobs[0].output), "--mode", "spectral", "--spp", "8",
                          "--seed", "3", "-D", "res=32", "--spectral-samples", "1", "-D", "thickness=76", "--quiet"])
        self.assertNotIn("res=32", jobs[4].command)  # per-scene setting only for "tf"
        self.assertEqual(jobs[4].label, "other")

    def test_variant_axis_applies_its_settings_together(self):
        s = Sweep("v", {"a": "s.xml"}, axes={"variant": [{"name": "two_beam", "phase_mode": "truncated", "bounces": 1},
                                                          {"name": "exact", "phase_mode": "exact"}]})
        jobs = s.jobs(self.tmp, Path("render"))
        self.assertEqual([j.output.name for j in jobs], ["variant=two_beam.exr", "variant=exact.exr"])
        self.assertEqual(jobs[0].settings["variant"], "two_beam")
        self.assertEqual(jobs[0].command[-5:], ["-D", "phase_mode=truncated", "-D", "bounces=1", "--quiet"])
        self.assertNotIn("variant=two_beam", " ".join(jobs[0].command[4:]))

    def test_tuples_linked_values_and_duplicates(self):
        s = Sweep("w", {"a": "s.xml"}, axes={"wavelengths": [(680, 520, 400)]}, fixed={"mode": "rgb"},
                  linked={"wavelengths": "rgb_wavelengths"})
        (job,) = s.jobs(self.tmp, Path("render"))
        self.assertEqual(job.output.name, "wavelengths=680_520_400.exr")
        self.assertIn("wavelengths=680,520,400", job.command)
        self.assertEqual(job.command[job.command.index("--rgb-wavelengths") + 1], "680,520,400")
        with self.assertRaises(ValueError):
            expand([s, s], self.tmp, Path("render"))
        two = expand([s, Sweep("v", {"a": "s.xml"}, axes={"seed": [1, 2]})], self.tmp, Path("render"))
        self.assertEqual([j.index for j in two], [0, 1, 2])


class SlurmTest(TempDirTest):
    def test_script_has_one_array_task_per_job_running_its_command(self):
        bdir = self.fake_build()
        scene = self.scene()
        s = Sweep("seeds", {"tf": str(scene)}, axes={"seed": [1, 2, 3]}, fixed={"spp": 2})
        jobs = expand([s], self.tmp / "out", bdir / "render")
        path = slurm.write_slurm_script(self.tmp / "run.sh", jobs, job_name="iris-test", time="00:10:00",
                                        cpus_per_task=4, partition="short")
        text = path.read_text()
        self.assertIn("#SBATCH --array=0-2\n", text)
        self.assertIn("#SBATCH --cpus-per-task=4\n", text)
        self.assertIn("#SBATCH --partition=short\n", text)
        self.assertIn("#SBATCH --time=00:10:00\n", text)
        positions = [text.index(j.output.name) for j in jobs]
        self.assertEqual(positions, sorted(positions))  # task i is job i
        self.assertEqual(subprocess.run(["bash", "-n", str(path)]).returncode, 0)
        # Run task 1 as Slurm would: it must render exactly job 1.
        env = dict(os.environ, SLURM_ARRAY_TASK_ID="1")
        proc = subprocess.run(["bash", str(path)], env=env, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertTrue(jobs[1].output.exists())
        self.assertFalse(jobs[0].output.exists())
        self.assertEqual(exr.read_exr_metadata(str(jobs[1].output))["iris.seed"], "2")


class WritersTest(TempDirTest):
    def test_csv_and_json(self):
        rows = [{"a": 1, "b": 0.5}, {"a": 2, "c": "x,y", "b": math.inf}]
        collect.write_csv(rows, self.tmp / "r.csv")
        back = collect.read_csv(self.tmp / "r.csv")
        self.assertEqual(list(back[0].keys()), ["a", "b", "c"])
        self.assertEqual(back[1], {"a": "2", "b": "inf", "c": "x,y"})
        collect.write_json({"rows": rows}, self.tmp / "r.json")
        data = json.loads((self.tmp / "r.json").read_text())
        self.assertIsNone(data["rows"][1]["b"])
        self.assertEqual(data["rows"][0]["b"], 0.5)

    def test_markdown_report(self):
        machine = report.machine_info()
        self.assertEqual(machine["nproc"], os.cpu_count())
        self.assertTrue(machine["cpu"])
        path = report.write_report(self.tmp / "report.md", title="T", question="Q?", machine=machine,
                                   settings={"spp": 4}, conclusions=["relMSE halves"],
                                   sections=[("Results", report.markdown_table([{"x": 1.23456789, "y": "a|b"}], ["x", "y"]))],
                                   figures=["fig.png"])
        text = path.read_text()
        for expected in ("# T", "Q?", f"- nproc: {os.cpu_count()}", "- spp: 4", "- relMSE halves", "| 1.235 | a\\|b |",
                         "![fig](fig.png)", machine["uname"]):
            self.assertIn(expected, text)


class ExrTest(TempDirTest):
    def test_round_trip_and_metadata(self):
        img = np.random.default_rng(3).normal(size=(5, 7, 3)).astype(np.float32)
        exr.write_exr(str(self.tmp / "a.exr"), img, metadata={"iris.spp": 16})
        pixels, names, meta = exr.read_exr(str(self.tmp / "a.exr"))
        np.testing.assert_array_equal(exr.rgb_of(pixels, names), img)
        self.assertEqual(meta["iris.spp"], "16")
        self.assertEqual(exr.read_exr_metadata(str(self.tmp / "a.exr"))["iris.spp"], "16")
        self.assertEqual(exr.exr_size(str(self.tmp / "a.exr")), (7, 5))  # (width, height), header only
        (self.tmp / "bad.exr").write_text("not an image")
        with self.assertRaises(exr.ExrError):
            exr.exr_size(str(self.tmp / "bad.exr"))
        with self.assertRaises(exr.ExrError) as cm:
            exr.read_exr(str(self.tmp / "bad.exr"))
        self.assertIn("bad.exr", str(cm.exception))
        data = (self.tmp / "a.exr").read_bytes()
        (self.tmp / "cut.exr").write_bytes(data[:len(data) - 40])
        with self.assertRaises(exr.ExrError):
            exr.read_exr(str(self.tmp / "cut.exr"))


class HtmlPayloadBudgetTest(TempDirTest):
    """The viewers of one HTML report share a pixel budget (html_report.PAYLOAD_BUDGET): a report with
    many comparisons shows every image at a larger step, a small one at full resolution."""

    def comparison(self, name, size, tests):
        rng = np.random.default_rng(len(name))
        paths = []
        for i in range(1 + tests):
            path = self.tmp / f"{name}_{i}.exr"
            exr.write_exr(str(path), rng.random((size, size, 3)).astype(np.float32))
            paths.append(path)
        return {"title": name, "reference": paths[0], "tests": [(f"t{i}", p) for i, p in enumerate(paths[1:])]}

    def viewer_bytes(self, page):
        import re
        return [len(json.loads(m)["reference"]["data"]) + sum(len(t["data"]) for t in json.loads(m)["tests"])
                for m in re.findall(r'<script type="application/json" id="[^"]+">(.*?)</script>', page, re.S)]

    def write(self, comparisons):
        from iris_experiments import html_report
        path = html_report.write_html_report(self.tmp / "report.html", title="t", question="q", provenance={},
                                             machine={}, settings={}, conclusions=[], sections=[],
                                             comparisons=comparisons)
        return path.read_text()

    def test_many_comparisons_take_a_larger_step_within_the_budget(self):
        from iris_experiments import html_report
        small = [self.comparison("small", 64, 2)]
        self.assertEqual(html_report.report_min_step(small), 1)
        self.assertIn('"step": 1', self.write(small))
        # per_bounce_phase's shape: ten 256² images in two viewers, 5.2 MB of base64 at MAX_SIDE alone.
        many = [self.comparison("a", 256, 3), self.comparison("b", 256, 5)]
        self.assertGreater(sum(html_report.payload_bytes(256, 256, n, 1) for n in (4, 6)), html_report.PAYLOAD_BUDGET)
        step = html_report.report_min_step(many)
        self.assertEqual(step, 2)
        page = self.write(many)
        sizes = self.viewer_bytes(page)
        self.assertEqual(sizes, [html_report.payload_bytes(256, 256, 4, 2), html_report.payload_bytes(256, 256, 6, 2)])
        self.assertLessEqual(sum(sizes), html_report.PAYLOAD_BUDGET)
        self.assertIn("Shown at 1/2 resolution", page)
        # A smaller budget steps further; one that no step meets stops at the largest step tried.
        self.assertEqual(html_report.report_min_step(many, budget=sum(sizes) // 2), 3)
        self.assertEqual(html_report.report_min_step(many, budget=0), 64)


@unittest.skipUnless(HAVE_TOOLS, f"compare/merge not built in {BUILD}")
class MergeAndCompareTest(TempDirTest):
    def test_merge_weights_by_spp_and_reads_back_zip_exr(self):
        rng = np.random.default_rng(0)
        a, b = rng.random((6, 9, 3)).astype(np.float32), rng.random((6, 9, 3)).astype(np.float32)
        meta = {"iris.mode": "spectral", "iris.scene": "s.xml", "iris.spectral_samples": "4"}
        exr.write_exr(str(self.tmp / "a.exr"), a, metadata={**meta, "iris.spp": 1, "iris.seed": 1})
        exr.write_exr(str(self.tmp / "b.exr"), b, metadata={**meta, "iris.spp": 3, "iris.seed": 2})
        out = collect.merge(BUILD / "merge", [self.tmp / "a.exr", self.tmp / "b.exr"], self.tmp / "m.exr")
        pixels, names, m = exr.read_exr(str(out))   # written by OpenEXR with ZIP compression
        np.testing.assert_allclose(exr.rgb_of(pixels, names), (a + 3 * b) / 4, rtol=1e-6, atol=1e-7)
        self.assertEqual(m["iris.spp"], "4")
        exr.write_exr(str(self.tmp / "c.exr"), a, metadata={**meta, "iris.mode": "rgb", "iris.spp": 1, "iris.seed": 3})
        with self.assertRaises(ExperimentError) as cm:
            collect.merge(BUILD / "merge", [self.tmp / "a.exr", self.tmp / "c.exr"], self.tmp / "bad.exr")
        self.assertIn("c.exr", str(cm.exception))
        self.assertIn("iris.mode", str(cm.exception))

    def test_compare_json(self):
        ref = np.full((4, 4, 3), 0.3, np.float32)
        exr.write_exr(str(self.tmp / "r.exr"), ref)
        exr.write_exr(str(self.tmp / "t.exr"), ref + 0.1)
        m = collect.compare(BUILD / "compare", self.tmp / "t.exr", self.tmp / "r.exr")
        self.assertAlmostEqual(m["mse"], 0.01, places=6)
        self.assertAlmostEqual(m["relmse"], 0.01 / 0.1, places=5)
        self.assertAlmostEqual(m["psnr"], 20.0, places=3)
        self.assertEqual(collect.compare(BUILD / "compare", self.tmp / "r.exr", self.tmp / "r.exr")["psnr"], math.inf)
        exr.write_exr(str(self.tmp / "small.exr"), ref[:2])
        with self.assertRaises(ExperimentError) as cm:
            collect.compare(BUILD / "compare", self.tmp / "small.exr", self.tmp / "r.exr")
        self.assertIn("small.exr", str(cm.exception))


    def test_band_errors_of_spectral_images(self):
        names = ("S0.555,000000nm", "S0.455,000000nm", "S0.655,000000nm")
        ref = np.full((4, 4, 3), 0.5, np.float32)
        test = ref.copy()
        test[:, :, 0] += 0.1   # only the 555 nm band differs
        exr.write_exr(str(self.tmp / "r.exr"), ref, channels=names)
        exr.write_exr(str(self.tmp / "t.exr"), test, channels=names)
        bands = collect.band_errors(BUILD / "compare", self.tmp / "t.exr", self.tmp / "r.exr")
        self.assertEqual(list(bands), [455.0, 555.0, 655.0])
        self.assertAlmostEqual(bands[555.0]["mse"], 0.01, places=6)
        self.assertEqual(bands[455.0]["mse"], 0.0)
        exr.write_exr(str(self.tmp / "rgb.exr"), ref)
        with self.assertRaises(ExperimentError):
            collect.band_errors(BUILD / "compare", self.tmp / "rgb.exr", self.tmp / "rgb.exr")


class SceneCheckTest(TempDirTest):
    def test_reports_missing_scene_parameter_and_material(self):
        scene = self.scene()
        rel = os.path.relpath(scene, REPO)
        plugins = {"MaterialRegistry": {"diffuse"}}
        scenes.check_scenes([scenes.SceneSpec(rel, materials=("diffuse",), params=("thickness",))], plugins=plugins)
        with self.assertRaises(ExperimentError) as cm:
            scenes.check_scenes([scenes.SceneSpec("scenes/nope.xml", note="being written"),
                                 scenes.SceneSpec(rel, materials=("thinfilm",), params=("alpha",))], plugins=plugins)
        msg = str(cm.exception)
        self.assertIn("scenes/nope.xml: scene not available yet (being written)", msg)
        self.assertIn("material 'thinfilm' is not available yet", msg)
        self.assertIn('<default name="alpha"', msg)
        bad = self.scene(SCENE_XML.replace("diffuse", "mystery"), "bad.xml")
        with self.assertRaises(ExperimentError) as cm:
            scenes.check_scenes([scenes.SceneSpec(os.path.relpath(bad, REPO))], plugins=plugins)
        self.assertIn("'mystery'", str(cm.exception))

    def test_registered_plugins_found_in_sources(self):
        self.assertIn("diffuse", scenes.registered_plugins()["MaterialRegistry"])


class RunnerTest(TempDirTest):
    def test_failures_are_reported_and_existing_outputs_skipped(self):
        bdir = self.fake_build()
        scene = self.scene()
        jobs = expand([Sweep("s", {"a": str(scene)}, axes={"fail": [0, 1]}, fixed={"spp": 1})], self.tmp, bdir / "render")
        results = runner.run_local(jobs, parallel=2, log=lambda *_: None)
        self.assertTrue(results[0].ok)
        self.assertFalse(results[1].ok)
        self.assertIn("not registered", results[1].message)
        self.assertIn("not registered", jobs[1].output.with_suffix(".log").read_text())
        again = runner.run_local(jobs[:1], log=lambda *_: None)
        self.assertTrue(again[0].skipped)


@unittest.skipUnless(HAVE_TOOLS, f"compare/merge not built in {BUILD}")
class ExperimentEndToEndTest(TempDirTest):
    """The experiment scripts with the fake renderer: the conclusions follow from the data."""

    def run_experiment(self, module, extra=(), scene_text=SCENE_XML):
        sys.path.insert(0, str(REPO / "experiments"))
        mod = __import__(module)
        exp_class = [v for v in vars(mod).values() if isinstance(v, type) and v.__module__ == module
                     and hasattr(v, "analyse")][0]
        out = self.tmp / "out"
        argv = ["--quick", "--build-dir", str(self.fake_build()), "--out", str(out), "--scene", str(self.scene(scene_text)),
                "--parallel", "2", *extra]
        stdout, stderr = io.StringIO(), io.StringIO()
        with redirect_stdout(stdout), redirect_stderr(stderr):
            code = run(exp_class(), argv)
        self.assertEqual(code, 0, stderr.getvalue())
        return out, stdout.getvalue()

    def test_channel_count(self):
        out, _ = self.run_experiment("channel_count")
        rows = collect.read_csv(out / "results.csv")
        spectral = [r for r in rows if r["mode"] == "spectral"]
        self.assertEqual([int(r["spectral_samples"]) for r in spectral], [1, 2, 4, 8, 16, 32])
        relmse = [float(r["relmse"]) for r in spectral]
        self.assertLess(relmse[-1], relmse[0])  # noise 0.2/sqrt(spp·N) falls with N
        text = (out / "report.md").read_text()
        best = min(spectral, key=lambda r: float(r["relmse"]))["wavelengths_per_path"]
        self.assertIn(f"lowest relMSE at N = {best}.", text)
        self.assertIn("## Machine", text)
        self.assertTrue((out / "thin_film_images.jpg").stat().st_size > 1000)
        ref_meta = exr.read_exr_metadata(str(out / "reference" / "thin_film.exr"))
        self.assertEqual(ref_meta["iris.spp"], "32")  # 2 seeds x 16 spp merged

    def test_sampler_efficiency_reports_the_variance_reduction(self):
        # The fake renderer scales its noise by 0.8, 0.7, 0.5, 0.4 for stratified, multijitter, sobol,
        # highdimsobol: relMSE falls by 1/0.64, 1/0.49, 1/0.25, 1/0.16 (within the reference's own noise).
        out, _ = self.run_experiment("sampler_efficiency")
        text = (out / "report.md").read_text()
        self.assertIn("Variance reduction at equal spp", text)
        for name, factor in (("stratified", 1 / 0.64), ("multijitter", 1 / 0.49), ("sobol", 4.0), ("highdimsobol", 1 / 0.16)):
            line = next(l for l in text.splitlines() if l.startswith(f"- ") and f": {name} lowers relMSE" in l)
            lo, hi = (float(x) for x in line.split("by a factor ")[1].split(" over")[0].split(" to "))
            self.assertGreater(lo, 0.8 * factor, line)
            self.assertLess(hi, 1.2 * factor, line)

    def test_media_mis_reports_the_error_ratio(self):
        # The fake renderer ignores the integrator: both variants have the same noise, so the ratio
        # table exists and the conclusion states a ratio for the whole spp range.
        out, _ = self.run_experiment("media_mis")
        text = (out / "report.md").read_text()
        self.assertIn("Error ratio at equal spp", text)
        line = next(l for l in text.splitlines() if "at equal spp volpathmis' relMSE is" in l)
        self.assertIn("over 2..8 spp", line)

    def test_per_bounce_phase_without_real_difference_has_zero_excess(self):
        # The fake renderer ignores phase_model: both variants are the same image, so the measured
        # difference must equal the noise floor exactly.
        text = SCENE_XML.replace('<default name="offset"', '<default name="phase_mode" value="exact"/>\n'
                                 '    <default name="bounces" value="1"/>\n    <default name="phase" value="true"/>\n'
                                 '    <default name="offset"')
        out, _ = self.run_experiment("per_bounce_phase", scene_text=text)
        rows = collect.read_csv(out / "results.csv")
        self.assertEqual(len(rows), (3 + 5) * 3)  # variants of both scenes x quick thicknesses
        for r in rows:
            self.assertEqual(float(r["excess_de00_mean"]), 0.0)
        report_text = (out / "report.md").read_text()
        self.assertEqual(report_text.count("just-noticeable ΔE00 = 1: none."), 2 + 4)  # all but the references

    def test_slurm_and_dry_run_modes_do_not_render(self):
        out, stdout = self.run_experiment("approximation_error", ["--slurm"])
        script = (out / "slurm_approximation_error.sh").read_text()
        # 5 thicknesses x (2 reference seeds + rgb + spectral) + convergence: 2 configurations x 2 spp levels x
        # 2 seeds + 2 x 2 equal-time renders.
        self.assertIn("#SBATCH --array=0-31\n", script)
        self.assertFalse((out / "renders").exists())
        self.assertIn("sbatch", stdout)

    def test_spp_scale_and_dry_run(self):
        _, stdout = self.run_experiment("channel_count", ["--dry-run", "--spp-scale", "0.5"])
        lines = stdout.strip().splitlines()
        by_sweep = {}
        for line in lines:
            by_sweep.setdefault(line.split("/renders/")[1].split("/")[0], []).append(line)
        self.assertEqual(len(by_sweep["reference"]), 2)
        self.assertEqual(len(by_sweep["spectral"]) + len(by_sweep["rgb"]), 6 + 1)  # wavelength counts, rgb
        self.assertTrue(all(" --spp 2 " in l for l in by_sweep["spectral"] + by_sweep["rgb"]))  # quick spp 4 halved
        self.assertTrue(all(" --spp 8 " in l for l in by_sweep["reference"]))  # reference 16 halved
        # Convergence: quick levels 1, 2, 4 halved are 1, 1, 2 -> 1, 2 (no duplicate jobs), 2 seeds, the 4
        # quick configurations (the fake renderer has no --wavelength-sampling: "N=4 independent" is left out).
        conv = by_sweep["convergence"]
        self.assertEqual(len(conv), 4 * 2 * 2)
        self.assertEqual(sorted({l.split(" --spp ")[1].split()[0] for l in conv}), ["1", "2"])
        self.assertFalse(any("independent" in l for l in lines))
        equal = by_sweep["convergence_equal_time"]
        self.assertEqual(len(equal), 4 * 2)
        self.assertTrue(all(" --spp 0 " in l and " --time-limit 0.2 " in l for l in equal))  # spp 0 is not scaled
        self.assertFalse((self.tmp / "out").exists())

    def test_shards_render_disjoint_jobs_and_collect_makes_the_report(self):
        out, stdout = self.run_experiment("approximation_error", ["--shard", "0/2"])
        self.assertIn("shard 0/2: 16 of 32 render jobs", stdout)
        self.assertFalse((out / "report.md").exists())   # no report until every shard is done
        rendered = sorted(p.name for p in (out / "renders").rglob("*.exr"))
        self.assertEqual(len(rendered), 16)
        _, stdout = self.run_experiment("approximation_error", ["--shard", "1/2"])
        self.assertIn("all renders exist", stdout)
        self.assertEqual(len(list((out / "renders").rglob("*.exr"))), 32)
        out, _ = self.run_experiment("approximation_error", ["--collect-only"])
        html = (out / "report.html").read_text()
        self.assertIn("Convergence: relMSE", html)
        self.assertNotIn(" src='http", html)
        self.assertNotIn(' src="http', html)
        # Bad shard specifications are one-line errors (exit 2).
        err = io.StringIO()
        sys.path.insert(0, str(REPO / "experiments"))
        import approximation_error
        with redirect_stderr(err), redirect_stdout(io.StringIO()):
            code = run(approximation_error.ApproximationError(), ["--quick", "--shard", "2/2", "--build-dir",
                                                                   str(self.fake_build()), "--out", str(out)])
        self.assertEqual(code, 2)
        self.assertIn("--shard 2/2: need 0 <= I < N", err.getvalue())

    def test_missing_scene_fails_clearly(self):
        sys.path.insert(0, str(REPO / "experiments"))
        import thesis_reproduction
        err = io.StringIO()
        exp = thesis_reproduction.ThesisReproduction()
        exp.scene_specs = {"granier": scenes.SceneSpec("scenes/does_not_exist.xml", note="being written")}
        with redirect_stderr(err), redirect_stdout(io.StringIO()):
            code = run(exp, ["--quick", "--build-dir", str(self.fake_build()), "--out", str(self.tmp / "o")])
        self.assertEqual(code, 2)
        self.assertIn("scenes/does_not_exist.xml: scene not available yet", err.getvalue())


class ConvergenceMathTest(unittest.TestCase):
    def test_fit_interpolation_and_common_values(self):
        from iris_experiments import convergence as cv
        times = [1.0, 2.0, 4.0, 8.0]
        errors = [0.8, 0.4, 0.2, 0.1]         # error ∝ 1 / time
        slope, icpt = cv.fit_loglog(times, errors)
        self.assertAlmostEqual(slope, -1.0, places=12)
        self.assertAlmostEqual(10 ** icpt, 0.8, places=12)
        t, extrapolated = cv.time_to_error(times, errors, 0.3, (slope, icpt))
        self.assertAlmostEqual(t, 0.8 / 0.3, places=9)   # on the line through (2, 0.4) and (4, 0.2)
        self.assertFalse(extrapolated)
        t, extrapolated = cv.time_to_error(times, errors, 0.05, (slope, icpt))
        self.assertAlmostEqual(t, 16.0, places=9)
        self.assertTrue(extrapolated)
        e, extrapolated = cv.loglog_at(times, errors, 3.0, (slope, icpt))
        self.assertAlmostEqual(e, 0.8 / 3.0, places=9)
        self.assertFalse(extrapolated)
        self.assertAlmostEqual(cv.common_value([0.1, 0.2], [1.0, 0.8]), math.sqrt(0.2 * 0.8))
        self.assertEqual(cv.common_value([0.5, 0.2], [0.4, 0.8]), 0.5)   # no overlap: the largest low
        m, sem = cv.mean_sem([1.0, 3.0])
        self.assertEqual(m, 2.0)
        self.assertAlmostEqual(sem, 1.0)


class ProvenanceAndStatusTest(unittest.TestCase):
    def test_dirty_tree_names_no_commit_and_status_marks_stale_results(self):
        prov = report.provenance()
        self.assertIn(prov["state"], ("clean", "dirty", "unknown"))
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True, text=True).stdout.strip()
        if prov["state"] == "dirty":
            self.assertIsNone(prov["commit"])
            self.assertNotIn(head[:7], prov["text"])
            self.assertIn("not the results of any commit", prov["text"])
        elif prov["state"] == "clean":
            self.assertEqual(prov["text"], f"commit {head} (clean working tree)")
        sys.path.insert(0, str(REPO / "experiments"))
        import run_all
        fields = run_all._report_fields("# T\n\nCommand:\n\n    python3 x.py --spp-scale 0.5\n\n## Machine\n\n"
                                        "- git: abc (with uncommitted changes)\n- date_utc: 2026\n\n## Settings\n\n"
                                        "- spp scale: 0.5 (every ...)\n\n## Conclusions (computed)\n\n- one\n- two\n\n"
                                        "## Results\n\n| a |\n")
        self.assertEqual(fields["conclusions"], ["one", "two"])
        self.assertEqual(fields["command"], "python3 x.py --spp-scale 0.5")
        self.assertTrue(fields["spp scale"].startswith("0.5"))
        status = run_all.status_markdown(["channel_count"])
        self.assertIn("## channel_count", status)
        self.assertIn("- status: ", status)
        # A dirty tree is STALE whatever the scale; a clean one at scaled counts is SCALED.
        self.assertTrue(run_all.result_status("channel_count", fields).startswith("STALE: not made from a clean commit"))
        # A commit this checkout does not know cannot be compared with the sources, and says so.
        unknown = dict(fields, git="commit abc (clean working tree)")
        self.assertEqual(run_all.result_status("channel_count", unknown),
                         "SCALED: sample counts x 0.5 of the experiment's definition, from a clean commit (its commit "
                         "is not in this checkout: sources not compared)")
        # A result's commit against HEAD, in a repository of its own (CI's checkout may be shallow):
        # nothing changed since, so current (or SCALED); a renderer source changed since, so OUTDATED;
        # a change outside the sources it depends on (docs) keeps it current.
        repo = Path(tempfile.mkdtemp(prefix="iris_status_repo_"))
        self.addCleanup(shutil.rmtree, repo, ignore_errors=True)

        def git(*a):
            return subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", *a], cwd=repo, check=True,
                                  capture_output=True, text=True).stdout.strip()
        git("init", "-q")
        (repo / "core").mkdir()
        (repo / "core" / "a.cpp").write_text("1")
        (repo / "docs").mkdir()  # the layer table run_all.renderer_sources reads
        (repo / "docs" / "architecture.md").write_text("| 0 | `core/` | x | - |\n| 7 | `experiments/` | x | - |\n"
                                                     "| 8 | `tests/` | x | - |\n")
        git("add", "-A")
        git("commit", "-q", "-m", "a")
        made = git("rev-parse", "HEAD")
        clean = dict(fields, git=f"commit {made} (clean working tree)")
        self.assertEqual(run_all.result_status("channel_count", clean, repo),
                         "SCALED: sample counts x 0.5 of the experiment's definition, from a clean commit")
        self.assertEqual(run_all.result_status("channel_count", dict(clean, **{"spp scale": ""}), repo), "current")
        self.assertEqual(run_all.renderer_sources(repo), ["CMakeLists.txt", "scenes", "core"])
        (repo / "docs" / "d.md").write_text("doc")
        (repo / "tests").mkdir()  # a layer above experiments/ is no source of a result
        (repo / "tests" / "t.cpp").write_text("t")
        git("add", "-A")
        git("commit", "-q", "-m", "docs")
        self.assertEqual(run_all.result_status("channel_count", dict(clean, **{"spp scale": ""}), repo), "current")
        (repo / "core" / "a.cpp").write_text("2")
        git("commit", "-q", "-am", "code")
        self.assertEqual(run_all.sources_changed(made, "channel_count", repo), ["core/a.cpp"])
        self.assertEqual(run_all.result_status("channel_count", dict(clean, **{"spp scale": ""}), repo),
                         f"OUTDATED: 1 source files of the renderer or of this experiment changed since commit "
                         f"{made[:7]} (core/a.cpp); regenerate it")


if __name__ == "__main__":
    unittest.main()
