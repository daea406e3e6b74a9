#!/usr/bin/env python3
"""Agreement of the light-tracing integrators with the path tracer (issue 35, item 3).

On every scene where `path` converges — Mitsuba 3's conformance scenes (../shared/conformance, through
their `$integrator` default), the regression close-ups (tests/data/regression/scenes/closeup.xml with
each thesis material, the exact thin film and the iridescent diffuse), the shipped scenes (default,
thin-film spheres, the thesis comparison scene when ../shared/data has the dragon) and the caustic
scenes with their area light (scenes/caustics/) — `ptracer` and `bdpt` are rendered in spectral and
RGB mode and compared with `path` (4× the samples, another seed) by Welch's t-test per pixel and
XYZ channel and on 4×4, 16×16 and whole-image blocks, at a Šidák-corrected level of 0.01
(experiments/conformance/welch.py, as the conformance suite). A scene whose integrator element is
not `$integrator` is switched in a temporary copy (`direct` becomes max_depth 2).

`ptracer` cannot sample paths whose vertex next to the camera is a delta lobe (smooth glass and
mirrors seen directly, the specular coat of `plastic`): on scenes that show such surfaces its
verdict is expected to fail there; the table says so for each scene (column `ptracer sees`).
On glossy surfaces (the thin film on gold, alpha 0.1, under the constant sky) its splats are
heavy-tailed: at low sample counts the image mean is low and the sample variance too small, so the
t-test fails although the mean converges (Y ratio 0.73 at 32 spp, 1.02 at 1024 spp in a 24² run);
a failing verdict there is not by itself a bias. So ptracer renders --ptracer-spp-factor (16) times the
samples where it sees every surface, and on the close-ups a control runs the same test between two
unbiased estimators inside BDPT (its unweighted splits (0, 3) and (1, 2), `control`): where the
control fails too, the test cannot separate heavy tails from bias on that scene. Its report is
experiments/results/light_tracing_agreement/.

    python3 experiments/light_tracing_agreement.py                 # everything
    python3 experiments/light_tracing_agreement.py --quick         # 24² pixels, few samples (smoke)
    python3 experiments/light_tracing_agreement.py --scenes default,caustic_glass --integrators bdpt
"""
from __future__ import annotations

import argparse
import json
import re
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE / "conformance"))

import mitsuba_refs  # noqa: E402
import welch  # noqa: E402
from run import render  # noqa: E402
from iris_experiments import tools  # noqa: E402
from iris_experiments.report import markdown_table, provenance  # noqa: E402

SIGNIFICANCE = 0.01
REPO = tools.REPO
CLOSEUP = "tests/data/regression/scenes/closeup.xml"

# name → (scene file relative to the repository or absolute, -D defines, whether every camera-visible
# surface has a non-delta lobe (else ptracer misses part of the image), needs the shared data)
SCENES = {
    **{f"closeup_{m}": (CLOSEUP, {"material": m}, True, False)
       for m in ("granier_table31", "proposed_table42", "proposed_table43", "thinfilm_gold", "iridescent_diffuse")},
    "default": ("scenes/default.xml", {}, False, False),
    "thinfilm_spheres": ("scenes/thinfilm_spheres.xml", {}, False, False),
    "thesis_comparison_table43": ("scenes/thesis_comparison_table43.xml", {}, True, True),
    "caustic_glass": ("scenes/caustics/glass_sphere.xml", {"light": "area"}, False, False),
    "caustic_bubble": ("scenes/caustics/glass_sphere.xml", {"light": "area", "coating": "bubble"}, False, False),
}
# Conformance scenes whose grid of spheres has smooth glass, mirror and plastic spheres in view.
CONFORMANCE_DELTA_VISIBLE = True


def uses_integrator_default(scene: Path) -> bool:
    """The scene (or the conformance fragment it includes) names `$integrator`."""
    return "$integrator" in scene.read_text() or scene.parent == mitsuba_refs.SCENE_DIR


def integrator_copy(scene: Path, element: str, stem: str, workdir: Path, path_type: str | None = None) -> Path:
    """A temporary copy of `scene` (workdir/stem.xml) whose `<integrator type="direct"/>` is `element`,
    or, failing that and given `path_type`, whose `<integrator type="path"` is of that type; `<path>`
    keeps relative names working."""
    text = scene.read_text()
    text = re.sub(r'<scene version="[^"]*">', lambda m: m.group(0) + f'\n    <path value="{scene.parent}"/>', text, count=1)
    text, n = re.subn(r'<integrator type="direct"\s*/>', element, text, count=1)
    if not n and path_type:
        text, n = re.subn(r'<integrator type="path"', f'<integrator type="{path_type}"', text, count=1)
    if not n:
        raise SystemExit(f"{scene}: no integrator element to switch")
    out = workdir / f"{stem}.xml"
    out.write_text(text)
    return out


