#!/usr/bin/python3
"""Where a camera sample's instructions go, iris against Mitsuba 0.6, on the peer scenes (issue 37,
item 1): callgrind instruction counts of one-thread renders, per camera sample, split into the
functions the render loop spends them in.

Wall time says how far iris is from a peer; instruction counts say where: they have no machine
noise (two runs of the render loop differ by a few hundred instructions in billions, from memory
allocation), so a small scene at a few samples per pixel suffices. Each
renderer renders the peer scene (../shared/peers/scenes/mitsuba/NAME.xml, 320×240) at `--spp`
samples per pixel with one thread under `valgrind --tool=callgrind`; the table gives the inclusive
instructions of the render loop and of named functions inside it, divided by the number of camera
samples (width × height × spp). Rows are inclusive, so they overlap ("of which" rows are parts of
the row above them). Loading (parsing, BVH or kd-tree build, tables) is outside the loop and shown
apart: at the scenes' own 64 spp it is amortised over 8× the samples of an 8-spp run.

Mitsuba 0.6 is compiled for SSE2/3 and iris's Embree picks AVX2 at run time, so an instruction is
not the same amount of work on both sides; the ratio of loop instructions is a guide to where the
per-sample work differs, not a time ratio (the side-by-side timing is peers.py's).

    /usr/bin/python3 experiments/perf/instruction_breakdown.py --peers-bin ../shared/peers/bin
        [--iris build/render] [--mitsuba-rgb EXE] [--scene-list spheres,bunny,dragon] [--spp 8]
        [--out experiments/perf/results/instruction_breakdown.md]

Needs valgrind and callgrind_annotate. Function names come from the executables' symbol tables
(present in a Release build; `-g` only splits inlined code by source file, which the table ignores
by taking each function's largest inclusive line).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

from iris_experiments.report import machine_info, markdown_table, provenance  # noqa: E402
from iris_experiments.tools import REPO  # noqa: E402
from peers import PEER_LAYOUT, command, out_for, prepare, scene_for  # noqa: E402

# (label, function name prefix as callgrind_annotate prints it, nesting level). The loop row is the
# denominator of the shares.
IRIS_ROWS = [
    ("render loop (tiles, samples, film)", "iris::Renderer::render(iris::Film&, std::atomic<bool> const*, iris::SpectralFilm*, iris::StokesFilm*) const::{lambda(tbb::detail::d1::blocked_range<int> const&)#2}::operator()", 0),
    ("camera rays (`PerspectiveSensor::generateRay`)", "iris::PerspectiveSensor::generateRay(", 1),
    ("wavelength sampling, with D65 (`SampledWavelengths::sampleVisible`)", "iris::SampledWavelengths::sampleVisible(", 1),
    ("spectrum to XYZ (`toXYZ`)", "iris::toXYZ(", 1),
    ("path (`PathIntegrator::Li`)", "iris::PathIntegrator::Li(", 1),
    ("ray queries (`Scene::intersect`)", "iris::Scene::intersect(iris::Ray const&)", 2),
    ("Embree (`rtcIntersect1`)", "rtcIntersect1", 3),
    ("surface interaction (`Scene::hitInteraction`)", "iris::Scene::hitInteraction(", 3),
    ("next-event estimation (`PathIntegrator::directLight`)", "iris::PathIntegrator::directLight(", 2),
    ("shadow rays (`Scene::occluded`)", "iris::Scene::occluded(iris::Ray const&)", 3),
    ("Embree (`rtcOccluded1`)", "rtcOccluded1", 4),
    ("RGB to spectrum at the path's wavelengths (`RGBSpectrum::sample`, anywhere)", "iris::RGBSpectrum::sample(", 1),
]
MITSUBA_ROWS = [
    ("render loop (`SamplingIntegrator::renderBlock`)", "mitsuba::SamplingIntegrator::renderBlock(", 0),
    ("camera rays (`sampleRayDifferential`)", "mitsuba::PerspectiveCameraImpl::sampleRayDifferential(", 1),
    ("path (`MIPathTracer::Li`)", "mitsuba::MIPathTracer::Li(", 1),
    ("ray queries with intersection record (`ShapeKDTree::rayIntersect(ray, its)`)",
     "mitsuba::ShapeKDTree::rayIntersect(mitsuba::TRay<mitsuba::TPoint3<float>, mitsuba::TVector3<float> > const&, mitsuba::Intersection&)", 2),
    ("emitter sampling with its shadow ray (`Scene::sampleEmitterDirect`)", "mitsuba::Scene::sampleEmitterDirect(", 2),
    ("shadow rays (`ShapeKDTree::rayIntersect(ray)`)",
     "mitsuba::ShapeKDTree::rayIntersect(mitsuba::TRay<mitsuba::TPoint3<float>, mitsuba::TVector3<float> > const&) const", 3),
]
TOTAL_LINE = re.compile(r"^\s*([\d,]+)(?: \([^)]*\))?\s+PROGRAM TOTALS")
COST_LINE = re.compile(r"^\s*([\d,]+) \(\s*[\d.]+%\)\s+(?:[*<>]\s+)?([^:\s][^:]*):(.*?)(?: \[[^\]]*\])?$")


def callgrind(cmd: list[str], out: Path, cwd: Path) -> None:
    full = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", *cmd]
    r = subprocess.run(full, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"instruction_breakdown: `{' '.join(cmd)}` failed under callgrind:\n{r.stderr[-2000:]}")


def inclusive_costs(profile: Path) -> tuple[int, dict[str, int]]:
    """Program total and, per function, its largest inclusive line (with -g, inlined code is split
    into extra lines per source file; the function's own line is the largest)."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", str(profile)],
                          capture_output=True, text=True, check=True).stdout
    return parse_inclusive(text)


