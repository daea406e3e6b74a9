#!/usr/bin/env python3
"""Spectral MIS in chromatic media: `volpath` (free flights sampled at one wavelength, weighted by
the ratio of the other wavelengths' pdfs) against `volpathmis` (one-sample MIS over the path's
wavelengths; docs/media.md) on a scattering medium whose extinction varies 20x over the spectrum:
error against wall time with several seeds, the error ratio at equal spp and the error at equal
time, against a converged volpathmis reference (issue 20: "volpathmis is no noisier than volpath on
chromatic media (measured)").

    python3 experiments/media_mis.py [--quick] [--parallel N] [--slurm] ...
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
SCENES = {"chromatic_medium": SceneSpec("experiments/scenes/chromatic_medium.xml",
                                        note="a chromatic scattering medium in a null-bounded cube over a lit floor")}
INTEGRATORS = ["volpath", "volpathmis"]
BASELINE = "volpath"   # Mitsuba 3's plain volumetric path tracer
FULL = {"res": 64, "ref_spp": 4096, "ref_seeds": 2,
        "convergence": {"spp_levels": [2 ** k for k in range(2, 9)], "seeds": [1, 2, 3, 4], "time_limit": 4.0}}
QUICK = {"res": 16, "ref_spp": 64, "ref_seeds": 2,
         "convergence": {"spp_levels": [2, 4, 8], "seeds": [1, 2], "time_limit": 0.2}}
# ---------------------------------------------------------------------------------------------


class MediaMIS(ConvergenceExperiment):
    name = "media_mis"
    title = "Chromatic media: volpath against volpathmis"
    question = ("Question: how much lower is the error of spectral MIS (volpathmis) than of single-wavelength "
                "free-flight sampling (volpath) on a medium whose extinction varies with wavelength, at equal "
                "samples and at equal time?")
    scene_specs = SCENES
    FULL, QUICK = FULL, QUICK

    def sweeps(self, quick, args):
        self.study = self.convergence_study(quick, {i: {"integrator": i} for i in INTEGRATORS}, BASELINE,
                                            {"integrator": "volpathmis"})
        return self.study.sweeps(self.scene_paths(), {label: {"res": self.cfg(quick)["res"]} for label in SCENES})

    def analyse(self, ctx):
        analysis = Analysis([], ["scene", "config", "spp", "render_time_s", "relmse"], [])
        for label in SCENES:
            result = self.study.analyse(ctx, label)
            analysis.rows += result.rows
            analysis.add_study(result)
            ratios = self.ratios(result.rows)
            table = [{"spp": spp, "relMSE volpath / volpathmis": r} for spp, r in ratios.items()]
            analysis.sections.append((f"Error ratio at equal spp ({label})",
                                      "relMSE of volpath divided by volpathmis' (mean over seeds; > 1: MIS is lower).\n\n" +
                                      markdown_table(table, ["spp", "relMSE volpath / volpathmis"], digits=3)))
            lo, hi = min(ratios.values()), max(ratios.values())
            verdict = "no noisier than" if lo >= 1 else "noisier than"
            analysis.conclusions.append(
                f"{label}: at equal spp volpathmis' relMSE is {fmt(1 / hi, 3)} to {fmt(1 / lo, 3)} times volpath's over "
                f"{min(ratios)}..{max(ratios)} spp: volpathmis is {verdict} volpath at every sample count.")
        return analysis

    def ratios(self, rows):
        """{spp: relMSE(volpath) / relMSE(volpathmis)} from the seed means at each spp."""
        def mean(cfg, spp):
            return mean_relmse_at_spp(rows, self.study.name, cfg, spp)
        return {spp: mean("volpath", spp) / mean("volpathmis", spp) for spp in self.study.spp_levels}


if __name__ == "__main__":
    sys.exit(run(MediaMIS()))