def switched_copy(scene: Path, integrator: str, workdir: Path) -> Path:
    """`scene` rendering with `integrator` (a `direct` scene's becomes max_depth 2)."""
    if uses_integrator_default(scene):
        return scene
    element = f'<integrator type="{integrator}"><integer name="max_depth" value="2"/></integrator>'
    return integrator_copy(scene, element, f"{scene.stem}_{integrator}", workdir, path_type=integrator)


def strategy_copy(scene: Path, strategy: str, workdir: Path) -> Path:
    """A copy of a `direct` scene rendering one BDPT split unweighted (max_depth 2: the paths of two
    segments only), an estimate of the whole path length by that split alone."""
    element = ('<integrator type="bdpt"><integer name="max_depth" value="2"/>'
               f'<string name="strategy" value="{strategy}"/><boolean name="mis_weights" value="false"/></integrator>')
    return integrator_copy(scene, element, f"{scene.stem}_bdpt_{strategy.replace(',', '_')}", workdir)


def control(args, render_exe, name, scene, defines, mode, workdir) -> dict:
    """The heavy-tail control: two unbiased estimators of the same image inside one integrator, BDPT's
    split (0, 3) (the camera path's BSDF sample reaches the light) against split (1, 2) (next-event
    estimation), both unweighted, at 4x --spp each, by the same test. Where these two disagree by
    Welch's test, a sharp lobe makes one of them heavy-tailed and the test cannot tell an unbiased
    heavy-tailed image from a biased one, so a ptracer rejection there is no evidence of bias."""
    d = defines_for(scene, defines, "bdpt", args.res)
    spp = 4 * args.spp
    ref = render(render_exe, strategy_copy(scene, "1,2", workdir), mode, spp, args.seed + 2000, workdir / f"{name}_{mode}_s12", d)
    test = render(render_exe, strategy_copy(scene, "0,3", workdir), mode, spp, args.seed + 3000, workdir / f"{name}_{mode}_s03", d)
    return verdict_row(name, mode, "control: bdpt split (0,3) vs (1,2), unweighted", test, ref)


def verdict_row(name: str, mode: str, integrator: str, test: tuple, ref: tuple) -> dict:
    """Welch's multiscale test of `test` against `ref`, each (mean, variance of the mean, spp) as
    render() returns them (the test's variance floored by the reference's), as a report row."""
    mean, var, n = test
    ref_mean, ref_var, ref_n = ref
    var = welch.floor_by_reference(var, n, ref_var, ref_n)
    r = welch.multiscale_test(mean, var, n, ref_mean, ref_var, ref_n, SIGNIFICANCE)
    ratio = float(mean[..., 1].sum() / ref_mean[..., 1].sum()) if ref_mean[..., 1].sum() else float("nan")
    return {"scene": name, "mode": mode, "integrator": integrator, "verdict": "pass" if r["passed"] else "fail",
            "p_min": r["p_min"], "threshold": r["threshold"], "scale": r["scale"], "ratio_Y": ratio,
            "spp": n, "ref_spp": ref_n, **failing_pixels(r, mean, ref_mean, ref_var)}


def scene_list(args) -> list[tuple[str, Path, dict, bool]]:
    rows = []
    for name, (path, defines, ptracer_sees, shared) in SCENES.items():
        full = REPO / path
        if shared and not (REPO.parent / "shared" / "data").is_dir() and not (REPO / ".." / "shared").is_dir():
            continue
        rows.append((name, full, defines, ptracer_sees))
    if mitsuba_refs.SCENE_DIR.is_dir():
        for n in mitsuba_refs.scene_names():
            rows.append((n, mitsuba_refs.scene_path(n), {}, not CONFORMANCE_DELTA_VISIBLE))
    if args.scenes:
        wanted = set(args.scenes.split(","))
        rows = [r for r in rows if r[0] in wanted]
    return rows


def defines_for(scene: Path, defines: dict, integrator: str, res: int | None) -> tuple:
    text = scene.read_text()
    d = dict(defines)
    if uses_integrator_default(scene):
        d["integrator"] = integrator
    if res and '<default name="res"' in text:
        d["res"] = str(res)
    return tuple(f"{k}={v}" for k, v in d.items())


