#!/usr/bin/python3
"""iris against peer renderers, scene by scene (issue 37): whole-process wall time side by side, and
error at equal wall time with each renderer's best sampler.

The peers are executables given on the command line (never part of the project); a peer not given,
or not executable, is skipped. `--peers-bin DIR` fills the ones found in a folder laid out as
../shared/peers/bin (mitsuba06-rgb/mitsuba, mitsuba06-spec16/mitsuba, tungsten). The scenes are
the peer scene folder's (../shared/peers/scenes: mitsuba/NAME.xml, which iris reads too, and
tungsten/NAME.json): the Stanford bunny under an environment map, the dragon under a constant sky,
two analytic spheres (rough plastic, glass) on a floor under an area light.

1. Timing ("side by side"): every renderer renders each scene as the files define it (320×240,
   64 spp, independent sampler) with `--threads` threads, once as a warm-up (page cache, plugin
   loading; not counted), then `--rounds` rounds in which every renderer runs once, the starting
   renderer rotating from round to round. The figure is the median over rounds of the per-round
   ratio iris ÷ peer of whole-process wall times, so a drift of the machine's speed hits both sides
   of a ratio alike. Mean Rec.709 luminance of each output is printed as a check that the renderers
   draw the same scene.
2. Equal time (`--equal-time`): each renderer with its best sampler available (iris `sobol` and
   `highdimsobol`, each scene's best counting,
   Mitsuba 0.6 `stratified` — the prebuilt 0.6 has no `ldsampler`/`sobol` plugin —, Tungsten's
   default `stratified_sampler`; iris also with `volpath`, whose shadow rays cross the thin glass
   sheet), at a reduced resolution, renders the sample counts of --et-spp and a long
   reference of its own (`--ref-spp`); error = relMSE of the luminance against that reference
   (mean of (x − r)² / (r² + 0.01)), wall time per run as above. Each renderer's own reference makes
   the figure its noise at a given time (renderers differ slightly in their models: the luminance
   check of part 1 shows by how much); relMSE at common time budgets is interpolated log-log between
   measured sample counts (never extrapolated).

    /usr/bin/python3 experiments/perf/peers.py --peers-bin ../shared/peers/bin [--iris build/render]
        [--rounds 5] [--threads 2] [--scenes bunny,dragon,spheres] [--equal-time] [--out DIR]

Writes peers.md and peers.json to --out (default experiments/perf/results/peers; run.py's target 8
calls this script and puts the side-by-side tables in its report); names the commit
(clean or not), the machine and its load. Run it on an otherwise idle machine; timings are never
pass/fail.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from iris_experiments.exr import read_exr  # noqa: E402
from iris_experiments.report import machine_info, markdown_table, provenance  # noqa: E402
from iris_experiments.thin_film_maps import REC709_Y  # noqa: E402
from iris_experiments.tools import REPO  # noqa: E402

import numpy as np  # noqa: E402

PEER_LAYOUT = {"mts-rgb": "mitsuba06-rgb/mitsuba", "mts-s16": "mitsuba06-spec16/mitsuba", "tungsten": "tungsten"}
PEER_LABEL = {"mts-rgb": "Mitsuba 0.6 RGB", "mts-s16": "Mitsuba 0.6 spectral (16)", "tungsten": "Tungsten"}
IRIS_VARIANTS = {"iris-s4": ["--spectral-samples", "4"], "iris-s16": ["--spectral-samples", "16"],
                 "iris-rgb": ["--mode", "rgb"]}
# Part 2's iris runs: name -> (variant of IRIS_VARIANTS, integrator, sampler). iris has two Sobol
# samplers and neither is best everywhere: `sobol` pads independently scrambled 1D/2D sets,
# `highdimsobol` takes the first 32 Sobol dimensions jointly (lower error on the meshes under sky
# light, higher on the caustics of the spheres), so both run and each scene's best counts. The
# volumetric path tracer runs on the same scene: its shadow rays cross pass-through lobes
# (thindielectric's transmission) with their weight where `path`, like Mitsuba's path tracers,
# tests plain occlusion (materials/thindielectric.cpp) — the integrator a user would pick for that.
EQUAL_TIME_IRIS = {"iris-s4": ("iris-s4", "path", "sobol"),
                   "iris-s4-volpath": ("iris-s4", "volpath", "sobol"),
                   "iris-rgb": ("iris-rgb", "path", "sobol"),
                   "iris-s4-highdim": ("iris-s4", "path", "highdimsobol"),
                   "iris-rgb-highdim": ("iris-rgb", "path", "highdimsobol")}


# ---------------------------------------------------------------- scene copies and commands

def scene_text(path: Path, width: int | None = None, height: int | None = None, spp: int | None = None,
               sampler: str | None = None, integrator: str | None = None) -> str:
    """A peer scene file with its resolution, sample count and sampler replaced (text edits of the
    Mitsuba XML or Tungsten JSON the peer folder defines; None keeps the file's value)."""
    s = path.read_text()
    if path.suffix == ".json":
        if width:
            s = re.sub(r'"resolution"\s*:\s*\[\s*\d+\s*,\s*\d+\s*\]', f'"resolution": [{width}, {height}]', s)
        if spp:
            s = re.sub(r'"spp"\s*:\s*\d+', f'"spp": {spp}', s)
        return s
    if width:
        s = re.sub(r'(<integer name="width" value=")\d+', rf'\g<1>{width}', s)
        s = re.sub(r'(<integer name="height" value=")\d+', rf'\g<1>{height}', s)
    if spp:
        s = re.sub(r'(<integer name="sampleCount" value=")\d+', rf'\g<1>{spp}', s)
    if sampler:
        s = re.sub(r'<sampler type="\w+">', f'<sampler type="{sampler}">', s)
    if integrator:
        s = re.sub(r'<integrator type="\w+">', f'<integrator type="{integrator}">', s)
    return s


def command(name: str, exe: str, scene: Path, out: Path, threads: int, extra=()) -> list[str]:
    """The command line of one renderer: output to `out` (iris: EXR; Mitsuba: PFM through the film's
    fileFormat, set in the scene copy; Tungsten: the PFM its scene names, in folder `out`)."""
    if name.startswith("iris"):
        variant = EQUAL_TIME_IRIS[name][0] if name in EQUAL_TIME_IRIS else name
        return [exe, str(scene), "--threads", str(threads), "--quiet", "--no-png", "-o", str(out),
                *IRIS_VARIANTS[variant], *extra]
    if name.startswith("mts"):
        return [exe, "-p", str(threads), "-q", "-o", str(out), *extra, str(scene)]
    return [exe, "-t", str(threads), "-d", str(out), *extra, str(scene)]


def run_wall(cmd: list[str], cwd: Path) -> tuple[float, int]:
    """Wall seconds and exit code of one whole process, run in the scene copies' folder (Mitsuba 0.6
    writes its log file into the working directory)."""
    t0 = time.perf_counter()
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=cwd).returncode
    return time.perf_counter() - t0, rc


