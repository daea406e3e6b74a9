#!/usr/bin/env python3
"""How far are the thin-film models that production formats ship from exact interference?
glTF's KHR_materials_iridescence evaluates Belcour & Barla 2017 in RGB with Schlick interfaces,
phase shifts of 0 or π, two harmonics of a Gaussian fit of the CIE functions and a fixed white;
OpenPBR's specification recommends Belcour & Barla (here iris's version with exact Fresnel
terms, spectral/belcour_barla.h); Blender Cycles 4.2 uses Belcour & Barla with exact dielectric
Fresnel terms, three harmonics, a 30 nm blend and a white-point product, on dielectric bases only
(spectral/thin_film_cycles.h); iris's own RGB mode evaluates the exact film at three
wavelengths. This experiment measures each against exact per-wavelength interference:

  * BRDF level: the Fresnel colour over film thickness 0–1500 nm × every angle, for film IOR
    1.2–2.3, on a dielectric base (IOR 1.5) and on two metals (gold- and silver-coloured),
    ΔE00 and relative luminance error (iris_experiments/thin_film_maps.py);
  * rendered glTF scenes (tests/data/gltf/iridescence_*_spheres.gltf, the Khronos sample models'
    sweep recreated by tests/gltf/make_assets.py): RGB mode with rgb_mode point and
    khr_iridescence, and spectral N = 4, 8, 16, against a converged spectral reference, with
    their render times; and the dielectric sweep made of iris's thinfilm material
    (experiments/scenes/industry_thin_film_thinfilm.xml), whose rgb_mode also offers
    belcour_barla and cycles_4_2 (the glTF material does not).

    python3 experiments/industry_thin_film.py [--quick] [--parallel N] ...
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import grid, thin_film_maps  # noqa: E402
from iris_experiments.collect import job_row  # noqa: E402
from iris_experiments.experiment import Analysis, Experiment, run  # noqa: E402
from iris_experiments.inprocess import import_iris  # noqa: E402
from iris_experiments.scenes import SceneSpec  # noqa: E402
from iris_experiments.sweep import Sweep  # noqa: E402

# ---- definition (edit here) -----------------------------------------------------------------
SCENES = {
    "dielectric": SceneSpec("experiments/scenes/industry_thin_film_dielectric.xml", params=("rgb_mode", "res")),
    "metallic": SceneSpec("experiments/scenes/industry_thin_film_metallic.xml", params=("rgb_mode", "res")),
    "thinfilm": SceneSpec("experiments/scenes/industry_thin_film_thinfilm.xml", params=("rgb_mode", "res")),
}
BASES = {"dielectric IOR 1.5": ("dielectric", 1.5), "gold-coloured metal": ("metal", (1.0, 0.71, 0.29)),
         "silver-coloured metal": ("metal", (0.97, 0.96, 0.91))}
FILM_IORS = [1.2, 1.5, 1.8, 2.3]
FULL = {"res": 200, "spp_levels": [16, 64], "ref_spp": 256, "ref_seeds": 2, "thickness_step": 10, "angle_step": 3,
        "lambda_step": 2}
QUICK = {"res": 32, "spp_levels": [2], "ref_spp": 8, "ref_seeds": 1, "thickness_step": 100, "angle_step": 15,
         "lambda_step": 10}
SPECTRAL_N = [4, 8, 16]
RGB_MODES = {"dielectric": ["point", "khr_iridescence"], "metallic": ["point", "khr_iridescence"],   # rgb_mode per scene
             "thinfilm": ["point", "belcour_barla", "cycles_4_2"]}
RGB_SWEEPS = {"rgb": ["dielectric", "metallic"], "rgb_thinfilm": ["thinfilm"]}   # scenes sharing their rgb_mode values
THICKNESS_BANDS = {"thin": (0, 100), "mid": (100, 600), "thick": (600, 1e9)}   # nm, for "where it fails"
JND = 1.0   # ΔE00 of about 1 is commonly taken as a just-noticeable difference
# ---------------------------------------------------------------------------------------------


class IndustryThinFilm(Experiment):
    name = "industry_thin_film"
    title = "The industry's RGB thin-film models against exact spectral interference"
    question = ("Question: where do KHR_materials_iridescence's RGB formulas, Belcour & Barla's RGB integration, "
                "Blender Cycles 4.2's thin film and three-wavelength point sampling differ visibly (ΔE00 > 1) from exact per-wavelength thin-film "
                "interference, and what does spectral rendering with N = 4, 8, 16 wavelengths cost in comparison?")
    scene_specs = SCENES

    def cfg(self, quick):
        return QUICK if quick else FULL

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "bases": {k: str(v) for k, v in BASES.items()},
                "film IOR": FILM_IORS, "thickness": f"0-1500 nm, step {c['thickness_step']} nm",
                "angles": f"0-{90 - c['angle_step']}°, step {c['angle_step']}°",
                "reference spectrum": f"360-830 nm, step {c['lambda_step']} nm, under D65",
                "render resolution": c["res"], "render spp": c["spp_levels"],
                "render reference": f"spectral N=16, {c['ref_seeds']} seeds x {c['ref_spp']} spp, merged",
                "just-noticeable ΔE00": JND, "scenes": {k: v.path for k, v in SCENES.items()}}

    def sweeps(self, quick, args):
        c = self.cfg(quick)
        res = {label: {"res": c["res"]} for label in SCENES}
        return [
            Sweep("reference", self.scene_paths(), axes={"seed": [1000 + i for i in range(c["ref_seeds"])]},
                  fixed={"mode": "spectral", "spectral_samples": 16, "spp": c["ref_spp"], "rgb_mode": "point"}, per_scene=res),
            # One RGB sweep per set of rgb_mode values: the glTF scenes, and the thinfilm scene.
            *[Sweep(name, {label: self.scene_paths()[label] for label in labels},
                    axes={"rgb_mode": RGB_MODES[labels[0]], "spp": c["spp_levels"]}, fixed={"mode": "rgb", "seed": 1},
                    per_scene=res) for name, labels in RGB_SWEEPS.items()],
            Sweep("spectral", self.scene_paths(), axes={"spectral_samples": SPECTRAL_N, "spp": c["spp_levels"]},
                  fixed={"mode": "spectral", "seed": 1, "rgb_mode": "point"}, per_scene=res),
        ]

    # -- BRDF level --------------------------------------------------------------------------
    def brdf_level(self, ctx, rows, figures, conclusions):
        iris = import_iris(ctx.build_dir)
        c = self.cfg(ctx.args.quick)
        thickness = np.arange(0.0, 1500.0 + 1e-9, c["thickness_step"])
        angles = np.arange(0.0, 90.0 - 1e-9, c["angle_step"])
        cos = np.cos(np.radians(angles))
        lam = np.arange(360.0, 830.0 + 1e-9, c["lambda_step"])
        maps = {}
        for base_name, base in BASES.items():
            for film in FILM_IORS:
                ref = thin_film_maps.exact_rgb(iris, base, film, thickness, cos, lam)
                for model, fn in thin_film_maps.MODELS.items():
                    test = fn(iris, base, film, thickness, cos)
                    if test is None:   # the model has no form for this base (Cycles 4.2 on metals)
                        continue
                    de, rel = thin_film_maps.errors(iris, test, ref)
                    maps[(base_name, film, model)] = de
                    over = de > JND
                    bands = {f"over_jnd_{name}": float(over[(thickness >= lo) & (thickness < hi)].mean())
                             for name, (lo, hi) in THICKNESS_BANDS.items()}
                    bands["over_jnd_grazing"] = float(over[:, angles >= 60].mean())
                    rows.append({**bands, "level": "BRDF", "base": base_name, "film_ior": film, "model": model,
                                 "de00_mean": float(de.mean()), "de00_p95": float(np.percentile(de, 95)),
                                 "de00_max": float(de.max()), "rel_lum_err_mean": float(rel.mean()),
                                 "fraction_over_jnd": float(over.mean()),
                                 "first_thickness_over_jnd_nm": float(thickness[over.any(axis=1)][0]) if over.any() else None})
        for model in thin_film_maps.MODELS:
            mine = [r for r in rows if r.get("model") == model]
            worst = max(mine, key=lambda r: r["de00_mean"])
            share = np.mean([r["fraction_over_jnd"] for r in mine])
            conclusions.append(
                f"BRDF level, {model}: ΔE00 > {JND:g} on {100 * share:.0f} % of (thickness, angle) cells over all bases "
                f"and film IORs; worst mean ΔE00 {worst['de00_mean']:.2f} ({worst['base']}, film IOR {worst['film_ior']})."
                + ("" if len({r["base"] for r in mine}) == len(BASES) else
                   f" Bases without this model: {', '.join(b for b in BASES if all(r['base'] != b for r in mine))}."))
            for base_name in BASES:
                b = [r for r in mine if r["base"] == base_name]
                if not b:
                    continue
                first = [r["first_thickness_over_jnd_nm"] for r in b if r["first_thickness_over_jnd_nm"] is not None]
                conclusions.append(
                    f"  {model} on {base_name}: mean ΔE00 {min(r['de00_mean'] for r in b):.2f}-{max(r['de00_mean'] for r in b):.2f} "
                    f"across film IORs, relative luminance error {100 * np.mean([r['rel_lum_err_mean'] for r in b]):.1f} % on average; "
                    + (f"exceeds the JND from d = {min(first):g} nm on" if first else "never exceeds the JND")
                    + "; share of cells over the JND for d < 100 nm / 100-600 nm / > 600 nm / angles ≥ 60°: "
                    + " / ".join(f"{100 * np.mean([r[k] for r in b]):.0f} %" for k in
                                 ("over_jnd_thin", "over_jnd_mid", "over_jnd_thick", "over_jnd_grazing")) + ".")
        conclusions.append("  (At d = 0 a model differs from the reference only by its bare base: Schlick instead of exact Fresnel "
                           "for KHR, and for metals the three-channel base colour against its upsampled spectrum.)")
        conclusions.append("  (cycles_4_2 blends the film index towards the outside below 30 nm, so thin films fade out by "
                           "construction; it exists for dielectric bases only.)")
        figures.append(self.heatmaps(ctx, maps, thickness, angles))

    def heatmaps(self, ctx, maps, thickness, angles):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        film = 1.8 if 1.8 in FILM_IORS else FILM_IORS[0]
        models = list(thin_film_maps.MODELS)
        fig, axes = plt.subplots(len(BASES), len(models), figsize=(3.8 * len(models), 3.3 * len(BASES)), squeeze=False)
        fig.subplots_adjust(hspace=0.65, wspace=0.3, right=0.84, top=0.9)
        for i, base in enumerate(BASES):
            for j, model in enumerate(models):
                if (base, film, model) not in maps:   # model without a form for this base
                    axes[i][j].set_axis_off()
                    axes[i][j].set_title(f"{model}\n{base}: not defined", fontsize=8)
                    continue
                im = axes[i][j].imshow(maps[(base, film, model)].T, origin="lower", aspect="auto", vmin=0, vmax=10,
                                       extent=[thickness[0], thickness[-1], angles[0], angles[-1]], cmap="magma")
                axes[i][j].contour(thickness, angles, maps[(base, film, model)].T, levels=[JND], colors="cyan", linewidths=0.6)
                axes[i][j].set_title(f"{model}\n{base}", fontsize=8)
                axes[i][j].set_xlabel("thickness [nm]", fontsize=7)
                axes[i][j].set_ylabel("angle [°]", fontsize=7)
        fig.colorbar(im, cax=fig.add_axes([0.87, 0.25, 0.02, 0.5]), label="ΔE00 (cyan: JND = 1)")
        fig.suptitle(f"ΔE00 against exact interference, film IOR {film}", fontsize=10)
        out = ctx.out_dir / "brdf_de00_maps.png"
        fig.savefig(out, dpi=90)
        plt.close(fig)
        return out

    # -- rendered scenes -----------------------------------------------------------------------
    def render_level(self, ctx, rows, figures, conclusions):
        for label in SCENES:
            refs = [j.output for j in ctx.by_sweep("reference") if j.label == label]
            ref = ctx.merge(refs, ctx.out_dir / "reference" / f"{label}.exr")
            series, mine = {}, []
            for job in [j for sweep in RGB_SWEEPS for j in ctx.by_sweep(sweep)] + ctx.by_sweep("spectral"):
                if job.label != label:
                    continue
                name = f"RGB {job.settings['rgb_mode']}" if job.sweep in RGB_SWEEPS else f"spectral N={job.settings['spectral_samples']}"
                m = ctx.compare(job.output, ref)
                row = job_row(job, {"level": "render", "model": name, "de00_mean": m["de00_mean"], "de00_p99": m["de00_p99"],
                                    "relmse": m["relmse"]})
                rows.append(row)
                mine.append(row)
                series.setdefault(name, ([], []))
                series[name][0].append(row.get("render_time_s", float("nan")))
                series[name][1].append(m["de00_mean"])
            figures.append(grid.line_plot(series, ctx.out_dir / f"{label}_de00_vs_time.png", "render time [s]",
                                          "mean ΔE00 vs spectral reference", title=f"{label} spheres", logx=True))
            best = {}
            for r in mine:
                if r["spp"] == max(x["spp"] for x in mine):
                    best[r["model"]] = r
            conclusions.append(f"Rendered {label} spheres at {max(x['spp'] for x in mine)} spp: " + "; ".join(
                f"{k} ΔE00 {v['de00_mean']:.2f} in {v.get('render_time_s', float('nan')):.1f} s" for k, v in sorted(best.items())) + ".")
            sweep = next(name for name, labels in RGB_SWEEPS.items() if label in labels)
            cells = [[ref] + [next(j.output for j in ctx.by_sweep(sweep) if j.label == label and j.settings["rgb_mode"] == mode
                                   and j.settings["spp"] == max(self.cfg(ctx.args.quick)["spp_levels"])) for mode in RGB_MODES[label]]]
            figures.append(grid.image_grid(cells, ctx.out_dir / f"{label}_renders.jpg",
                                           col_labels=["spectral reference"] + [f"RGB {m}" for m in RGB_MODES[label]], cell_inches=2.6))

    def analyse(self, ctx):
        rows, figures, conclusions = [], [], []
        self.brdf_level(ctx, rows, figures, conclusions)
        self.render_level(ctx, rows, figures, conclusions)
        cols = ["level", "base", "scene", "film_ior", "model", "spp", "de00_mean", "de00_p95", "de00_max", "fraction_over_jnd",
                "over_jnd_thin", "over_jnd_mid", "over_jnd_thick", "over_jnd_grazing", "first_thickness_over_jnd_nm",
                "rel_lum_err_mean", "render_time_s"]
        return Analysis(rows, cols, conclusions, figures=figures)


if __name__ == "__main__":
    sys.exit(run(IndustryThinFilm()))