def test_spp(args, integrator: str, ptracer_sees: bool) -> int:
    """Samples per pixel of the test render. `ptracer`'s per-pass pixel values are sums of a few
    light-path splats, heavy-tailed on glossy receivers: at the reference's sample counts their
    sample variance underestimates the variance of the mean and Welch's test rejects an unbiased
    image (at every rejected pixel the ptracer estimate is the lower one). With
    --ptracer-spp-factor times more passes the means are close enough to normal for the test, on
    the scenes where ptracer sees every surface (elsewhere it is black on delta surfaces by
    construction and not comparable, so it keeps the base count)."""
    return args.spp * (args.ptracer_spp_factor if integrator == "ptracer" and ptracer_sees else 1)


def compare(args, render_exe, name, scene, defines, mode, workdir, ptracer_sees: bool) -> list[dict]:
    # The reference is `path` (a `direct` scene's path of max_depth 2).
    ref_scene = switched_copy(scene, "path", workdir)
    ref = render(render_exe, ref_scene, mode, 4 * args.spp, args.seed + 1000, workdir / f"{name}_{mode}_path",
                 defines_for(scene, defines, "path", args.res))
    rows = []
    for integrator in args.integrators.split(","):
        test_scene = switched_copy(scene, integrator, workdir)
        test = render(render_exe, test_scene, mode, test_spp(args, integrator, ptracer_sees), args.seed,
                      workdir / f"{name}_{mode}_{integrator}", defines_for(scene, defines, integrator, args.res))
        rows.append(verdict_row(name, mode, integrator, test, ref))
    return rows


def failing_pixels(r: dict, mean, ref_mean, ref_var) -> dict:
    """What the rejected pixels (scale 1) look like: how many, how many of them the reference saw with
    zero variance (it never sampled what the test image shows there: a silhouette sliver a light
    path's splat reaches but no camera sample hit), the median |relative difference| over them, and
    the share of them where the test image is the lower one (a heavy-tailed estimator is low at most
    pixels and very high at a few)."""
    p = r["per_scale"].get(1)
    if p is None:
        return {"failing": 0, "ref_blind": 0, "median_rel": float("nan"), "low_share": float("nan")}
    bad = p <= r["threshold"]
    rel = np.abs(mean - ref_mean) / np.maximum(np.abs(ref_mean), 1e-12)
    return {"failing": int(bad.sum()), "ref_blind": int((bad & (ref_var == 0)).sum()),
            "median_rel": float(np.median(rel[bad])) if bad.any() else float("nan"),
            "low_share": float((mean[bad] < ref_mean[bad]).mean()) if bad.any() else float("nan")}


def dash(v: float, spec: str) -> str:
    return "—" if v != v else format(v, spec)


def summary(args, rows) -> str:
    """Pass counts per integrator; ptracer's split by whether it sees every surface of the scene."""
    parts = []
    for i in args.integrators.split(","):
        mine = [r for r in rows if r["integrator"] == i]
        passed = sum(r["verdict"] == "pass" for r in mine)
        if i != "ptracer":
            parts.append(f"{i}: {passed} of {len(mine)} scene/mode pairs pass")
            continue
        seen = [r for r in mine if r["ptracer_sees"]]
        parts.append(f"ptracer: {sum(r['verdict'] == 'pass' for r in seen)} of {len(seen)} scene/mode pairs pass where "
                     f"it sees every surface ({passed} of {len(mine)} in all; on the others it is black on the delta "
                     "surfaces in view by construction, as Mitsuba 3's ptracer is)")
    controls = [r for r in rows if r["integrator"].startswith("control")]
    if controls:
        parts.append(f"heavy-tail control (BDPT's unweighted splits (0,3) against (1,2), see `control`): "
                     f"{sum(r['verdict'] == 'pass' for r in controls)} of {len(controls)} pass")
    return "; ".join(parts) + "."