# ---------------------------------------------------------------- images

def read_pfm(path: Path) -> np.ndarray:
    """Portable float map (Debevec's PFM: "PF" header, width height, scale whose sign is the byte
    order, bottom-to-top rows)."""
    data = path.read_bytes()
    m = re.match(rb"(P[Ff])\s+(\d+)\s+(\d+)\s+(\S+)\s", data[:128])
    if not m:
        raise ValueError(f"{path}: not a PFM file")
    channels = 3 if m.group(1) == b"PF" else 1
    w, h, scale = int(m.group(2)), int(m.group(3)), float(m.group(4))
    raw = data[m.end():]
    arr = np.frombuffer(raw, dtype="<f4" if scale < 0 else ">f4", count=w * h * channels)
    arr = arr.reshape(h, w, channels)[::-1]
    return np.repeat(arr, 3, axis=2) if channels == 1 else arr


def luminance(path: Path) -> np.ndarray:
    """Rec.709 luminance of an output: iris's EXR (R, G, B channels) or a PFM."""
    if path.suffix == ".pfm":
        rgb = read_pfm(path)
    else:
        pixels, names, _ = read_exr(str(path))
        rgb = np.stack([pixels[..., names.index(c)] for c in ("R", "G", "B")], axis=-1)
    return np.asarray(rgb, dtype=np.float64) @ REC709_Y


def output_file(name: str, out: Path, scene: str) -> Path:
    return out / f"{scene}.pfm" if name == "tungsten" else out


