#!/usr/bin/env python3
"""Phase once or per internal reflection? Thesis 000 §5 names as a limitation that its models apply
the interference phase once instead of to each internal reflection in the film. With the exact
film-stack material (`thinfilm`, docs/thin_film.md §2) the same film can be rendered with
  two_beam     phase_mode = truncated, bounces = 1: one round trip in the film, i.e. the phase once,
  truncated_3  phase_mode = truncated, bounces = 3,
  exact        phase_mode = exact: the Airy sum over every internal reflection,
  incoherent   phase_mode = incoherent: no interference (phase averaged),
over the thesis' thicknesses (Fig. 4.2). Each variant is compared with `exact` (another seed) and
against the noise floor (exact, two seeds), in spectral mode.

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
# The scene passes <default>s thickness, phase_mode and bounces to a `thinfilm` material.
SCENES = {
    "thin_film": SceneSpec("scenes/thin_film_spheres.xml", materials=("thinfilm",),
                           params=("thickness", "phase_mode", "bounces"),
                           note="spheres with the thinfilm material and thickness/phase_mode/bounces "
                                "<default>s, being written"),
}
THICKNESS_NM = [76, 200, 350, 600, 1000]
VARIANTS = [
    {"name": "two_beam", "phase_mode": "truncated", "bounces": 1},
    {"name": "truncated_3", "phase_mode": "truncated", "bounces": 3},
    {"name": "exact", "phase_mode": "exact", "bounces": 1},
    {"name": "incoherent", "phase_mode": "incoherent", "bounces": 1},
]
REFERENCE = "exact"
FULL = {"spp": 1024, "spectral_samples": 8}
QUICK = {"spp": 8, "spectral_samples": 8, "res": 32}
JND = 1.0
# ---------------------------------------------------------------------------------------------


class PerBouncePhase(Experiment):
    name = "per_bounce_phase"
    title = "Interference phase applied once vs per internal reflection"
    question = ("Question: how much does applying the thin-film phase once (two-beam interference, as the thesis' "
                "models do, §5) instead of to every internal reflection (exact Airy sum) change the rendered images, "
                "and for which thicknesses?")
    scene_specs = SCENES

    def cfg(self, quick):
        return QUICK if quick else FULL

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "thickness [nm]": THICKNESS_NM,
                "variants": {v["name"]: {k: x for k, x in v.items() if k != "name"} for v in VARIANTS},
                "compared with": f"{REFERENCE}, seed 2", "noise floor": f"{REFERENCE} seed 1 vs seed 2",
                "spp": c["spp"], "render mode": f"spectral, {c['spectral_samples']} wavelengths/path",
                "just-noticeable ΔE00": JND, "scenes": {k: v.path for k, v in self.scene_specs.items()}}

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        fixed = {"mode": "spectral", "spectral_samples": c["spectral_samples"], "spp": c["spp"]}
        per_scene = self.quick_resolution(quick, c.get("res", 48))
        ref = next(v for v in VARIANTS if v["name"] == REFERENCE)
        return [
            Sweep("variants", self.scene_paths(), axes={"variant": VARIANTS, "thickness": THICKNESS_NM},
                  fixed={**fixed, "seed": 1}, per_scene=per_scene),
            Sweep("reference", self.scene_paths(), axes={"variant": [ref], "thickness": THICKNESS_NM},
                  fixed={**fixed, "seed": 2}, per_scene=per_scene),
        ]

    def analyse(self, ctx):
        rows, figures, conclusions = [], [], []
        names = [v["name"] for v in VARIANTS]
        for label in self.scene_specs:
            def find(sweep, variant, d):
                return next(j for j in ctx.by_sweep(sweep) if j.label == label and
                            j.settings["variant"] == variant and j.settings["thickness"] == d)
            for d in THICKNESS_NM:
                ref = find("reference", REFERENCE, d)
                noise = ctx.compare(find("variants", REFERENCE, d).output, ref.output)  # noise only
                for name in names:
                    job = find("variants", name, d)
                    m = ctx.compare(job.output, ref.output)  # independent seeds: noise + the real difference
                    rows.append(job_row(job, {"thickness_nm": d, "de00_mean": m["de00_mean"], "de00_p99": m["de00_p99"],
                                              "relmse": m["relmse"], "noise_de00_mean": noise["de00_mean"],
                                              "excess_de00_mean": m["de00_mean"] - noise["de00_mean"]}))
            for name in names:
                if name == REFERENCE:
                    continue
                mine = [r for r in rows if r["scene"] == label and r["variant"] == name]
                worst = max(mine, key=lambda r: r["excess_de00_mean"])
                visible = [r["thickness_nm"] for r in mine if r["excess_de00_mean"] > JND]
                conclusions.append(
                    f"{label}, {name} vs {REFERENCE}: mean ΔE00 above the noise floor ranges "
                    f"{min(r['excess_de00_mean'] for r in mine):.3g} .. {worst['excess_de00_mean']:.3g} (largest at d = "
                    f"{worst['thickness_nm']} nm: ΔE00 {worst['de00_mean']:.3g}, noise {worst['noise_de00_mean']:.3g}); "
                    f"thicknesses where the excess exceeds the just-noticeable ΔE00 = {JND:g}: " +
                    (", ".join(f"{d} nm" for d in visible) if visible else "none") + ".")
            cells = [[find("variants", n, d).output for d in THICKNESS_NM] for n in names]
            figures.append(grid.image_grid(cells, ctx.out_dir / f"{label}_variants.png", row_labels=names,
                                           col_labels=[f"d = {d} nm" for d in THICKNESS_NM]))
            figures.append(grid.line_plot(
                {**{n: (THICKNESS_NM, [r["de00_mean"] for r in rows if r["scene"] == label and r["variant"] == n])
                    for n in names if n != REFERENCE},
                 "noise floor": (THICKNESS_NM, [r["noise_de00_mean"] for r in rows
                                                if r["scene"] == label and r["variant"] == REFERENCE])},
                ctx.out_dir / f"{label}_de00_vs_thickness.png", "film thickness d [nm]", f"mean ΔE00 vs {REFERENCE}",
                title=f"{label}: phase treatment"))
        cols = ["scene", "variant", "thickness_nm", "spp", "de00_mean", "noise_de00_mean", "excess_de00_mean",
                "de00_p99", "relmse"]
        return Analysis(rows, cols, conclusions, figures=figures)


if __name__ == "__main__":
    sys.exit(run(PerBouncePhase()))
