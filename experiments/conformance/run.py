#!/usr/bin/env python3
"""Conformance suite: iris against Mitsuba 3's own reference renders of its bsdf_spheres and
participating_media test scenes.

Every scene of ../shared/conformance/mitsuba3 is rendered as written, in spectral mode (against
<name>_ref_spectral.exr), in RGB mode (against <name>_ref_rgb.exr) and in polarized mode (against
<name>_ref_spectral_polarized.exr, the S0 of Mitsuba's scalar_spectral_polarized; the
participating_media suite has none, so its scenes are skipped in that mode); the render's per-pixel
variance of the mean comes from `render --variance` (the film's second moments, in CIE XYZ). Welch's
t-test (Jung, Hanika & Dachsbacher, JCGT 2020) runs per pixel and channel in XYZ and on block means
(welch.py), against a Šidák threshold at significance 0.01 over all tests. A scene that iris cannot
load is reported as "load error: <message>".

    python3 experiments/conformance/run.py                   # all scenes, Mitsuba's test budget
    python3 experiments/conformance/run.py --quick           # fewer samples (CI smoke run)
    python3 experiments/conformance/run.py --scenes test_envmap,test_roughdielectric --modes rgb
    python3 experiments/conformance/run.py --perturb albedo=1.02 --reference iris   # must be rejected
    python3 experiments/conformance/run.py --expect experiments/conformance/expected.json

Writes report.md and results.json to experiments/results/conformance/ (or --out); with --expect,
exits 1 when a verdict differs from the file's (scene/mode → pass | fail | load error).
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

import mitsuba_refs  # noqa: E402
import perturb  # noqa: E402
import welch  # noqa: E402
from table import table  # noqa: E402
from iris_experiments import tools  # noqa: E402
from iris_experiments.errors import ExperimentError  # noqa: E402
from iris_experiments.exr import read_exr, read_exr_metadata  # noqa: E402
from iris_experiments.report import markdown_table, provenance  # noqa: E402

SIGNIFICANCE = 0.01
MODES = ("spectral", "rgb", "polarized")
# The mode a failing render is compared with in the diagnosis (iris's and Mitsuba's other variant).
OTHER_MODE = {"spectral": "rgb", "rgb": "spectral", "polarized": "spectral"}
QUICK_SPP = 128
SKIP = 77   # exit code when the shared scenes are not beside the repository (ctest SKIP_RETURN_CODE)


def render(render_exe: Path, scene: Path, mode: str, spp: int, seed: int, out: Path, defines: tuple = ()):
    """Render scene (with -D name=value for each of `defines`); returns (XYZ mean, XYZ variance of the
    mean, spp) or raises RuntimeError with render's error line."""
    image, var = out.with_suffix(".exr"), out.with_name(out.stem + "_var.exr")
    # RGB mode: the film's own space (linear Rec.709), taken to XYZ below by the same matrix as
    # Mitsuba's RGB reference, so that no difference between two renditions of the sRGB matrix
    # (iris's OCIO config has the 4-digit IEC one) is mistaken for a bias at pixels of tiny variance.
    space = "lin_rec709" if mode == "rgb" else "CIE-XYZ"
    cmd = [str(render_exe), str(scene), "-o", str(image), "--variance", str(var), "--no-png", "--quiet",
           "--mode", mode, "--spp", str(spp), "--seed", str(seed), "--output-space", space]
    for d in defines:
        cmd += ["-D", d]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        lines = [l for l in proc.stderr.strip().splitlines() if l.strip()]
        raise RuntimeError((lines[-1] if lines else f"exit {proc.returncode}").removeprefix("render: error: "))
    mean = _xyz(image) if mode != "rgb" else mitsuba_refs.to_xyz(mitsuba_refs.rgb_channels(image))
    variance = _xyz(var)
    return mean, variance, int(read_exr_metadata(str(image)).get("iris.spp", spp))


def _xyz(path: Path) -> np.ndarray:
    pixels, names, _ = read_exr(str(path))
    order = [names.index(c) for c in (("X", "Y", "Z") if "X" in names else ("R", "G", "B"))]
    return pixels[:, :, order].astype(np.float64)


def channel_ratios(test: np.ndarray, ref: np.ndarray) -> list[float]:
    """Image-mean ratio test/reference per XYZ channel."""
    return [float(test[..., c].sum() / ref[..., c].sum()) if ref[..., c].sum() != 0 else float("nan")
            for c in range(3)]


