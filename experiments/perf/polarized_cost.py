#!/usr/bin/python3
"""The cost of polarization (issue 34, item 6): render time per sample of polarized mode against
spectral mode with N = 4 wavelengths, on the default scene and the thin-film scene, same seed and
sample count, one thread (less noise from a shared machine). Each configuration is rendered
`--repeats` times alternately and the fastest run counts (the least disturbed by other work); the
figure is iris's own render time (the EXR's iris.render_time_s, without scene loading) divided by
the number of samples. Goal: polarized / spectral ≤ 1.8. Defaults: 9 repeats of 64 spp: with 3 of
32 spp, four runs within minutes on this idle 2-core VM gave ratios from 1.61 to 2.07 for the same
build (the spectral runs of about 0.4 s were the noisy ones).

    /usr/bin/python3 experiments/perf/polarized_cost.py [--build build] [--repeats 9] [--res 128] [--spp 64]
        [--out experiments/perf/results/polarized_cost.md]

Writes a Markdown table naming the commit, the machine and the command; timings are never pass/fail.
"""
import argparse
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = [("default", "scenes/default.xml"), ("thin-film spheres", "scenes/thinfilm_spheres.xml")]
MODES = [("spectral N=4", ["--mode", "spectral", "--spectral-samples", "4"]),
         ("polarized N=4", ["--mode", "polarized", "--spectral-samples", "4"])]


def render_seconds(render, scene, mode_args, res, spp, workdir):
    """iris.render_time_s of one render."""
    out = os.path.join(workdir, "img.exr")
    cmd = [render, os.path.join(REPO, scene), "-o", out, "--no-png", "--quiet", "--threads", "1", "--seed", "1",
           "--spp", str(spp), "-D", f"res={res}"] + mode_args
    subprocess.run(cmd, check=True, capture_output=True)
    info = subprocess.run(["iinfo", "-v", out], capture_output=True, text=True, check=True).stdout
    m = re.search(r'iris\.render_time_s:\s*"?([0-9.eE+-]+)', info)
    if not m:
        raise RuntimeError(f"no iris.render_time_s in {out}")
    return float(m.group(1))


def commit():
    head = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    # experiments/perf/results holds outputs (this table, run.py's report), not source
    dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--untracked-files=no", "--", ".",
                            ":(exclude)experiments/perf/results"], capture_output=True, text=True).stdout.strip()
    return head + (" (with uncommitted changes)" if dirty else "")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--out", help="Markdown report (default: print only)")
    args = ap.parse_args(argv)
    render = os.path.join(args.build, "render")
    samples = args.res * args.res * args.spp
    rows = []
    with tempfile.TemporaryDirectory(prefix="iris_polcost_") as tmp:
        for name, scene in SCENES:
            best = {label: float("inf") for label, _ in MODES}
            for _ in range(args.repeats):
                for label, mode_args in MODES:  # alternating: slow phases of the machine hit both
                    best[label] = min(best[label], render_seconds(render, scene, mode_args, args.res, args.spp, tmp))
            per = {label: 1e6 * best[label] / samples for label in best}
            rows.append((name, scene, per["spectral N=4"], per["polarized N=4"], per["polarized N=4"] / per["spectral N=4"]))
            print(f"{name:18s} spectral {rows[-1][2]:8.2f} us/sample  polarized {rows[-1][3]:8.2f} us/sample  "
                  f"ratio {rows[-1][4]:.2f}", flush=True)
    cmdline = " ".join(["/usr/bin/python3", "experiments/perf/polarized_cost.py"] + (argv if argv is not None else sys.argv[1:]))
    lines = ["# Polarized against spectral N = 4: time per sample", "",
             f"Generated {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC from commit {commit()} on "
             f"{platform.node()} ({os.cpu_count()} cores, shared) by `{cmdline}`.", "",
             f"One thread, {args.res}×{args.res} pixels, {args.spp} spp, seed 1; fastest of {args.repeats} alternating runs; "
             "iris.render_time_s per sample. Goal (issue 34): ratio ≤ 1.8.", "",
             "| scene | spectral N=4 (µs/sample) | polarized N=4 (µs/sample) | ratio |", "| --- | --- | --- | --- |"]
    lines += [f"| {n} (`{s}`) | {a:.2f} | {b:.2f} | {r:.2f} |" for n, s, a, b, r in rows]
    text = "\n".join(lines) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        print(f"report: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