def relmse(img: np.ndarray, ref: np.ndarray) -> float:
    """relMSE = mean (x − r)² / (r² + 0.01) (the ε keeps black pixels finite)."""
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2)))


# ---------------------------------------------------------------- part 1: side by side

def renderers(args) -> dict[str, str]:
    """The renderers to run, as absolute paths: they run in the scratch folder of the scene copies,
    where a path relative to the caller's folder would name nothing."""
    found = {v: os.path.abspath(args.iris) for v in IRIS_VARIANTS}
    for name, rel in PEER_LAYOUT.items():
        exe = getattr(args, name.replace("-", "_")) or (str(Path(args.peers_bin) / rel) if args.peers_bin else None)
        if exe and os.access(exe, os.X_OK):
            found[name] = os.path.abspath(exe)
        else:
            print(f"peers: {PEER_LABEL[name]} not given or not executable ({exe}): skipped", file=sys.stderr)
    return found


def prepare(args, scene: str, work: Path, **edits) -> dict[str, Path]:
    """Scene copies for one configuration in the work folder: the Mitsuba XML (iris), the same with
    PFM output (Mitsuba 0.6) and the Tungsten JSON, file references made absolute (relocate)."""
    sdir = Path(args.scenes)
    tag = "_".join(f"{k}{v}" for k, v in sorted(edits.items()) if v) or "asis"
    files = {"xml": work / f"{scene}_{tag}.xml", "json": work / f"{scene}_{tag}.json",
             "mts_xml": work / f"{scene}_{tag}_mts.xml"}
    xml = scene_text(sdir / "mitsuba" / f"{scene}.xml", **edits)
    files["xml"].write_text(xml)
    files["mts_xml"].write_text(re.sub(r'(<film type="hdrfilm">)', r'\1<string name="fileFormat" value="pfm"/>', xml))
    files["json"].write_text(scene_text(sdir / "tungsten" / f"{scene}.json", **edits))
    for key, sub in (("xml", "mitsuba"), ("mts_xml", "mitsuba"), ("json", "tungsten")):
        relocate(files[key], sdir / sub, Path(args.meshes))
    return files


def relocate(path: Path, base: Path, meshes: Path):
    """Make a copy's file references absolute: `../meshes/NAME` goes to the meshes folder (the peer
    folder's `meshes` link points at ../shared/data/meshes), anything else is taken relative to the
    original scene's folder."""
    def absolute(ref: str) -> str:
        if ref.startswith("/"):
            return ref
        if ref.startswith("../meshes/"):
            return str((meshes / ref[len("../meshes/"):]).resolve())
        return str((base / ref).resolve())
    s = path.read_text()
    s = re.sub(r'(name="filename" value=")([^"]+)"', lambda m: m.group(1) + absolute(m.group(2)) + '"', s)
    s = re.sub(r'("file"\s*:\s*")([^"]+)"', lambda m: m.group(1) + absolute(m.group(2)) + '"', s)
    path.write_text(s)


def scene_for(name: str, files: dict[str, Path]) -> Path:
    return files["json"] if name == "tungsten" else files["mts_xml"] if name.startswith("mts") else files["xml"]


def out_for(name: str, scene: str, work: Path, tag: str) -> Path:
    if name == "tungsten":
        d = work / f"{name}_{scene}_{tag}"
        d.mkdir(exist_ok=True)
        return d
    return work / f"{name}_{scene}_{tag}.{'pfm' if name.startswith('mts') else 'exr'}"


def side_by_side(args, found, work: Path) -> dict:
    results = {}
    for scene in args.scenes_list:
        files = prepare(args, scene, work)
        names = list(found)
        cmds = {n: command(n, found[n], scene_for(n, files), out_for(n, scene, work, "t"), args.threads) for n in names}
        for n in names:  # warm-up
            run_wall(cmds[n], work)
        times = {n: [] for n in names}
        codes = {n: [] for n in names}
        for r in range(args.rounds):
            for k in range(len(names)):
                n = names[(k + r) % len(names)]
                sec, rc = run_wall(cmds[n], work)
                times[n].append(sec)
                codes[n].append(rc)
            print(f"peers: {scene} round {r + 1}/{args.rounds}: " +
                  ", ".join(f"{n} {times[n][-1]:.2f}s" for n in names), file=sys.stderr)
        lum = {}
        for n in names:
            f = output_file(n, out_for(n, scene, work, "t"), scene)
            lum[n] = float(np.mean(luminance(f))) if f.exists() else None
        results[scene] = {"times": times, "exit_codes": codes, "mean_luminance": lum}
    return results