def parse_inclusive(text: str) -> tuple[int, dict[str, int]]:
    """callgrind_annotate --inclusive=yes output: (program total, {function: largest inclusive})."""
    total, costs = 0, {}
    for line in text.splitlines():
        m = TOTAL_LINE.match(line)
        if m:
            total = int(m.group(1).replace(",", ""))
            continue
        m = COST_LINE.match(line)
        if m:
            cost, func = int(m.group(1).replace(",", "")), m.group(3)
            costs[func] = max(costs.get(func, 0), cost)
    return total, costs


def cost_of(costs: dict[str, int], prefix: str) -> int | None:
    found = [c for f, c in costs.items() if f.startswith(prefix)]
    return max(found) if found else None


def breakdown(rows, total: int, costs: dict[str, int], samples: int) -> tuple[list[dict], int]:
    loop = cost_of(costs, rows[0][1])
    if not loop:
        sys.exit(f"instruction_breakdown: no render-loop function `{rows[0][1]}` in the profile")
    out = []
    for label, prefix, level in rows:
        c = cost_of(costs, prefix)
        out.append({"what": ("  " * level + ("of which " if level > 1 else "")) + label,
                    "per sample": "—" if c is None else f"{c / samples:,.0f}",
                    "share of loop": "—" if c is None else f"{100 * c / loop:.1f} %",
                    "instructions": c})
    out.append({"what": "outside the loop (start-up, loading, acceleration structure, writing the image)",
                "per sample": f"{(total - loop) / samples:,.0f}", "share of loop": "",
                "instructions": total - loop})
    return out, loop


def film_size(xml: Path) -> tuple[int, int]:
    s = xml.read_text()
    w = re.search(r'<integer name="width" value="(\d+)"', s)
    h = re.search(r'<integer name="height" value="(\d+)"', s)
    if not (w and h):
        sys.exit(f"instruction_breakdown: {xml}: no film width/height")
    return int(w.group(1)), int(h.group(1))


# The runs per scene: (label, peers.py renderer name, rows of the table). Command lines, scene
# copies and output names are peers.py's (command, scene_for, out_for), run with one thread.
RUNS = [("iris spectral N = 4", "iris-s4", IRIS_ROWS), ("iris RGB", "iris-rgb", IRIS_ROWS),
        ("Mitsuba 0.6 RGB", "mts-rgb", MITSUBA_ROWS)]


def measure_scene(args, scene: str, work: Path) -> dict:
    files = prepare(args, scene, work, spp=args.spp)
    w, h = film_size(files["xml"])
    samples = w * h * args.spp
    result = {"scene": scene, "width": w, "height": h, "spp": args.spp, "camera_samples": samples, "runs": {}}
    exes = {"iris-s4": args.iris, "iris-rgb": args.iris, "mts-rgb": args.mts_rgb}
    for label, name, rows in RUNS:
        if not exes[name]:
            continue
        prof = work / f"cg_{scene}_{name}.out"
        cmd = command(name, exes[name], scene_for(name, files), out_for(name, scene, work, "instr"), threads=1)
        callgrind(cmd, prof, work)
        total, costs = inclusive_costs(prof)
        table, loop = breakdown(rows, total, costs, samples)
        result["runs"][label] = {"total": total, "loop": loop, "rows": table}
        print(f"instruction_breakdown: {scene}, {label}: {loop / samples:,.0f} loop instructions per sample", file=sys.stderr)
    return result