def integrator_defines(args) -> tuple:
    """The test render's integrator (the scenes' `$integrator` default, path): --integrator."""
    return (f"integrator={args.integrator}",) if args.integrator else ()


def check_one(args, render_exe, name, mode, workdir) -> dict:
    """Render one scene in one mode and test it; returns a row of the table."""
    row = {"scene": name, "mode": mode}
    scene_dir = args.scene_dir or mitsuba_refs.scene_dir_of(name)
    original = mitsuba_refs.scene_path(name, scene_dir)
    scene = original
    if args.perturb:
        scene = perturb.perturbed_copy(original, args.perturb, workdir / f"{name}_perturbed")
    spp = args.spp
    try:
        mean, var, spp = render(render_exe, scene, mode, spp, args.seed, workdir / f"{name}_{mode}", integrator_defines(args))
    except RuntimeError as e:
        return {**row, "verdict": f"load error: {e}", "spp": spp}
    if args.reference == "mitsuba":
        ref_mean, ref_sample_var = mitsuba_refs.reference(name, mode, args.cache, scene_dir)
        ref_n = mitsuba_refs.REFERENCE_SPP
        ref_var = ref_sample_var / ref_n
    else:   # iris itself, unperturbed, with another seed and more samples: checks the test's size and power
        ref_scene = original
        if args.perturb:   # the same kind of edit with its neutral value (albedo=1, fov=0)
            ref_scene = perturb.perturbed_copy(original, perturb.neutral(args.perturb), workdir / f"{name}_neutral")
        ref_mean, ref_var, ref_n = render(render_exe, ref_scene, mode, 4 * spp, args.seed + 1000, workdir / f"{name}_{mode}_ref")
    if ref_mean.shape != mean.shape:
        return {**row, "verdict": f"fail: image size {mean.shape[1]}x{mean.shape[0]}, reference {ref_mean.shape[1]}x{ref_mean.shape[0]}",
                "spp": spp}
    var = welch.floor_by_reference(var, spp, ref_var, ref_n)   # rare-event pixels (welch.py)
    r = welch.multiscale_test(mean, var, spp, ref_mean, ref_var, ref_n, SIGNIFICANCE)
    ratios = channel_ratios(mean, ref_mean)
    extra = {}
    if args.reference == "mitsuba":
        passed, fraction, _ = welch.mitsuba_z_test(mean, spp, ref_mean, ref_sample_var, SIGNIFICANCE)
        extra = {"mitsuba_ztest": "pass" if passed else "fail", "mitsuba_ztest_fraction": fraction}
        if not r["passed"]:
            other_render = render(render_exe, scene, OTHER_MODE[mode], spp, args.seed + 500,
                                  workdir / f"{name}_{mode}_other", integrator_defines(args))
            extra["diagnosis"] = diagnose(args, name, mode, r, mean, var, ref_mean, ref_var, other_render)
    pixel_p = r["per_scale"][1]
    if args.worst:
        print_worst_pixels(name, mode, pixel_p, mean, var, ref_mean, ref_var, args.worst)
        for k, p in r["per_scale"].items():
            if k != 1:
                y, x, c = np.unravel_index(np.argmin(p), p.shape)
                print(f"  {name} {mode} worst {'whole-image' if k == 0 else f'{k}x{k} block'} test: "
                      f"block x={x} y={y} {'XYZ'[c]} p {p[y, x, c]:.3g}")
    return {**row, "verdict": "pass" if r["passed"] else "fail", "p_min": r["p_min"], "threshold": r["threshold"],
            "scale": r["scale"], "tests": r["tests"], "spp": spp, "ref_spp": ref_n,
            "rejected_pixels": int(np.count_nonzero((pixel_p <= r["threshold"]).any(axis=2))),
            "ratio_X": ratios[0], "ratio_Y": ratios[1], "ratio_Z": ratios[2], **extra}