def ratio_stats(a: list[float], b: list[float]) -> dict:
    rs = [x / y for x, y in zip(a, b)]
    return {"median": statistics.median(rs), "min": min(rs), "max": max(rs)}


# ---------------------------------------------------------------- part 2: equal time

def equal_time_run(args, name, exe, scene, spp, work, reference):
    """One run of part 2: (wall seconds, exit code, luminance image). The reference is drawn from a
    sample stream independent of the runs': iris and Tungsten with another seed; Mitsuba 0.6, which
    has no seed parameter, with the `independent` sampler instead of `stratified`."""
    mts_sampler = ("independent" if reference else "stratified") if name.startswith("mts") else None
    iris = EQUAL_TIME_IRIS.get(name)
    files = prepare(args, scene, work, width=args.et_width, height=args.et_height, spp=spp, sampler=mts_sampler,
                    integrator=iris[1] if iris else None)
    seed = "7" if reference else "1"
    extra = ["--sampler", iris[2], "--seed", seed] if iris else ["--seed", seed] if name == "tungsten" else []
    out = out_for(name, scene, work, f"et{spp}")
    sec, rc = run_wall(command(name, exe, scene_for(name, files), out, args.threads, extra), work)
    return sec, rc, luminance(output_file(name, out, scene))


def equal_time(args, found, work: Path) -> dict:
    """Part 2: per scene and renderer, the reference, then the sample counts of --et-spp."""
    res = {}
    names = [*EQUAL_TIME_IRIS, *(n for n in found if not n.startswith("iris"))]
    found = {**found, **{n: args.iris for n in EQUAL_TIME_IRIS}}
    for scene in args.scenes_list:
        res[scene] = {}
        for n in names:
            sec, rc, ref = equal_time_run(args, n, found[n], scene, args.ref_spp, work, reference=True)
            rows = []
            res[scene][n] = {"reference_spp": args.ref_spp, "reference_seconds": sec, "reference_exit": rc,
                             "rows": rows}
            for spp in args.spp_list:
                sec, rc, lum = equal_time_run(args, n, found[n], scene, spp, work, reference=False)
                rows.append({"spp": spp, "seconds": sec, "relmse": relmse(lum, ref), "exit": rc})
                print(f"peers: equal time {scene} {n} {spp} spp {sec:.2f}s relMSE {rows[-1]['relmse']:.4g}",
                      file=sys.stderr)
    return res