def summary_rows(results: list[dict]) -> list[dict]:
    rows = []
    for r in results:
        runs, n = r["runs"], r["camera_samples"]
        mts = runs.get("Mitsuba 0.6 RGB")
        for name, run in runs.items():
            row = {"scene": r["scene"], "renderer": name, "loop per sample": f"{run['loop'] / n:,.0f}",
                   "outside the loop per sample": f"{(run['total'] - run['loop']) / n:,.0f}"}
            if mts:
                row["loop ÷ Mitsuba 0.6 RGB's"] = f"{run['loop'] / mts['loop']:.3f}"
                row["whole process at 64 spp ÷ Mitsuba's (estimate)"] = f"{at64(run, r['spp']) / at64(mts, r['spp']):.3f}"
            rows.append(row)
    return rows


def at64(run: dict, spp: int) -> float:
    """A run's instructions scaled to 64 spp: the loop's scale with the samples, the rest does not."""
    return run["loop"] * 64 / spp + (run["total"] - run["loop"])


def write(args, results: list[dict], prov: dict, started: str) -> None:
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    m = machine_info(prov)
    lines = ["# Where a camera sample's instructions go: iris against Mitsuba 0.6 (issue 37, item 1)", "",
             f"Generated by `experiments/perf/instruction_breakdown.py` ({' '.join(sys.argv[1:])}); every number "
             "below was counted in this run (callgrind, one thread). The script's docstring says what the rows are.", "",
             f"- source: {prov['text']}",
             f"- machine: {m['cpu']}, {m['uname']}; started {started} UTC",
             f"- renderers: iris = `{args.iris}`" + (f", Mitsuba 0.6 RGB = `{args.mts_rgb}`" if args.mts_rgb else ""),
             "- Mitsuba 0.6 is built for SSE2/3, iris's Embree runs AVX2: instructions are not equal work "
             "across renderers, and an instruction ratio is not a time ratio.", "",
             "## Summary", "",
             "The 64-spp estimate scales each run's loop instructions to the scenes' own 64 spp and adds its "
             "outside-the-loop instructions once.", ""]
    cols = ["scene", "renderer", "loop per sample", "outside the loop per sample"]
    if args.mts_rgb:
        cols += ["loop ÷ Mitsuba 0.6 RGB's", "whole process at 64 spp ÷ Mitsuba's (estimate)"]
    lines += [markdown_table(summary_rows(results), cols), ""]
    for r in results:
        lines += [f"## {r['scene']} ({r['width']}×{r['height']}, {r['spp']} spp: {r['camera_samples']:,} camera samples)", ""]
        for name, run in r["runs"].items():
            lines += [f"### {name}", "", markdown_table(run["rows"], ["what", "per sample", "share of loop"]), ""]
    out.write_text("\n".join(lines) + "\n")
    out.with_suffix(".json").write_text(json.dumps({"provenance": prov, "results": results}, indent=1) + "\n")
    print(f"instruction_breakdown: wrote {out}", file=sys.stderr)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--iris", default=str(Path(REPO) / "build" / "render"))
    ap.add_argument("--mitsuba-rgb", dest="mts_rgb", help="Mitsuba 0.6 RGB `mitsuba` executable (skipped if not given)")
    ap.add_argument("--peers-bin", help="folder laid out as ../shared/peers/bin: fills --mitsuba-rgb if not given")
    ap.add_argument("--scenes", default=str(Path(REPO).parent / "shared" / "peers" / "scenes"))
    ap.add_argument("--meshes", default=str(Path(REPO).parent / "shared" / "data" / "meshes"))
    ap.add_argument("--scene-list", default="spheres,bunny,dragon")
    ap.add_argument("--spp", type=int, default=8)
    ap.add_argument("--out", default=str(HERE / "results" / "instruction_breakdown.md"))
    args = ap.parse_args(argv)
    for tool in ("valgrind", "callgrind_annotate"):
        if not shutil.which(tool):
            sys.exit(f"instruction_breakdown: `{tool}` not found (Debian package valgrind)")
    if not args.mts_rgb and args.peers_bin:
        args.mts_rgb = str(Path(args.peers_bin) / PEER_LAYOUT["mts-rgb"])
    if args.mts_rgb and not Path(args.mts_rgb).is_file():
        print(f"instruction_breakdown: Mitsuba 0.6 not found at {args.mts_rgb}: skipped", file=sys.stderr)
        args.mts_rgb = None
    # The renderers run in a scratch folder: name them by absolute paths (as peers.renderers does).
    args.iris = os.path.abspath(args.iris)
    args.mts_rgb = args.mts_rgb and os.path.abspath(args.mts_rgb)
    prov = provenance(("experiments/results", "experiments/perf/results"))
    started = time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())
    with tempfile.TemporaryDirectory(prefix="iris_instr_") as tmp:
        results = [measure_scene(args, s, Path(tmp)) for s in args.scene_list.split(",") if s]
    write(args, results, prov, started)


if __name__ == "__main__":
    main()
