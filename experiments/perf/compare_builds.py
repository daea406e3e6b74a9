#!/usr/bin/python3
"""Compare two builds of iris (e.g. a change and the commit it started from): the rendered images
must be the same, and the instructions executed per sample (callgrind) must not grow.

    /usr/bin/python3 experiments/perf/compare_builds.py --base BUILD_A --new BUILD_B
        [--out experiments/perf/results/compare_builds.md] [--no-images] [--no-instructions] [--quick]

Images: every scene of IMAGE_RUNS rendered by both builds' `render` in RGB mode and spectral N = 8
(seed 0, fixed spp), compared pixel by pixel (oiiotool --dumpdata): MSE and the largest relative
difference |a − b| / max(|a|, |b|). Instructions: the callgrind measurements of
experiments/perf/run.py (targets 2 and 3: `valgrind --tool=callgrind`, whole process, 64×64, the
difference of two spp counts), for both builds, with the change in per cent. The report names the
commit of each build's source tree. Exit status 1 when an image differs by more than TOLERANCE or
an instruction count grows by more than 2 %.
"""
import argparse
import concurrent.futures
import datetime
import json
import threading
import os
import re
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PERF = os.path.join("experiments", "perf", "scenes")

# (scene relative to the source tree, defines, spp) rendered at 64×64 by each build.
IMAGE_RUNS = [
    ("scenes/thinfilm_spheres.xml", ["res=64"], 4),
    ("scenes/thesis_proposed_table42.xml", [], 2),
    ("scenes/thesis_granier_table31.xml", [], 2),
    (f"{PERF}/lane_materials.xml", [], 4),
    (f"{PERF}/thesis_pair.xml", ["res=48", "material=proposed", "integrator=path"], 2),
    (f"{PERF}/thesis_pair.xml", ["res=48", "material=granier", "integrator=path"], 2),
]
IMAGE_MODES = ["rgb", 8]
# Largest relative pixel difference accepted: the batched Airy kernel's documented agreement with
# the scalar kernel (docs/thin_film.md §8); bit-identical builds give 0.
TOLERANCE = 1e-14
MAX_GROWTH = 0.02

# The callgrind runs of experiments/perf/run.py: (label, scene, defines, spp_lo, spp_hi, mode).
INSTRUCTION_RUNS = [(f"thin film, {m}", "scenes/thinfilm_spheres.xml", ["res=64"], 1, 3, m)
                    for m in ["rgb", 4, 16, 32]] + [
    (f"dragon {mat} {integ}, {m}", f"{PERF}/thesis_pair.xml", ["res=64", f"material={mat}", f"integrator={integ}"],
     2, 6, m)
    for integ in ["direct", "path"] for m in ["rgb", 4] for mat in ["granier", "proposed"]]


def source_dir(build):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            if line.startswith("CMAKE_HOME_DIRECTORY:"):
                return line.split("=", 1)[1].strip()
    sys.exit(f"compare_builds.py: {build} has no CMakeCache.txt")


