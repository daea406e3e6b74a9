#!/usr/bin/env python3
"""How wrong is unpolarized transport for thin films? (issue 34, item 5; docs/polarization.md)

iris's spectral mode averages a film's |rs|² and |rp|² into one unpolarized reflectance at every
bounce; polarized mode (`render --mode polarized`) carries a Stokes vector per wavelength and applies
every surface's Mueller matrix. Both agree when nothing polarizes. This experiment renders scenes
where something does, in both modes, and measures the spectral (unpolarized) images against a
converged polarized reference:

  * glass_plate: a film-coated sphere (oxide film n = 2.1 on tantalum) seen in a polished black
    glass plate: two specular bounces; per film thickness and per viewing angle on the plate
    (Brewster's angle of n = 1.5 is 56.3°);
  * soap_film, oil_on_water: a free-standing water film and an oil film on water (the thinfilm
    parameters of scenes/default.xml) lit by a white area light seen through a linear polarizer that
    passes s- or p-polarized light; per thickness, viewing angle and polarizer orientation;
  * soap_sky, oil_sky: the same films under a polarized sky: a box of Rayleigh-scattering air in the
    film's mirror direction, lit by a sun 90° from the reflected ray (sky light s- or p-polarized at
    the film); per thickness, viewing angle and sun position;
  * camera_polarizer: scenes/default.xml's three film spheres seen through a linear polarizer in
    front of the lens, per orientation of its axis; and camera_stokes, the same view without the
    polarizer rendered by the `stokes` integrator: its S1 image (what unpolarized transport predicts
    to be 0), checked against S1 = I(0) - I(90) of the polarizer renders.

For every grid point: ΔE00 and relMSE of a spectral render against the polarized reference, next to
the noise floor (a polarized render of the same spp and another seed against the same reference),
and both modes' render times. At one point per scene a convergence study (error against wall time,
several seeds, and an equal-time budget) shows the cost of polarization: where the spectral curve
stops falling (its bias) and when the slower polarized mode overtakes it.

    python3 experiments/polarization.py [--quick] [--parallel N] [--slurm] ...
"""
import math
import statistics
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import exr, grid, stokes_images  # noqa: E402
from iris_experiments.collect import job_row  # noqa: E402
from iris_experiments.convergence import ConvergenceStudy  # noqa: E402
from iris_experiments.experiment import Analysis, ConvergenceExperiment, run  # noqa: E402
from iris_experiments.report import fmt, markdown_table  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402
from iris_experiments.sweep import Sweep, format_value, slug  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
PLATE = "experiments/scenes/polarization_glass_plate.xml"
LIGHT = "experiments/scenes/polarization_polarized_light.xml"
CAMERA = "experiments/scenes/polarization_camera_polarizer.xml"
SKY = "experiments/scenes/polarization_rayleigh_sky.xml"
STOKES = "experiments/scenes/polarization_camera_stokes.xml"
SKY_PARAMS = ("angle", "thickness", "sun", "film_ior", "substrate_eta", "res", "spp")
FILM_PARAMS = ("angle", "thickness", "pol_theta", "film_ior", "substrate_eta", "transmission", "res", "spp")
SCENES = {
    "glass_plate": SceneSpec(PLATE, materials=("thinfilm",), params=("angle", "thickness", "res", "spp"),
                             note="film-coated sphere (n = 2.1 on Ta) seen in a black glass plate"),
    "soap_film": SceneSpec(LIGHT, materials=("thinfilm", "polarizer"), params=FILM_PARAMS,
                           note="free-standing water film lit through a linear polarizer"),
    "oil_on_water": SceneSpec(LIGHT, materials=("thinfilm", "polarizer"), params=FILM_PARAMS,
                              note="oil film on water lit through a linear polarizer"),
    "soap_sky": SceneSpec(SKY, materials=("thinfilm",), params=SKY_PARAMS,
                          note="free-standing water film under a Rayleigh-scattering sky lit by the sun"),
    "oil_sky": SceneSpec(SKY, materials=("thinfilm",), params=SKY_PARAMS,
                         note="oil film on water under a Rayleigh-scattering sky lit by the sun"),
    "camera_polarizer": SceneSpec(CAMERA, materials=("thinfilm", "polarizer"), params=("pol_theta", "res", "spp"),
                                  note="scenes/default.xml's film spheres behind a linear polarizer"),
    "camera_stokes": SceneSpec(STOKES, materials=("thinfilm",), params=("res", "spp"),
                               note="the camera_polarizer view without the polarizer, S0-S3 from the stokes integrator"),
}
# The films' parameters (scenes/default.xml: soap bubble and oil on water).
# The soap film's transmitted light would only reach the black absorber under it: the scene leaves
# out its transmission lobe (same image, less noise; see the scene's comment).
SCENE_DEFINES = {"soap_film": {"film_ior": 1.33, "substrate_eta": 1.0, "transmission": "false"},
                 "oil_on_water": {"film_ior": 1.47, "substrate_eta": 1.33, "transmission": "false"},
                 "soap_sky": {"film_ior": 1.33, "substrate_eta": 1.0},
                 "oil_sky": {"film_ior": 1.47, "substrate_eta": 1.33}}
