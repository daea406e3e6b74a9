#!/usr/bin/env python3
"""Phase once or per internal reflection? Thesis 000 §5 names as a limitation that its models apply
the interference phase once, to the total, instead of to each internal reflection in the film.
Two scenes answer it:
  proposed   the thesis' proposed model (materials/thesis/proposed.cpp) with phase_mode = total (the thesis,
             eqs. 3.21–3.22), per_reflection (coherent sum over internal round trips, §5), and the
             phase switched off (phase = false, i.e. rough plastic; thesis §4.2.2);
  thin_film  the exact film-stack material `thinfilm` (docs/thin_film.md §2) with two_beam
             (truncated, 1 round trip: the phase once), truncated_2, truncated_3, exact (Airy sum over every
             internal reflection) and incoherent (no interference),
over the thesis' thicknesses (Fig. 4.2), in spectral mode. Each variant is compared with the
scene's reference variant rendered with another seed, next to the noise floor (the reference
variant, two seeds).

    python3 experiments/per_bounce_phase.py [--quick] [--parallel N] [--slurm] ...
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import grid  # noqa: E402
from iris_experiments.collect import job_row  # noqa: E402
from iris_experiments.convergence import ConvergenceStudy  # noqa: E402
from iris_experiments.experiment import Analysis, Experiment, run  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402
from iris_experiments.sweep import Sweep  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
SCENES = {
    "proposed": SceneSpec("experiments/scenes/proposed_thickness.xml", materials=("proposed",),
                          params=("thickness", "phase_mode", "phase")),
    "thin_film": SceneSpec("experiments/scenes/thinfilm_phase.xml", materials=("thinfilm",),
                           params=("thickness", "phase_mode", "bounces")),
}
VARIANTS = {   # per scene: the variants (settings applied together) and the reference variant
    "proposed": ([{"name": "total", "phase_mode": "total", "phase": "true"},
                  {"name": "per_reflection", "phase_mode": "per_reflection", "phase": "true"},
                  {"name": "no_phase", "phase_mode": "total", "phase": "false"}], "per_reflection"),
    "thin_film": ([{"name": "two_beam", "phase_mode": "truncated", "bounces": 1},
                   {"name": "truncated_2", "phase_mode": "truncated", "bounces": 2},
                   {"name": "truncated_3", "phase_mode": "truncated", "bounces": 3},
                   {"name": "exact", "phase_mode": "exact", "bounces": 1},
                   {"name": "incoherent", "phase_mode": "incoherent", "bounces": 1}], "exact"),
}
THICKNESS_NM = [76, 200, 350, 600, 1000]
FULL = {"spp": 512, "spectral_samples": 8, "thickness": THICKNESS_NM,
        "convergence": {"thickness": 350, "spp_levels": [2 ** k for k in range(9)], "seeds": [1, 2, 3],
                        "ref_spp": 1024, "ref_seeds": [1000, 1001, 1002, 1003], "time_limit": 20.0}}
QUICK = {"spp": 4, "spectral_samples": 8, "res": 32, "thickness": [76, 350, 1000],
         "convergence": {"thickness": 350, "spp_levels": [1, 4], "seeds": [1, 2], "ref_spp": 16,
                         "ref_seeds": [1000, 1001], "time_limit": 0.2}}
# Error against wall time (issue 15): at one thickness every variant at 2^k spp with several seeds
# against a converged render of the scene's reference variant, which is also the baseline.
JND = 1.0
# ---------------------------------------------------------------------------------------------


class PerBouncePhase(Experiment):
    name = "per_bounce_phase"
    title = "Interference phase applied once vs per internal reflection"
    question = ("Question: how much does applying the thin-film phase once (to the total, as the thesis' models do, "
                "§5) instead of to every internal reflection change the rendered images, and for which thicknesses?")
    scene_specs = SCENES

    def cfg(self, quick):
        return QUICK if quick else FULL

    def make_study(self, quick, label):
        c = self.cfg(quick)
        conv = c["convergence"]
        variants, reference = VARIANTS[label]
        configs = {v["name"]: {k: x for k, x in v.items() if k != "name"} for v in variants}
        return ConvergenceStudy(configs, reference, configs[reference], conv["spp_levels"], conv["seeds"],
                                conv["ref_spp"], conv["ref_seeds"], time_limit=conv["time_limit"],
                                fixed={"mode": "spectral", "spectral_samples": c["spectral_samples"],
                                       "thickness": conv["thickness"]})

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "thickness [nm]": c["thickness"],
                "variants": {label: [v["name"] for v in VARIANTS[label][0]] for label in self.scene_specs},
                "reference variant (seed 2)": {label: VARIANTS[label][1] for label in self.scene_specs},
                "noise floor": "reference variant, seed 1 vs seed 2",
                "spp": c["spp"], "render mode": f"spectral, {c['spectral_samples']} wavelengths/path",
                "just-noticeable ΔE00": JND, "scenes": {k: v.path for k, v in self.scene_specs.items()},
                "convergence thickness [nm]": c["convergence"]["thickness"],
                **{f"{label}: {k}": v for label in self.scene_specs
                   for k, v in self.make_study(quick, label).settings().items()}}

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        fixed = {"mode": "spectral", "spectral_samples": c["spectral_samples"], "spp": c["spp"]}
        per_scene = self.quick_resolution(quick, c.get("res", 48))
        sweeps = []
        for label, spec in self.scene_specs.items():
            variants, reference = VARIANTS[label]
            ref = next(v for v in variants if v["name"] == reference)
            sweeps += [
                Sweep("variants", {label: spec.path}, axes={"variant": variants, "thickness": c["thickness"]},
                      fixed={**fixed, "seed": 1}, per_scene=per_scene),
                Sweep("reference", {label: spec.path}, axes={"variant": [ref], "thickness": c["thickness"]},
                      fixed={**fixed, "seed": 2}, per_scene=per_scene),
            ]
            sweeps += self.make_study(quick, label).sweeps({label: spec.path}, per_scene)
        return sweeps

    def analyse(self, ctx):
        rows, figures, conclusions = [], [], []
        thicknesses = self.cfg(ctx.args.quick)["thickness"]
        for label in self.scene_specs:
            variants, reference = VARIANTS[label]
            names = [v["name"] for v in variants]

            def find(sweep, variant, d):
                return next(j for j in ctx.by_sweep(sweep) if j.label == label and
                            j.settings["variant"] == variant and j.settings["thickness"] == d)
            mine = []
            for d in thicknesses:
                ref = find("reference", reference, d)
                noise = ctx.compare(find("variants", reference, d).output, ref.output)  # noise only
                for name in names:
                    job = find("variants", name, d)
                    m = ctx.compare(job.output, ref.output)  # independent seeds: noise + the real difference
                    mine.append(job_row(job, {"thickness_nm": d, "compared_with": reference,
                                              "de00_mean": m["de00_mean"], "de00_p99": m["de00_p99"],
                                              "relmse": m["relmse"], "noise_de00_mean": noise["de00_mean"],
                                              "excess_de00_mean": m["de00_mean"] - noise["de00_mean"]}))
            rows += mine
            for name in names:
                if name == reference:
                    continue
                vr = [r for r in mine if r["variant"] == name]
                worst = max(vr, key=lambda r: r["excess_de00_mean"])
                visible = [r["thickness_nm"] for r in vr if r["excess_de00_mean"] > JND]
                conclusions.append(
                    f"{label}, {name} vs {reference}: mean ΔE00 above the noise floor ranges "
                    f"{min(r['excess_de00_mean'] for r in vr):.3g} .. {worst['excess_de00_mean']:.3g} (largest at d = "
                    f"{worst['thickness_nm']} nm: ΔE00 {worst['de00_mean']:.3g}, noise {worst['noise_de00_mean']:.3g}); "
                    f"thicknesses where the excess exceeds the just-noticeable ΔE00 = {JND:g}: " +
                    (", ".join(f"{d} nm" for d in visible) if visible else "none") + ".")
            cells = [[find("variants", n, d).output for d in thicknesses] for n in names]
            figures.append(grid.image_grid(cells, ctx.out_dir / f"{label}_variants.jpg", row_labels=names,
                                           col_labels=[f"d = {d} nm" for d in thicknesses]))
            series = {n: (thicknesses, [r["de00_mean"] for r in mine if r["variant"] == n])
                      for n in names if n != reference}
            series["noise floor"] = (thicknesses, [r["noise_de00_mean"] for r in mine if r["variant"] == reference])
            figures.append(grid.line_plot(series, ctx.out_dir / f"{label}_de00_vs_thickness.png",
                                          "film thickness d [nm]", f"mean ΔE00 vs {reference}",
                                          title=f"{label}: phase treatment"))
        cols = ["scene", "variant", "compared_with", "thickness_nm", "spp", "de00_mean", "noise_de00_mean",
                "excess_de00_mean", "de00_p99", "relmse"]
        analysis = Analysis(rows, cols, conclusions, figures=figures)
        for label in self.scene_specs:
            analysis.add_study(self.make_study(ctx.args.quick, label).analyse(ctx, label))
        return analysis


if __name__ == "__main__":
    sys.exit(run(PerBouncePhase()))