def commit_of(src):
    head = subprocess.run(["git", "-C", src, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", src, "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    return head + (" (with uncommitted changes)" if dirty else "")


def render_cmd(build, src, scene, out, spp, mode, defines, threads):
    # The scenes of this checkout for both builds (a scene added with the change exists only here).
    cmd = [os.path.join(build, "render"), os.path.join(REPO, scene), "--quiet", "--no-png", "-o", out,
           "--threads", str(threads), "--spp", str(spp), "--seed", "0"]
    cmd += ["--mode", "rgb"] if mode == "rgb" else ["--spectral-samples", str(mode)]
    for d in defines:
        cmd += ["-D", d]
    return cmd


def run(cmd, env):
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError(f"command failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-2000:]}")
    return p


def pixels(path):
    out = subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True, check=True).stdout
    vals = []
    for line in out.splitlines():
        m = re.match(r"\s*Pixel \(\d+, \d+\):\s*(.*)", line)
        if m:
            vals += [float(v) for v in m.group(1).split()]
    return vals


def compare_images(a, b):
    pa, pb = pixels(a), pixels(b)
    if len(pa) != len(pb) or not pa:
        return float("inf"), float("inf")
    mse = sum((x - y) ** 2 for x, y in zip(pa, pb)) / len(pa)
    rel = max((abs(x - y) / max(abs(x), abs(y)) if x != y else 0.0) for x, y in zip(pa, pb))
    return mse, rel


class Counts:
    """Instruction counts, optionally kept in a JSON file across runs (--cache), keyed by the
    executable, its modification time and the command line without the output path: a build that
    did not change is not measured again."""

    def __init__(self, path):
        self.path, self.lock = path, threading.Lock()
        self.data = json.load(open(path)) if path and os.path.exists(path) else {}

    def measure(self, cmd, env, tmp, key):
        exe = cmd[0]
        args = [a for i, a in enumerate(cmd) if i == 0 or (cmd[i - 1] != "-o" and a != "-o")]
        ckey = f"{exe}|{os.path.getmtime(exe)}|{' '.join(args[1:])}"
        with self.lock:
            if ckey in self.data:
                return self.data[ckey]
        out = os.path.join(tmp, f"callgrind_{key}.out")
        p = run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] + cmd, env)
        n = int(re.search(r"Collected\s*:\s*(\d+)", p.stderr).group(1))
        with self.lock:
            self.data[ckey] = n
            if self.path:
                with open(self.path, "w") as f:
                    json.dump(self.data, f, indent=0)
        return n


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", required=True, help="build directory of the reference")
    ap.add_argument("--new", required=True, help="build directory of the change")
    ap.add_argument("--out", default=os.path.join(REPO, "experiments", "perf", "results", "compare_builds.md"))
    ap.add_argument("--no-images", action="store_true")
    ap.add_argument("--no-instructions", action="store_true")
    ap.add_argument("--quick", action="store_true", help="instructions of the thin-film scene only")
    ap.add_argument("--only", help="instruction runs whose label matches this regular expression")
    ap.add_argument("--cache", help="JSON file of instruction counts kept across runs")
    ap.add_argument("--jobs", type=int, default=2, help="callgrind runs at once (counts do not depend on it)")
    args = ap.parse_args()
    builds = {"base": os.path.abspath(args.base), "new": os.path.abspath(args.new)}
    srcs = {k: source_dir(b) for k, b in builds.items()}
    tmp = tempfile.mkdtemp(prefix="iris_compare_")
    env = dict(os.environ, IRIS_CACHE_DIR=os.path.join(tmp, "cache"))
    started = datetime.datetime.utcnow().isoformat(timespec="seconds") + "Z"
    ok = True
    L = ["# Two builds compared: images and instructions per sample", "",
         "Generated by `experiments/perf/compare_builds.py`; every number below is measured in this run.", "",
         "| | |", "|---|---|",
         f"| base | `{builds['base']}`, source commit `{commit_of(srcs['base'])}` |",
         f"| new | `{builds['new']}`, source commit `{commit_of(srcs['new'])}` |",
         f"| started (UTC) | {started} |", ""]
    if not args.no_images:
        L += ["## Images (seed 0; 64×64 unless the scene sets its size)", "",
              f"Accepted: max relative difference ≤ {TOLERANCE:g} (0 for bit-identical builds).", "",
              "| scene | defines | spp | mode | MSE | max relative difference |", "|---|---|---|---|---|---|"]
        for scene, defines, spp in IMAGE_RUNS:
            for mode in IMAGE_MODES:
                paths = {}
                for k in builds:
                    paths[k] = os.path.join(tmp, f"{k}.exr")
                    run(render_cmd(builds[k], srcs[k], scene, paths[k], spp, mode, defines, 2), env)
                mse, rel = compare_images(paths["new"], paths["base"])
                ok &= rel <= TOLERANCE
                label = "RGB" if mode == "rgb" else f"N={mode}"
                L.append(f"| `{scene}` | {' '.join(defines) or '—'} | {spp} | {label} | {mse:.3g} | {rel:.3g} |")
                print(L[-1], flush=True)
        L.append("")
    if not args.no_instructions:
        # Fill the rough-plastic table cache (both distributions) outside valgrind.
        run(render_cmd(builds["base"], srcs["base"], f"{PERF}/lane_materials.xml", os.path.join(tmp, "w.exr"), 1,
                       "rgb", ["res=8"], 2), env)
        L += ["## Instructions per sample (callgrind, whole process, 1 thread, spp difference)", "",
              f"The runs of experiments/perf/run.py targets 2 and 3. Accepted: growth ≤ {100 * MAX_GROWTH:g} %.", "",
              "| run | spp | base | new | change |", "|---|---|---|---|---|"]
        runs = INSTRUCTION_RUNS[:4] if args.quick else INSTRUCTION_RUNS
        if args.only:
            runs = [r for r in runs if re.search(args.only, r[0])]
        counts = Counts(args.cache)
        tasks = {}
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            for r, (label, scene, defines, lo, hi, mode) in enumerate(runs):
                for k in builds:
                    for spp in (lo, hi):
                        key = f"{r}_{k}_{spp}"
                        cmd = render_cmd(builds[k], srcs[k], scene, os.path.join(tmp, f"{key}.exr"), spp, mode,
                                         defines, 1)
                        tasks[(r, k, spp)] = pool.submit(counts.measure, cmd, env, tmp, key)
            for r, (label, scene, defines, lo, hi, mode) in enumerate(runs):
                per = {k: (tasks[(r, k, hi)].result() - tasks[(r, k, lo)].result()) / (hi - lo) for k in builds}
                change = per["new"] / per["base"] - 1
                ok &= change <= MAX_GROWTH
                L.append(f"| {label} | {hi} − {lo} | {per['base']:,.0f} | {per['new']:,.0f} | {100 * change:+.2f} % |")
                print(L[-1], flush=True)
        L.append("")
    L.append(f"Finished {datetime.datetime.utcnow().isoformat(timespec='seconds')}Z; "
             f"result: {'accepted' if ok else '**not accepted**'}.")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        f.write("\n".join(L) + "\n")
    print(f"wrote {args.out}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