# Scene parameters swept per scene (film thickness in nm, viewing angle from the normal in degrees,
# polarizer axis in degrees: 0 passes s-polarized light in the film scenes and horizontal light at
# the camera, 90 p-polarized / vertical; sun position in degrees about the reflected ray: 0 makes the
# sky light reaching the film s-polarized, 90 p-polarized).
FULL_GRID = {
    "glass_plate": {"thickness": [100, 250, 400], "angle": [30, 56, 70]},
    "soap_film": {"thickness": [200, 400, 800], "angle": [30, 53, 70], "pol_theta": [0, 90]},
    "oil_on_water": {"thickness": [200, 400, 800], "angle": [30, 53, 70], "pol_theta": [0, 90]},
    "soap_sky": {"thickness": [200, 400, 800], "angle": [30, 53, 70], "sun": [0, 90]},
    "oil_sky": {"thickness": [200, 400, 800], "angle": [30, 53, 70], "sun": [0, 90]},
    "camera_polarizer": {"pol_theta": [0, 45, 90]},
}
QUICK_GRID = {
    "glass_plate": {"thickness": [250], "angle": [30, 56]},
    "soap_film": {"thickness": [400], "angle": [53], "pol_theta": [0, 90]},
    "oil_on_water": {"thickness": [400], "angle": [53], "pol_theta": [0, 90]},
    "soap_sky": {"thickness": [400], "angle": [53], "sun": [0, 90]},
    "oil_sky": {"thickness": [400], "angle": [53], "sun": [0, 90]},
    "camera_polarizer": {"pol_theta": [0, 90]},
}
# The grid point of each scene whose convergence study (error against wall time) is rendered.
CONVERGENCE_POINT = {"glass_plate": {"thickness": 250, "angle": 56},
                     "soap_film": {"thickness": 400, "angle": 53, "pol_theta": 0},
                     "oil_on_water": {"thickness": 400, "angle": 53, "pol_theta": 0},
                     "soap_sky": {"thickness": 400, "angle": 53, "sun": 0},
                     "oil_sky": {"thickness": 400, "angle": 53, "sun": 0},
                     "camera_polarizer": {"pol_theta": 90}}
MODES = {"spectral": {"mode": "spectral"}, "polarized": {"mode": "polarized"}}
BASELINE = "polarized"
FULL = {"res": 64, "ref_spp": 128, "ref_seeds": 2, "test_spp": 32,
        "convergence": {"ref_spp": 512, "ref_seeds": 2, "spp_levels": [4, 16, 64], "seeds": [1, 2], "time_limit": 1.5}}
QUICK = {"res": 32, "ref_spp": 16, "ref_seeds": 2, "test_spp": 4,
         "convergence": {"ref_spp": 32, "ref_seeds": 2, "spp_levels": [2, 8], "seeds": [1, 2], "time_limit": 0.2}}
JND = 1.0   # ΔE00 of about 1: a just-noticeable difference
AXIS_NAMES = {"thickness": "thickness [nm]", "angle": "angle [°]", "pol_theta": "polarizer [°]", "sun": "sun [°]"}
# The pair of camera_polarizer renders whose difference is S1 (polarizer along and normal to the
# stokes integrator's basis vector, the image's horizontal).
S1_PAIR = (0, 90)
# ---------------------------------------------------------------------------------------------


def point_text(point: dict) -> str:
    return ", ".join(f"{AXIS_NAMES.get(k, k)} {format_value(v)}" for k, v in point.items())