def diagnose(args, name, mode, r, mean, var, ref_mean, ref_var, other_render) -> dict:
    """Where a render fails, compare at the failing block (or pixel) iris with Mitsuba's reference of
    the same variant, Mitsuba's two references with each other (spectral against RGB), iris's two
    modes with each other (other_render: iris's render in the other mode, another seed), and iris
    with Mitsuba's reference of the other variant: t and ratio per XYZ channel. When Mitsuba's own
    two variants disagree there by more than their noise while iris's agree, no renderer can agree
    with both of Mitsuba's; the table of docs/conformance.md shows which one iris agrees with."""
    k = r["scale"]
    p = r["per_scale"][k]
    by, bx, c = np.unravel_index(np.argmin(p), p.shape)
    other = OTHER_MODE[mode]
    mitsuba_other, mitsuba_other_sample_var = mitsuba_refs.reference(name, other, args.cache,
                                                                     args.scene_dir or mitsuba_refs.scene_dir_of(name))
    mitsuba = {mode: (ref_mean, ref_var), other: (mitsuba_other, mitsuba_other_sample_var / mitsuba_refs.REFERENCE_SPP)}
    iris = {mode: (mean, var), other: other_render[:2]}
    # Spectral and RGB rows compare Mitsuba's and iris's spectral with their RGB renders; polarized
    # rows their polarized with their spectral ones (table.py names the columns).
    first, second = ("spectral", "rgb") if mode != "polarized" else ("polarized", "spectral")
    pairs = {"iris_vs_same": (*iris[mode], *mitsuba[mode]),
             f"mitsuba_{first}_vs_{second}": (*mitsuba[first], *mitsuba[second]),
             f"iris_{first}_vs_{second}": (*iris[first], *iris[second]),
             "iris_vs_other": (*iris[mode], *mitsuba[other])}
    out = {"scale": int(k), "block_x": int(bx), "block_y": int(by), "channel": "XYZ"[c], "other_variant": other}
    for key, (m1, v1, m2, v2) in pairs.items():
        t, ratio = welch.block_t_and_ratio(m1, v1, m2, v2, k, bx, by)
        out[key] = {"t": [float(x) for x in t], "ratio": [float(x) for x in ratio]}
    return out


def print_worst_pixels(name, mode, pixel_p, mean, var, ref_mean, ref_var, count):
    """Diagnosis (--worst N): the N single-pixel tests with the smallest p-values, with both
    means, their ratio and the t statistic."""
    order = np.argsort(pixel_p, axis=None)[:count]
    for flat in order:
        y, x, c = np.unravel_index(flat, pixel_p.shape)
        m, r = mean[y, x, c], ref_mean[y, x, c]
        t = (m - r) / np.sqrt(var[y, x, c] + ref_var[y, x, c]) if var[y, x, c] + ref_var[y, x, c] > 0 else float("inf")
        print(f"  {name} {mode} pixel x={x} y={y} {'XYZ'[c]}: iris {m:.5g} mitsuba {r:.5g} "
              f"ratio {m / r if r else float('nan'):.4f} t {t:.2f} p {pixel_p[y, x, c]:.3g}")


def verdict_class(verdict: str) -> str:
    return "load error" if verdict.startswith("load error") else ("pass" if verdict == "pass" else "fail")


def write_report(args, rows, seconds, prov) -> Path:
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    passed = sum(r["verdict"] == "pass" for r in rows)
    loaded = sum(not r["verdict"].startswith("load error") for r in rows)
    settings = {"spp": args.spp, "seed": args.seed, "reference": args.reference,
                "reference spp": mitsuba_refs.REFERENCE_SPP if args.reference == "mitsuba" else 4 * args.spp,
                "significance": SIGNIFICANCE, "scales": list(welch.SCALES), "perturbation": args.perturb or "none",
                "integrator": args.integrator or "the scenes' (path)",
                "command": " ".join(["python3", "experiments/conformance/run.py"] + sys.argv[1:])}
    md = ["# Conformance: iris against Mitsuba 3's reference renders", "",
          f"{passed} of {len(rows)} scene/mode pairs pass; {loaded} load. "
          f"Welch's t-test per pixel and XYZ channel and on 4x4, 16x16 and whole-image block means; "
          f"Šidák threshold for significance {SIGNIFICANCE} over all tests of a render. 'at' is the "
          f"scale of the smallest p-value; ratios are image means iris / reference per XYZ channel.", "",
          table(rows), "", "Settings: " + json.dumps(settings), "",
          f"Generated by experiments/conformance/run.py in {seconds:.0f} s; {prov['text']} (at the start of the run).", ""]
    (out / "report.md").write_text("\n".join(md))
    (out / "results.json").write_text(json.dumps({"settings": settings, "rows": rows}, indent=1))
    return out / "report.md"