def relmse_at(rows: list[dict], budget: float) -> float | None:
    """relMSE at a wall-time budget, log-log interpolated between the two measured runs around it."""
    pts = sorted((r["seconds"], r["relmse"]) for r in rows if r["relmse"] > 0)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= budget <= t1 and t1 > t0:
            w = (math.log(budget) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return math.exp((1 - w) * math.log(e0) + w * math.log(e1))
    return None


# ---------------------------------------------------------------- report

def loadavg() -> str:
    try:
        return "/".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "unknown"


def timing_section(sbs: dict, found: dict) -> list[str]:
    lines = ["## Side by side: whole-process wall time", "",
             "Median over rounds of the per-round ratio iris ÷ peer (min–max over rounds in brackets).", ""]
    peers = [p for p in PEER_LAYOUT if p in found]
    rows = []
    for scene, r in sbs.items():
        for v in IRIS_VARIANTS:
            row = {"scene": scene, "iris": v}
            for p in peers:
                s = ratio_stats(r["times"][v], r["times"][p])
                row[p] = f"{s['median']:.2f} ({s['min']:.2f}–{s['max']:.2f})"
            rows.append(row)
    lines.append(markdown_table(rows, ["scene", "iris", *peers],
                                ["scene", "iris variant", *[f"÷ {PEER_LABEL[p]}" for p in peers]]))
    lines += ["", "Median wall seconds (min–max), and mean Rec.709 luminance of the last output:", ""]
    rows = []
    for scene, r in sbs.items():
        for n, ts in r["times"].items():
            bad = any(c != 0 for c in r["exit_codes"][n])
            lum = r["mean_luminance"][n]
            rows.append({"scene": scene, "renderer": n, "wall": f"{statistics.median(ts):.2f} ({min(ts):.2f}–{max(ts):.2f})"
                         + (" NONZERO EXIT" if bad else ""), "Y": f"{lum:.4f}" if lum is not None else "—"})
    lines.append(markdown_table(rows, ["scene", "renderer", "wall", "Y"], ["scene", "renderer", "wall s", "mean Y"]))
    return lines


def lowest_error_line(per: dict, budgets: list[float]) -> str:
    """The renderer with the lowest relMSE at each budget where every renderer was measured; a budget
    outside some renderer's measured range names none (a renderer without a value there is not
    beaten, only not measured)."""
    best, partial = [], []
    for b in budgets:
        vals = {n: relmse_at(v["rows"], b) for n, v in per.items()}
        if all(e is not None for e in vals.values()):
            best.append(f"{b:g}s: {min(vals, key=vals.get)}")
        else:
            partial.append(f"{b:g}s")
    line = "Lowest error per budget: " + (", ".join(best) if best else "none measured by every renderer")
    if partial:
        line += f" (not named at {', '.join(partial)}: not every renderer has a value there)"
    return line + "."


def budgets_of(per: dict) -> list[float]:
    """The wall-time budgets of one scene's equal-time table: powers of two within the range of
    all its renderers' measured runs."""
    times = sorted(r["seconds"] for v in per.values() for r in v["rows"])
    return [2.0 ** k for k in range(-3, 8) if times and times[0] <= 2.0 ** k <= times[-1]]


def iris_against_peers(per: dict, budgets: list[float]) -> list[dict]:
    """Issue 37's question at each budget: is iris's lowest relMSE (over its variants) below every
    peer's? A renderer whose first run took longer than the budget has no image by then (a peer is
    beaten, an iris variant left out); a budget beyond any renderer's longest run, or where no iris
    variant has a value, is undecided."""
    verdicts = []
    for b in budgets:
        iris, peers, beaten, unmeasured = {}, {}, [], []
        for n, v in per.items():
            e = relmse_at(v["rows"], b)
            times = [r["seconds"] for r in v["rows"]]
            if e is not None:
                (iris if n.startswith("iris") else peers)[n] = e
            elif times and b < min(times):
                beaten.append(n)  # no image within the budget
            else:
                unmeasured.append(n)  # its longest run ended before the budget: it might do better
        v = {"budget": b, "no_image_yet": beaten, "not_measured": unmeasured}
        if iris:
            v["iris"] = min(iris, key=iris.get)
            v["iris_relmse"] = iris[v["iris"]]
        if peers:
            v["peer"] = min(peers, key=peers.get)
            v["peer_relmse"] = peers[v["peer"]]
        v["decided"] = bool(iris) and not unmeasured
        v["iris_lowest"] = v["decided"] and (not peers or v["iris_relmse"] < v["peer_relmse"])
        verdicts.append(v)
    return verdicts


def iris_against_peers_line(verdicts: list[dict]) -> str:
    parts = []
    for v in verdicts:
        b = f"{v['budget']:g}s"
        if not v["decided"]:
            why = f"{', '.join(v['not_measured'])} not measured" if v["not_measured"] else "no iris value"
            parts.append(f"{b}: undecided ({why})")
            continue
        iris = f"{v['iris']} {v['iris_relmse']:.4g}"
        peer = f"{v['peer']} {v['peer_relmse']:.4g}" if "peer" in v else "no peer image yet"
        parts.append(f"{b}: {'**iris**' if v['iris_lowest'] else v['peer']} ({iris} vs {peer})")
    return "iris (its best variant) against the best peer: " + "; ".join(parts) + "."


def equal_time_section(et: dict, args) -> list[str]:
    lines = ["", "## Equal time: relMSE of each renderer's best sampler against its own long reference", "",
             f"{args.et_width}×{args.et_height}, {args.threads} threads, sample counts {args.spp_list}, "
             f"reference {args.ref_spp} spp (another seed for iris). relMSE at a wall-time budget is "
             "interpolated log-log between the runs around it; — where the budget is outside the measured "
             "range. Lower is better.", ""]
    for scene, per in et.items():
        budgets = budgets_of(per)
        rows = []
        for n, v in per.items():
            row = {"renderer": n}
            for b in budgets:
                e = relmse_at(v["rows"], b)
                row[f"{b:g}s"] = f"{e:.4g}" if e is not None else "—"
            rows.append(row)
        lines += [f"### {scene}", "", markdown_table(rows, ["renderer", *[f"{b:g}s" for b in budgets]]), ""]
        lines.append(lowest_error_line(per, budgets))
        lines.append("")
        lines.append(iris_against_peers_line(iris_against_peers(per, budgets)))
        lines.append("")
    return lines


def write(args, found, sbs, et, prov, started, load_before, load_after):
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    m = machine_info(prov)
    lines = ["# iris against peer renderers (issue 37)", "",
             f"Generated by `experiments/perf/peers.py` ({' '.join(sys.argv[1:])}); every number below was "
             "measured in this run.", "",
             f"- source: {prov['text']}",
             f"- machine: {m['cpu']}, {m['nproc']} logical CPUs, {m['uname']}",
             f"- started {started} UTC; load average (1/5/15 min) before {load_before}, after {load_after}",
             "- renderers: " + ", ".join(f"{n} = `{e}`" for n, e in found.items()),
             "- builds: Mitsuba 0.6 is compiled for SSE2/3 and Tungsten's bundled Embree for SSE4.2, while iris "
             "links Debian's Embree, which picks AVX2 at run time (../shared/peers/README.md).", ""]
    if sbs:
        lines += timing_section(sbs, found)
    if et:
        lines += equal_time_section(et, args)
    (out / "peers.md").write_text("\n".join(lines) + "\n")
    (out / "peers.json").write_text(json.dumps({"provenance": prov, "renderers": found, "side_by_side": sbs,
                                                "equal_time": et}, indent=1))
    print(f"peers: wrote {out / 'peers.md'}", file=sys.stderr)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--iris", default=str(Path(REPO) / "build" / "render"))
    ap.add_argument("--mitsuba-rgb", dest="mts_rgb", help="Mitsuba 0.6 RGB `mitsuba` executable")
    ap.add_argument("--mitsuba-spectral", dest="mts_s16", help="Mitsuba 0.6 spectral `mitsuba` executable")
    ap.add_argument("--tungsten", help="Tungsten `tungsten` executable")
    ap.add_argument("--peers-bin", help="folder laid out as ../shared/peers/bin: fills the peers not given")
    ap.add_argument("--scenes", default=str(Path(REPO).parent / "shared" / "peers" / "scenes"))
    ap.add_argument("--meshes", default=str(Path(REPO).parent / "shared" / "data" / "meshes"),
                    help="folder of the meshes the peer scenes name as ../meshes/ (default ../shared/data/meshes)")
    ap.add_argument("--scene-list", default="bunny,dragon,spheres")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--no-timing", action="store_true", help="skip part 1")
    ap.add_argument("--equal-time", action="store_true", help="run part 2")
    ap.add_argument("--et-size", default="160x120")
    ap.add_argument("--et-spp", default="4,16,64,256,512")
    ap.add_argument("--ref-spp", type=int, default=2048)
    ap.add_argument("--out", default=str(HERE / "results" / "peers"))
    args = ap.parse_args(argv)
    args.scenes_list = [s for s in args.scene_list.split(",") if s]
    args.et_width, args.et_height = (int(x) for x in args.et_size.split("x"))
    args.spp_list = [int(x) for x in args.et_spp.split(",")]
    # run.py's other targets write experiments/perf/results before this part runs: outputs, not source
    prov = provenance(("experiments/results", "experiments/perf/results"))
    started = time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())
    load_before = loadavg()
    found = renderers(args)
    with tempfile.TemporaryDirectory(prefix="iris_peers_") as tmp:
        work = Path(tmp)
        sbs = {} if args.no_timing else side_by_side(args, found, work)
        et = equal_time(args, found, work) if args.equal_time else {}
    write(args, found, sbs, et, prov, started, load_before, loadavg())


if __name__ == "__main__":
    main()
