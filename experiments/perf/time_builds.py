#!/usr/bin/python3
"""Time two builds of iris against each other on one render, pair by pair: the renders of build A
and build B alternate (A first in odd pairs, B first in even ones, so a drift of the machine's speed
hits both alike), and the figure is the median over pairs of B's render time ÷ A's, with its
quartiles. The time is iris's own (the EXR's iris.render_time_s: the render loop, without scene
loading). Used for a change whose effect is below this shared VM's noise for single runs (a ±15 %
spread is common), e.g. the render loop's scheduling at 2 threads.

    /usr/bin/python3 experiments/perf/time_builds.py --a BUILD_A/render --b BUILD_B/render [--pairs 30]
        -- scenes/default.xml -D res=192 --spp 64 --threads 2

Everything after `--` is passed to both renderers (add --quiet --no-png -o is done here). Prints one
line; timings are never pass/fail.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run import REPO, exr_meta  # noqa: E402


def render_time(exe, args, out):
    subprocess.run([exe, *args, "--quiet", "--no-png", "-o", out], check=True, cwd=REPO, capture_output=True)
    return float(exr_meta(out)["iris.render_time_s"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="the first build's render executable (the base)")
    ap.add_argument("--b", required=True, help="the second build's render executable (the change)")
    ap.add_argument("--pairs", type=int, default=30)
    ap.add_argument("render_args", nargs="+", help="the render's arguments (after --)")
    args = ap.parse_args()
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "t.exr")
        for i in range(args.pairs):
            order = [("a", args.a), ("b", args.b)] if i % 2 == 0 else [("b", args.b), ("a", args.a)]
            t = {name: render_time(exe, args.render_args, out) for name, exe in order}
            ratios.append(t["b"] / t["a"])
    q = statistics.quantiles(ratios, n=4)
    print(f"B/A render time: median {statistics.median(ratios):.4f}, quartiles {q[0]:.3f}-{q[2]:.3f} over "
          f"{args.pairs} pairs (A = {args.a}, B = {args.b}; {' '.join(args.render_args)})")


if __name__ == "__main__":
    main()
