#!/usr/bin/env python3
"""Phase once or per internal reflection? Thesis 000 §5 names as a limitation that the proposed model
(§3.2, eqs. 3.15–3.22) applies the interference phase once to the total reflected energy instead of
to each internal reflection in the film. This experiment renders the proposed model with both
treatments over the thesis' thicknesses (Fig. 4.2) in spectral mode and measures how different the
images are, against the noise floor (two seeds of the same variant).

    python3 experiments/per_bounce_phase.py [--quick] [--parallel N] [--slurm] ...
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import grid  # noqa: E402
from iris_experiments.collect import job_row  # noqa: E402
from iris_experiments.experiment import Analysis, Experiment, run  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402
from iris_experiments.sweep import Sweep  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
# The scene must declare <default name="thickness"/> and <default name="phase_model"/>, the latter
# passed to the proposed material so that "once" = thesis eq. 3.15–3.22 and "per_bounce" = the phase
# applied to each internal reflection (§5).
SCENES = {
    "proposed": SceneSpec("scenes/thin_film_proposed.xml", materials=("proposed",),
                          params=("thickness", "phase_model"),
                          note="the thesis' proposed model with a phase_model switch, being written"),
}
THICKNESS_NM = [76, 200, 350, 600, 1000]
VARIANTS = ["once", "per_bounce"]
FULL = {"spp": 1024, "spectral_samples": 8}
QUICK = {"spp": 8, "spectral_samples": 8, "res": 32}
JND = 1.0
# ---------------------------------------------------------------------------------------------


class PerBouncePhase(Experiment):
    name = "per_bounce_phase"
    title = "Interference phase applied once vs per internal reflection"
    question = ("Question: how much does applying the thin-film phase to each internal reflection, instead of once "
                "to the total (thesis 000 §5), change the rendered images, and for which thicknesses?")
    scene_specs = SCENES

    def cfg(self, quick):
        return QUICK if quick else FULL

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "thickness [nm]": THICKNESS_NM, "variants": VARIANTS,
                "spp": c["spp"], "render mode": f"spectral, {c['spectral_samples']} wavelengths/path",
                "noise floor": "same variant ('once'), seeds 1 and 2", "just-noticeable ΔE00": JND,
                "scenes": {k: v.path for k, v in self.scene_specs.items()}}

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        fixed = {"mode": "spectral", "spectral_samples": c["spectral_samples"], "spp": c["spp"]}
        per_scene = self.quick_resolution(quick, c.get("res", 48))
        return [
            Sweep("variants", self.scene_paths(), axes={"phase_model": VARIANTS, "thickness": THICKNESS_NM},
                  fixed={**fixed, "seed": 1}, per_scene=per_scene),
            Sweep("noise", self.scene_paths(), axes={"phase_model": ["once"], "thickness": THICKNESS_NM},
                  fixed={**fixed, "seed": 2}, per_scene=per_scene),
        ]

    def analyse(self, ctx):
        rows, figures, conclusions = [], [], []
        for label in self.scene_specs:
            def find(sweep, variant, d):
                return next(j for j in ctx.by_sweep(sweep) if j.label == label and
                            j.settings["phase_model"] == variant and j.settings["thickness"] == d)
            for d in THICKNESS_NM:
                once, per, once2 = find("variants", "once", d), find("variants", "per_bounce", d), find("noise", "once", d)
                diff = ctx.compare(per.output, once2.output)   # independent seeds: noise + the real difference
                noise = ctx.compare(once.output, once2.output)  # noise only
                row = job_row(once, {"thickness_nm": d, "variant_de00_mean": diff["de00_mean"],
                                     "variant_de00_p99": diff["de00_p99"], "noise_de00_mean": noise["de00_mean"],
                                     "noise_de00_p99": noise["de00_p99"], "variant_relmse": diff["relmse"],
                                     "noise_relmse": noise["relmse"]})
                row["excess_de00_mean"] = diff["de00_mean"] - noise["de00_mean"]
                rows.append(row)
            mine = [r for r in rows if r["scene"] == label]
            worst = max(mine, key=lambda r: r["excess_de00_mean"])
            visible = [r["thickness_nm"] for r in mine if r["excess_de00_mean"] > JND]
            conclusions.append(
                f"{label}: per-bounce vs once differs by mean ΔE00 {worst['variant_de00_mean']:.3g} at d = "
                f"{worst['thickness_nm']} nm (largest excess over the noise floor {worst['noise_de00_mean']:.3g}); "
                f"excess ranges {min(r['excess_de00_mean'] for r in mine):.3g} .. {worst['excess_de00_mean']:.3g}.")
            conclusions.append(f"{label}: thicknesses where the excess exceeds the just-noticeable ΔE00 = {JND:g}: " +
                               (", ".join(f"{d} nm" for d in visible) if visible else "none") + ".")
            cells = [[find("variants", v, d).output for d in THICKNESS_NM] for v in VARIANTS]
            figures.append(grid.image_grid(cells, ctx.out_dir / f"{label}_variants.png", row_labels=VARIANTS,
                                           col_labels=[f"d = {d} nm" for d in THICKNESS_NM]))
            figures.append(grid.line_plot(
                {"once vs per-bounce": (THICKNESS_NM, [r["variant_de00_mean"] for r in mine]),
                 "noise floor": (THICKNESS_NM, [r["noise_de00_mean"] for r in mine])},
                ctx.out_dir / f"{label}_de00_vs_thickness.png", "film thickness d [nm]", "mean ΔE00",
                title=f"{label}: phase once vs per bounce"))
        cols = ["scene", "thickness_nm", "spp", "variant_de00_mean", "noise_de00_mean", "excess_de00_mean",
                "variant_de00_p99", "noise_de00_p99", "variant_relmse", "noise_relmse"]
        return Analysis(rows, cols, conclusions, figures=figures)


if __name__ == "__main__":
    sys.exit(run(PerBouncePhase()))
