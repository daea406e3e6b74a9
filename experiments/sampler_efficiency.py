#!/usr/bin/env python3
"""Which sampler? The five sample sequences (render --sampler: independent, stratified, multijitter,
sobol, highdimsobol; docs/rendering.md "Samplers") on the default scene, the thin-film spheres, the thesis
scene pair and the bunny: error against wall time with several seeds, the variance reduction of
each sampler at equal spp, and the error at equal time, all against a converged reference
(issue 17, item 3).

    python3 experiments/sampler_efficiency.py [--quick] [--parallel N] [--slurm] ...
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import tools  # noqa: E402
from iris_experiments.convergence import mean_relmse_at_spp  # noqa: E402
from iris_experiments.experiment import Analysis, ConvergenceExperiment, run  # noqa: E402
from iris_experiments.report import fmt, markdown_table  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
SCENES = {
    "default": SceneSpec("scenes/default.xml", note="the built-in default scene"),
    "thin_film": SceneSpec("scenes/thinfilm_spheres.xml", materials=("thinfilm", "iridescent_diffuse"),
                           note="spheres with the spectral thin-film materials"),
    "thesis_pair": SceneSpec("experiments/perf/scenes/thesis_pair.xml", note="the thesis models' scene pair"),
    "bunny": SceneSpec("experiments/perf/scenes/bunny.xml", note="the Stanford bunny"),
}
SAMPLERS = ["independent", "stratified", "multijitter", "sobol", "highdimsobol"]
BASELINE = "independent"   # the renderer's and Mitsuba's default
FULL = {"res": 64, "ref_spp": 2048, "ref_seeds": 2,
        "convergence": {"spp_levels": [2 ** k for k in range(1, 8)], "seeds": [1, 2, 3, 4], "time_limit": 4.0}}
QUICK = {"res": 16, "ref_spp": 64, "ref_seeds": 2,
         "convergence": {"spp_levels": [2, 4, 8], "seeds": [1, 2], "time_limit": 0.2}}
# ---------------------------------------------------------------------------------------------


class SamplerEfficiency(ConvergenceExperiment):
    name = "sampler_efficiency"
    title = "Samplers: error at equal samples and at equal time"
    question = ("Question: how much do stratified, multi-jittered and Owen-scrambled Sobol points (padded per request, "
                "and joint over the first 32 dimensions) lower the error of a render against independent points, at "
                "equal samples per pixel and at equal wall time?")
    scene_specs = SCENES
    FULL, QUICK = FULL, QUICK

    def sweeps(self, quick, args):
        render = tools.build_dir(args.build_dir) / "render"
        unavailable = {} if tools.render_supports(render, "--sampler") else {
            s: "render has no --sampler option" for s in SAMPLERS if s != BASELINE}
        # The reference: Sobol points (the lowest error per sample here), spectral mode with the
        # renderer's default 4 wavelengths per path, like every test render.
        self.study = self.convergence_study(quick, {s: {"sampler": s} for s in SAMPLERS}, BASELINE, {"sampler": "sobol"},
                                            unavailable=unavailable)
        per_scene = {label: {"res": self.cfg(quick)["res"]} for label in SCENES}
        return self.study.sweeps(self.scene_paths(), per_scene)

    def analyse(self, ctx):
        analysis = Analysis([], ["scene", "config", "spp", "render_time_s", "relmse"], [])
        for label in SCENES:
            result = self.study.analyse(ctx, label)
            analysis.rows += result.rows
            analysis.add_study(result)
            analysis.sections.append(self.reduction_table(result.rows, label))
            analysis.conclusions += self.reduction_conclusions(result.rows, label)
        return analysis

    def reductions(self, rows, label):
        """{sampler: {spp: relMSE(independent) / relMSE(sampler)}} from the seed means at each spp."""
        def mean(cfg, spp):
            return mean_relmse_at_spp(rows, self.study.name, cfg, spp)
        levels = self.study.spp_levels
        return {s: {spp: mean(BASELINE, spp) / mean(s, spp) for spp in levels}
                for s in self.study.active_configs() if s != BASELINE}

    def reduction_table(self, rows, label):
        red = self.reductions(rows, label)
        table = [{"sampler": s, **{f"{spp} spp": v[spp] for spp in self.study.spp_levels}} for s, v in red.items()]
        cols = ["sampler"] + [f"{spp} spp" for spp in self.study.spp_levels]
        return (f"Variance reduction at equal spp ({label})",
                "relMSE of independent points divided by the sampler's (mean over seeds; > 1: lower error).\n\n" +
                markdown_table(table, cols, digits=3))

    def reduction_conclusions(self, rows, label):
        out = []
        for s, v in self.reductions(rows, label).items():
            lo, hi = min(v.values()), max(v.values())
            out.append(f"{label}: {s} lowers relMSE at equal spp by a factor {fmt(lo, 3)} to {fmt(hi, 3)} "
                       f"over {min(v)}..{max(v)} spp (independent = 1).")
        return out


if __name__ == "__main__":
    sys.exit(run(SamplerEfficiency()))