def write_report(args, rows, seconds, out: Path, prov: dict) -> Path:
    """report.md and results.json; `prov` is the source's provenance taken when the run started."""
    out.mkdir(parents=True, exist_ok=True)
    columns = ["scene", "mode", "integrator", "spp", "verdict", "p-min", "threshold", "at", "Y ratio", "rejected pixel-channels",
               "of which reference variance 0", "median rel. diff there", "share test lower", "ptracer sees every surface"]
    table = [dict(zip(columns, [r["scene"], r["mode"], r["integrator"], r["spp"], r["verdict"], f"{r['p_min']:.3g}", f"{r['threshold']:.3g}",
                                {0: "image", 1: "1x1"}.get(r["scale"], f"{r['scale']}x{r['scale']}"), f"{r['ratio_Y']:.4f}",
                                r["failing"], r["ref_blind"], dash(r["median_rel"], ".2g"), dash(r["low_share"], ".2f"),
                                "yes" if r["ptracer_sees"] else "no: delta surfaces in view"])) for r in rows]
    md = ["# Light tracing against path tracing: agreement by Welch's t-test", "",
          summary(args, rows) + " "
          f"Test: {args.spp} spp (`ptracer` {args.ptracer_spp_factor * args.spp} where it sees every surface: "
          f"its per-pass values are heavy-tailed, see `test_spp`); reference: `path`, {4 * args.spp} spp, another seed; Welch's t-test per pixel and XYZ "
          f"channel and on 4x4, 16x16 and whole-image blocks, Šidák-corrected level {SIGNIFICANCE}; 'at' is the scale of "
          "the smallest p-value, 'Y ratio' the image-mean ratio test / path. `ptracer` cannot sample paths whose vertex "
          "next to the camera has only delta lobes: the last column says whether the scene shows such surfaces. "
          "The four columns before it describe the pixel-channels rejected at scale 1x1 (see `failing_pixels`): a "
          "rejection where the reference's variance is 0 and the difference is tiny is a silhouette sliver that the "
          "light-tracing strategies splat and no camera sample of the reference hit; a heavy-tailed estimate "
          "(ptracer on glossy surfaces under an environment) is low at most rejected pixels (share near 1) while "
          "its image mean stays near the reference's.", "",
          markdown_table(table, columns),
          "", "Command: `" + " ".join(["python3", "experiments/light_tracing_agreement.py"] + sys.argv[1:]) + "`", "",
          f"Generated in {seconds:.0f} s; {prov['text']}.", ""]
    (out / "report.md").write_text("\n".join(md))
    (out / "results.json").write_text(json.dumps({"settings": vars(args) | {"provenance": prov}, "rows": rows}, indent=1, default=str))
    return out / "report.md"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="24x24 pixels where the scene has a res default, 32 spp")
    ap.add_argument("--spp", type=int, help="test samples per pixel (the reference has 4x): default 256, quick 32")
    ap.add_argument("--res", type=int, help="image size where the scene has a `res` default: default 48, quick 24")
    ap.add_argument("--ptracer-spp-factor", type=int, default=16,
                    help="ptracer's spp is this times --spp on scenes where it sees every surface (default 16)")
    ap.add_argument("--no-controls", dest="controls", action="store_false",
                    help="skip the heavy-tail control (BDPT's unweighted splits against each other, see control())")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--scenes", help="comma-separated names (default: all)")
    ap.add_argument("--integrators", default="ptracer,bdpt")
    ap.add_argument("--modes", default="spectral,rgb")
    ap.add_argument("--build-dir")
    ap.add_argument("--out", default=str(REPO / "experiments" / "results" / "light_tracing_agreement"))
    args = ap.parse_args(argv)
    args.spp = args.spp or (32 if args.quick else 256)
    args.res = args.res or (24 if args.quick else 48)
    render_exe = tools.tool("render", tools.build_dir(args.build_dir))
    prov = provenance()  # at the start: the tree may change while the renders run
    start = time.monotonic()
    rows = []
    with tempfile.TemporaryDirectory(prefix="iris_lt_agreement_") as tmp:
        for name, scene, defines, sees in scene_list(args):
            for mode in args.modes.split(","):
                rows_here = compare(args, render_exe, name, scene, defines, mode, Path(tmp), sees)
                if args.controls and sees and "ptracer" in args.integrators and "<integrator type=\"direct\"" in scene.read_text():
                    rows_here.append(control(args, render_exe, name, scene, defines, mode, Path(tmp)))
                for r in rows_here:
                    r["ptracer_sees"] = sees
                    rows.append(r)
                    print(f"{name:40s} {mode:8s} {r['integrator']:8s} {r['verdict']}  p_min {r['p_min']:.3g} "
                          f"(threshold {r['threshold']:.3g})  Y ratio {r['ratio_Y']:.4f}", flush=True)
    print(f"report: {write_report(args, rows, time.monotonic() - start, Path(args.out), prov)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
