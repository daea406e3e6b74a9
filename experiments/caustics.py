#!/usr/bin/env python3
"""Caustics: `path`, `ptracer` and `bdpt` on the caustic scenes of issue 35 (scenes/caustics/: a
glass sphere over a diffuse floor lit by a small spherical area light or by a point light of the
same power, and the same scene with a soap bubble, a 380 nm water film in air, in place of the
glass): error against wall time with several seeds, and at equal time, against a long `bdpt`
reference (two seeds, whose halves estimate its own error).

What to expect (docs/rendering.md, "Which integrator"): with the area light every integrator
converges to the same image and the question is speed; with the point light `path` cannot find
the caustic on the floor (a shadow ray is stopped by the glass and no BSDF sample hits a point),
so its error stops falling (a flat convergence slope), while `ptracer` and `bdpt` converge. No
integrator can render a point light's caustic seen through the glass (no connection at a delta
vertex): it is black in the reference too. `ptracer` cannot see the sphere itself (a delta surface
next to the camera), so on these scenes its error also levels off at the sphere's pixels.

    python3 experiments/caustics.py [--quick] [--parallel N] [--slurm] ...
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import tools  # noqa: E402,F401
from iris_experiments.convergence import mean_relmse_at_spp  # noqa: E402
from iris_experiments.experiment import Analysis, ConvergenceExperiment, run  # noqa: E402
from iris_experiments.report import fmt, markdown_table  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
CAUSTIC = "scenes/caustics/glass_sphere.xml"
SCENES = {
    "glass_area": SceneSpec(CAUSTIC, params=("integrator", "light", "coating", "res", "spp"),
                            note="glass sphere, small spherical area light"),
    "glass_point": SceneSpec(CAUSTIC, params=("integrator", "light", "coating", "res", "spp"),
                             note="glass sphere, point light of the same power"),
    "bubble_area": SceneSpec(CAUSTIC, params=("integrator", "light", "coating", "res", "spp"),
                             note="soap bubble (thin film, 380 nm of water in air), small spherical area light"),
}
SCENE_DEFINES = {"glass_area": {"light": "area", "coating": "glass"},
                 "glass_point": {"light": "point", "coating": "glass"},
                 "bubble_area": {"light": "area", "coating": "bubble"}}
INTEGRATORS = ["path", "ptracer", "bdpt"]
BASELINE = "path"
FULL = {"res": 64, "ref_spp": 1024, "ref_seeds": 2,
        "convergence": {"spp_levels": [4, 16, 64], "seeds": [1, 2], "time_limit": 2.0}}
QUICK = {"res": 16, "ref_spp": 64, "ref_seeds": 2,
         "convergence": {"spp_levels": [2, 8], "seeds": [1, 2], "time_limit": 0.2}}
# ---------------------------------------------------------------------------------------------


class Caustics(ConvergenceExperiment):
    name = "caustics"
    title = "Caustics: path, ptracer and bdpt"
    question = ("Question: on a glass sphere's and a soap bubble's caustic, lit by a small area light or a point "
                "light, which of path, ptracer and bdpt reaches a given error first, and which does not converge "
                "to the bdpt reference at all?")
    scene_specs = SCENES
    FULL, QUICK = FULL, QUICK

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        self.study = self.convergence_study(quick, {i: {"integrator": i} for i in INTEGRATORS}, BASELINE, {"integrator": "bdpt"})
        return self.study.sweeps(self.scene_paths(), {label: {"res": c["res"], **SCENE_DEFINES[label]} for label in SCENES})

    def analyse(self, ctx):
        analysis = Analysis([], ["scene", "config", "spp", "render_time_s", "relmse"], [])
        for label in SCENES:
            result = self.study.analyse(ctx, label)
            analysis.rows += result.rows
            analysis.add_study(result)
            lo, hi = min(self.study.spp_levels), max(self.study.spp_levels)
            table, falls = [], {}
            for cfg in INTEGRATORS:
                e_lo = mean_relmse_at_spp(result.rows, self.study.name, cfg, lo)
                e_hi = mean_relmse_at_spp(result.rows, self.study.name, cfg, hi)
                falls[cfg] = e_lo / e_hi if e_hi > 0 else float("nan")
                table.append({"integrator": cfg, f"relMSE at {lo} spp": e_lo, f"relMSE at {hi} spp": e_hi,
                              "reduction": falls[cfg]})
            analysis.sections.append((f"Error at the lowest and highest sample count ({label})",
                                      f"Mean relMSE over seeds against the bdpt reference; an unbiased estimator's "
                                      f"falls by about {hi // lo}x from {lo} to {hi} spp (until the reference's own "
                                      f"error is reached).\n\n" +
                                      markdown_table(table, list(table[0]), digits=3)))
            stalled = [c for c, f in falls.items() if not f > 0.25 * hi / lo]
            analysis.conclusions.append(
                f"{label}: from {lo} to {hi} spp the relMSE falls by " +
                ", ".join(f"{fmt(falls[c], 3)}x ({c})" for c in INTEGRATORS) + f" (an unbiased, converging estimator: "
                f"about {hi // lo}x); " + (f"less than a quarter of that: {', '.join(stalled)}." if stalled else
                                          "every integrator is within a factor of 4 of that."))
        return analysis


if __name__ == "__main__":
    sys.exit(run(Caustics()))