class Polarization(ConvergenceExperiment):
    name = "polarization"
    title = "How wrong is unpolarized transport for thin films?"
    question = ("Question: where polarization matters (two specular bounces off a film and a glass plate, soap and oil "
                "films lit by polarized light and under a polarized sky, a camera behind a linear polarizer and its S1 image), how far (ΔE00, relMSE) is iris's "
                "spectral mode, which averages the s and p reflectances at every bounce, from the polarized mode's "
                "converged image, per film thickness and viewing angle; and what does polarized transport cost in "
                "render time for a given error?")
    scene_specs = SCENES
    FULL, QUICK = FULL, QUICK

    def study_labels(self):
        """The scenes with a convergence study (camera_stokes has none: spectral mode has no S1)."""
        return [label for label in self.scene_specs if label in CONVERGENCE_POINT]

    def grid_axes(self, quick):
        return {label: axes for label, axes in (QUICK_GRID if quick else FULL_GRID).items() if label in self.scene_specs}

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "resolution": f"{c['res']} (-D res)",
                "scenes": {k: v.path for k, v in self.scene_specs.items()},
                "scene parameters": {k: v for k, v in SCENE_DEFINES.items() if k in self.scene_specs},
                "grid": self.grid_axes(quick),
                "grid reference": f"polarized, {c['ref_seeds']} seeds x {c['ref_spp']} spp, merged",
                "grid test renders": f"spectral and polarized (noise floor), {c['test_spp']} spp, seeds 1 and 2",
                "convergence points": {k: v for k, v in CONVERGENCE_POINT.items() if k in self.scene_specs},
                "stokes render": f"camera_stokes, polarized, {c['ref_seeds'] * c['ref_spp']} spp, seed 3000",
                "just-noticeable ΔE00": JND, **self.study.settings()}

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        conv = c["convergence"]
        out = []
        for label, axes in self.grid_axes(quick).items():
            scene = {label: self.scene_specs[label].path}
            fixed = {"res": c["res"], **SCENE_DEFINES.get(label, {})}
            out += [
                Sweep("grid_reference", scene, axes={**axes, "seed": [1000 + i for i in range(c["ref_seeds"])]},
                      fixed={**fixed, "mode": "polarized", "spp": c["ref_spp"]}),
                Sweep("grid_spectral", scene, axes=dict(axes), fixed={**fixed, "mode": "spectral", "spp": c["test_spp"],
                                                                      "seed": 1}),
                Sweep("grid_polarized", scene, axes=dict(axes), fixed={**fixed, "mode": "polarized",
                                                                       "spp": c["test_spp"], "seed": 2}),
            ]
        self.study = ConvergenceStudy(MODES, BASELINE, {"mode": "polarized"}, conv["spp_levels"], conv["seeds"],
                                      conv["ref_spp"], [2000 + i for i in range(conv["ref_seeds"])],
                                      time_limit=conv["time_limit"])
        if "camera_stokes" in self.scene_specs:
            out.append(Sweep("stokes", {"camera_stokes": self.scene_specs["camera_stokes"].path},
                             fixed={"res": c["res"], "mode": "polarized", "spp": c["ref_seeds"] * c["ref_spp"], "seed": 3000}))
        labels = self.study_labels()
        per_scene = {label: {"res": c["res"], **SCENE_DEFINES.get(label, {}), **CONVERGENCE_POINT[label]} for label in labels}
        return out + self.study.sweeps({label: self.scene_specs[label].path for label in labels}, per_scene)

    # -- the grid: spectral against the polarized reference per thickness / angle ----------------
    @staticmethod
    def mean_ratio(test: Path, ref: Path) -> float:
        """Mean pixel value of test / mean of ref (all colour channels): the brightness error."""
        a, an, _ = exr.read_exr(str(test))
        b, bn, _ = exr.read_exr(str(ref))
        mb = float(np.mean(exr.rgb_of(b, bn)))
        return float(np.mean(exr.rgb_of(a, an))) / mb if mb > 0 else math.nan

    def grid_rows(self, ctx, label, axes):
        keys = list(axes)
        key_of = lambda j: tuple(j.settings[k] for k in keys)   # noqa: E731
        refs, spectral, polarized = {}, {}, {}
        for j in ctx.by_sweep("grid_reference"):
            if j.label == label:
                refs.setdefault(key_of(j), []).append(j.output)
        for j in ctx.by_sweep("grid_spectral"):
            if j.label == label:
                spectral[key_of(j)] = j
        for j in ctx.by_sweep("grid_polarized"):
            if j.label == label:
                polarized[key_of(j)] = j
        rows, images = [], {}
        for key, outputs in refs.items():
            stem = "_".join(f"{slug(k)}={slug(format_value(v))}" for k, v in zip(keys, key))
            ref = ctx.merge(outputs, ctx.out_dir / "reference" / "grid" / label / f"{stem}.exr")
            s, p = spectral[key], polarized[key]
            ms, mp = ctx.compare(s.output, ref), ctx.compare(p.output, ref)
            ts = job_row(s).get("render_time_s", math.nan)
            tp = job_row(p).get("render_time_s", math.nan)
            row = {"sweep": "grid", "scene": label, **dict(zip(keys, key)), "spp": s.settings["spp"],
                   "de00_spectral": ms["de00_mean"], "de00_floor": mp["de00_mean"],
                   "de00_excess": ms["de00_mean"] - mp["de00_mean"], "de00_p99_spectral": ms["de00_p99"],
                   "relmse_spectral": ms["relmse"], "relmse_floor": mp["relmse"],
                   "relmse_ratio": ms["relmse"] / mp["relmse"] if mp["relmse"] > 0 else math.nan,
                   "mean_ratio": self.mean_ratio(s.output, ref),
                   "time_spectral_s": ts, "time_polarized_s": tp,
                   "cost_ratio": tp / ts if ts and ts > 0 else math.nan,
                   "spectral_output": job_row(s)["output"], "polarized_output": job_row(p)["output"]}
            rows.append(row)
            images[key] = (ref, s.output, p.output)
        return rows, images

    def grid_section(self, label, axes, rows):
        keys = list(axes)
        cols = keys + ["de00_spectral", "de00_floor", "de00_excess", "relmse_spectral", "relmse_floor", "relmse_ratio",
                       "mean_ratio", "time_spectral_s", "time_polarized_s", "cost_ratio"]
        text = (f"{SCENES[label].note} ({SCENES[label].path}). Each spectral render ({rows[0]['spp']} spp, seed 1) and "
                f"a polarized render of the same spp (seed 2, the noise floor) against the polarized reference; "
                f"de00_excess = ΔE00 of spectral − ΔE00 of the noise floor (the visible part of the unpolarized "
                f"transport's error, noise aside); relmse_ratio = relMSE of spectral / relMSE of the noise floor; "
                f"mean_ratio = mean pixel value of the spectral render / the reference's; cost_ratio = polarized / "
                f"spectral render time at equal spp.\n\n" + markdown_table(rows, cols, digits=3))
        return (f"Unpolarized against polarized: {label}", text)

    def grid_conclusions(self, label, axes, rows):
        out = []
        worst = max(rows, key=lambda r: r["de00_excess"])
        over = [r for r in rows if r["de00_excess"] > JND]
        keys = list(axes)
        out.append(
            f"{label}: unpolarized (spectral) transport against the polarized reference: mean ΔE00 "
            f"{fmt(statistics.mean(r['de00_spectral'] for r in rows), 3)} over {len(rows)} grid points "
            f"(noise floor at the same spp {fmt(statistics.mean(r['de00_floor'] for r in rows), 3)}), largest at "
            f"{point_text({k: worst[k] for k in keys})}: ΔE00 {fmt(worst['de00_spectral'], 3)} (floor "
            f"{fmt(worst['de00_floor'], 3)}), relMSE {fmt(worst['relmse_spectral'], 3)} "
            f"({fmt(worst['relmse_ratio'], 3)}x the floor's), mean brightness {fmt(worst['mean_ratio'], 3)}x the "
            f"reference's; the excess over the noise floor is above the just-noticeable ΔE00 = {JND:g} at "
            f"{len(over)} of {len(rows)} points.")
        for key in keys:
            values = sorted({r[key] for r in rows})
            if len(values) < 2:
                continue
            parts = []
            for v in values:
                mine = [r for r in rows if r[key] == v]
                parts.append(f"{format_value(v)}: ΔE00 {fmt(statistics.mean(r['de00_spectral'] for r in mine), 3)}, "
                             f"relMSE {fmt(statistics.mean(r['relmse_spectral'] for r in mine), 3)}")
            out.append(f"  {label} by {AXIS_NAMES.get(key, key)} (mean over the other parameters): " + "; ".join(parts) + ".")
        return out

    def grid_figures(self, ctx, label, axes, rows, images):
        figs = []
        keys = list(axes)
        if "angle" in keys:
            series = {}
            for r in rows:
                name = ", ".join(f"{AXIS_NAMES.get(k, k)} {format_value(r[k])}" for k in keys if k != "angle")
                series.setdefault(name or label, ([], []))
                series[name or label][0].append(r["angle"])
                series[name or label][1].append(r["de00_spectral"])
            series = {k: tuple(zip(*sorted(zip(*v)))) for k, v in series.items()}
            floor = sorted((r["angle"], r["de00_floor"]) for r in rows)
            series["noise floor (max over points)"] = tuple(zip(*[(a, max(f for b, f in floor if b == a))
                                                                  for a in sorted({a for a, _ in floor})]))
            figs.append(grid.line_plot(series, ctx.out_dir / f"{label}_de00_vs_angle.png", "viewing angle [°]",
                                       "mean ΔE00, spectral vs polarized ref.", title=label))
        point = CONVERGENCE_POINT[label]
        shown = [k for k in images if all(v == point[kk] for kk, v in zip(keys, k) if kk not in ("angle", "pol_theta", "sun"))]
        cells = [list(images[k]) for k in sorted(shown)]
        names = [point_text(dict(zip(keys, k))) for k in sorted(shown)]
        figs.append(grid.image_grid(cells, ctx.out_dir / f"{label}_renders.jpg", row_labels=names,
                                    col_labels=["polarized reference", "spectral (unpolarized)", "polarized, same spp"],
                                    cell_inches=1.9))
        return figs

    # -- everything ------------------------------------------------------------------------------
    def analyse(self, ctx):
        analysis = Analysis([], ["sweep", "scene", "thickness", "angle", "pol_theta", "config", "spp", "de00_spectral",
                                 "de00_floor", "relmse_spectral", "relmse_floor", "mean_ratio", "cost_ratio",
                                 "render_time_s", "relmse", "de00_mean"], [])
        costs, grid_images = {}, {}
        for label, axes in self.grid_axes(ctx.args.quick).items():
            rows, images = self.grid_rows(ctx, label, axes)
            grid_images[label] = images
            analysis.rows += rows
            analysis.sections.append(self.grid_section(label, axes, rows))
            analysis.conclusions += self.grid_conclusions(label, axes, rows)
            analysis.figures += self.grid_figures(ctx, label, axes, rows, images)
            costs[label] = [r["cost_ratio"] for r in rows if math.isfinite(r["cost_ratio"])]
        analysis.conclusions.append(
            "Cost of polarization at equal spp (polarized / spectral render time, median over each scene's grid "
            "renders): " + "; ".join(f"{k} {fmt(statistics.median(v), 3)}x" for k, v in costs.items() if v) + ".")
        self.stokes_analysis(ctx, analysis, grid_images.get("camera_polarizer", {}))
        for label in self.study_labels():
            result = self.study.analyse(ctx, label)
            for r in result.rows:
                r["sweep"] = r.get("study", "convergence")
            analysis.rows += result.rows
            analysis.add_study(result)
            analysis.conclusions.append(self.crossover(label, result))
        cost_rows = [{"scene": k, "median cost ratio": statistics.median(v), "min": min(v), "max": max(v)}
                     for k, v in costs.items() if v]
        analysis.sections.append(("Cost of polarization at equal spp",
                                  "Polarized / spectral render time (iris.render_time_s) of the grid's test renders, "
                                  "same spp and resolution, one job at a time.\n\n" +
                                  markdown_table(cost_rows, ["scene", "median cost ratio", "min", "max"], digits=3)))
        return analysis

    # -- the camera behind a linear polarizer: the S1 image ----------------------------------------
    def stokes_analysis(self, ctx, analysis, pair_images):
        """S1 of the stokes render against I(0) - I(90) of the camera_polarizer references."""
        jobs = ctx.by_sweep("stokes")
        pair = [pair_images.get((t,)) for t in S1_PAIR]
        if not jobs or not all(pair):
            return
        stokes = stokes_images.stokes_of(jobs[0].output)
        refs = [stokes_images.grey_of(p[0]) for p in pair]        # polarized references
        spectral = [stokes_images.grey_of(p[1]) for p in pair]    # spectral renders (same seed)
        m = stokes_images.s1_metrics(stokes, *refs)
        spectral_s1 = float(np.mean(np.abs(spectral[0] - spectral[1])))
        analysis.rows.append({"sweep": "stokes", "scene": "camera_stokes", **m, "spectral_abs_s1_over_s0":
                              spectral_s1 / m["s0_mean"] if m["s0_mean"] > 0 else math.nan, "output": str(jobs[0].output)})
        analysis.figures.append(stokes_images.s1_figure(
            [("S0 (stokes)", stokes[0]), ("S1 (stokes)", stokes[1]), ("I(0) − I(90), polarized", refs[0] - refs[1]),
             ("I(0) − I(90), spectral", spectral[0] - spectral[1])],
            ctx.out_dir / "camera_stokes_s1.png", title="camera behind a linear polarizer: S1 (red: horizontal)"))
        analysis.sections.append(("The camera behind a linear polarizer: S1", self.stokes_text(m, spectral_s1)))
        analysis.conclusions.append(
            f"camera_stokes: the S1 image (stokes integrator) has mean |S1| = {fmt(m['abs_s1_over_s0'], 3)} of mean S0 "
            f"(mean linear polarization sqrt(S1² + S2²): {fmt(m['dolp_mean'], 3)} of S0); unpolarized (spectral) "
            f"transport predicts S1 = 0 (its I(0) − I(90): {fmt(spectral_s1, 3)}). The polarizer pair agrees with the "
            f"Stokes channels: mean I(0) − I(90) = {fmt(m['pair_s1_mean'], 3)} against S1 {fmt(m['s1_mean'], 3)}, "
            f"I(0) + I(90) = {fmt(m['pair_s0_mean'], 3)} against S0 {fmt(m['s0_mean'], 3)}, pixel correlation "
            f"{fmt(m['pair_s1_corr'], 3)} (relative L2 distance {fmt(m['pair_s1_rel_l2'], 3)}, render noise included).")

    @staticmethod
    def stokes_text(m, spectral_s1):
        rows = [{"quantity": k, "value": v} for k, v in m.items()] + [
            {"quantity": "spectral mean |I(0) − I(90)|", "value": spectral_s1}]
        return ("The camera_polarizer view without the polarizer, rendered by the stokes integrator "
                f"({STOKES}); its basis vector is the image's horizontal, the polarizer's axis at 0°, so "
                "S1 = I(0) − I(90) and S0 = I(0) + I(90) of the camera_polarizer references (Malus's law). "
                "abs_s1_over_s0 is the share of the image that unpolarized transport cannot reproduce behind a "
                "polarizer (its S1 is 0); pair_* compare the Stokes channels with the polarizer pair.\n\n"
                + markdown_table(rows, ["quantity", "value"], digits=4))

    def crossover(self, label, result):
        """Where the polarized curve's relMSE falls below the spectral one's (its bias)."""
        per = result.summary["metrics"]["relmse"]["configs"]
        s, p = per.get("spectral"), per.get("polarized")
        if not s or not p:
            return f"{label}: convergence study incomplete."
        pts = [r for r in result.rows if r.get("study") == self.study.name and r["config"] == "spectral"]
        top = max(r["spp"] for r in pts)
        floor = statistics.mean(r["relmse"] for r in pts if r["spp"] == top)
        pol_top = statistics.mean(r["relmse"] for r in result.rows if r.get("study") == self.study.name
                                  and r["config"] == "polarized" and r["spp"] == top)
        t = math.nan
        pol_times = [r for r in result.rows if r.get("study") == self.study.name and r["config"] == "polarized"]
        below = sorted((r["render_time_s"], r["relmse"]) for r in pol_times if r["relmse"] < floor)
        if below:
            t = below[0][0]
        return (f"{label} ({point_text(CONVERGENCE_POINT[label])}), error against time: spectral relMSE falls at slope "
                f"{fmt(s['slope_time'], 3)} against wall time, polarized at {fmt(p['slope_time'], 3)}; at {top} spp "
                f"spectral reaches relMSE {fmt(floor, 3)} and polarized {fmt(pol_top, 3)}; "
                + (f"the first polarized render below spectral's {top}-spp error took {fmt(t, 3)} s."
                   if math.isfinite(t) else f"no polarized render reached spectral's {top}-spp error (the noise, "
                                              f"not the bias, dominates spectral's error at this budget)."))


if __name__ == "__main__":
    sys.exit(run(Polarization()))