def check_expectations(rows, path: Path) -> list[str]:
    expected = json.loads(path.read_text())
    problems = []
    for r in rows:
        key = f"{r['scene']}/{r['mode']}"
        if key in expected and verdict_class(r["verdict"]) != expected[key]:
            problems.append(f"{key}: expected {expected[key]}, got {r['verdict']}")
    return problems


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help=f"{QUICK_SPP} spp instead of Mitsuba's test budget")
    ap.add_argument("--scenes", help="comma-separated test names (default: all), e.g. test_envmap")
    ap.add_argument("--modes", default=",".join(MODES), help="spectral,rgb,polarized (default all three)")
    ap.add_argument("--spp", type=int, help="samples per pixel (default: 2e6 / pixel count, Mitsuba's test budget)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--reference", choices=("mitsuba", "iris"), default="mitsuba",
                    help="iris: test against iris's own render of the unperturbed scene (4x spp, another seed)")
    ap.add_argument("--perturb", help="a deliberate error in a temporary copy: albedo=F or fov=D (see perturb.py)")
    ap.add_argument("--integrator", help="render the tested images with this integrator (-D integrator=NAME: ptracer, bdpt); "
                                         "with --reference iris the reference keeps the scene's own (path)")
    ap.add_argument("--expect", help="JSON of expected verdicts (scene/mode → pass|fail|load error)")
    ap.add_argument("--expect-all", choices=("pass", "fail", "load error"), help="the verdict every scene/mode must have")
    ap.add_argument("--update-expected", help="write the verdicts of this run to this JSON file (merged into it)")
    ap.add_argument("--scene-dir", type=Path, default=None,
                    help="one suite folder (default: every suite, bsdf_spheres and participating_media)")
    ap.add_argument("--out", default=str(tools.REPO / "experiments" / "results" / "conformance"))
    ap.add_argument("--build-dir")
    ap.add_argument("--worst", type=int, default=0, metavar="N",
                    help="diagnosis: print the N pixel tests with the smallest p-values per render")
    args = ap.parse_args(argv)
    if not (args.scene_dir or mitsuba_refs.SUITE_DIR).is_dir():
        print(f"conformance: {args.scene_dir or mitsuba_refs.SUITE_DIR} not found (../shared is not beside the repository); skipped")
        return SKIP
    try:
        render_exe = tools.tool("render", tools.build_dir(args.build_dir))
        names = args.scenes.split(",") if args.scenes else mitsuba_refs.scene_names(args.scene_dir)
        modes = args.modes.split(",")
        if args.spp is None:
            args.spp = QUICK_SPP if args.quick else mitsuba_refs.TEST_SAMPLE_BUDGET // (48 * 48)
        start = time.monotonic()
        prov = provenance()  # the commit the renders come from, before anything can change the tree
        rows = []
        with tempfile.TemporaryDirectory(prefix="iris_conformance_") as tmp:
            args.cache = Path(tmp) / "refs"
            for name in names:
                for mode in modes:
                    if args.reference == "mitsuba" and not mitsuba_refs.has_reference(
                            name, mode, args.scene_dir or mitsuba_refs.scene_dir_of(name)):
                        print(f"{name:42s} {mode:8s} skipped: Mitsuba has no reference in this mode", flush=True)
                        continue
                    row = check_one(args, render_exe, name, mode, Path(tmp))
                    rows.append(row)
                    print(f"{name:42s} {mode:8s} {row['verdict'][:90]}"
                          + (f"  p_min {row['p_min']:.3g} (threshold {row['threshold']:.3g})" if "p_min" in row else ""),
                          flush=True)
        report = write_report(args, rows, time.monotonic() - start, prov)
        print(f"report: {report}")
        if args.update_expected:
            path = Path(args.update_expected)
            known = json.loads(path.read_text()) if path.exists() else {}
            known.update({f"{r['scene']}/{r['mode']}": verdict_class(r["verdict"]) for r in rows})
            path.write_text(json.dumps(dict(sorted(known.items())), indent=1) + "\n")
        problems = []
        if args.expect:
            problems += check_expectations(rows, Path(args.expect))
        if args.expect_all:
            problems += [f"{r['scene']}/{r['mode']}: expected {args.expect_all}, got {r['verdict']}"
                         for r in rows if verdict_class(r["verdict"]) != args.expect_all]
        if args.expect or args.expect_all:
            for p in problems:
                print(f"conformance: {p}", file=sys.stderr)
            return 1 if problems else 0
        return 0
    except ExperimentError as e:
        print(f"conformance: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
