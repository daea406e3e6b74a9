"""A stand-in for build/render used by the framework tests: same command line, writes an EXR with
the renderer's metadata. Pixel values: 0.5 + offset + Gaussian noise of standard deviation
0.2 / sqrt(spp · wavelengths-per-path) (fixed by --seed), so error falls as samples rise; --sampler
scales that deviation by NOISE_OF_SAMPLER (so sobol's relMSE is a quarter of independent's).
-D fail=1 makes it fail like a broken scene."""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from iris_experiments import exr  # noqa: E402


NOISE_OF_SAMPLER = {"independent": 1.0, "stratified": 0.8, "multijitter": 0.7, "sobol": 0.5, "highdimsobol": 0.4}


def main(argv):
    p = argparse.ArgumentParser()
    p.add_argument("scene")
    p.add_argument("-o", dest="out", required=True)
    p.add_argument("--spp", type=int, default=4)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--mode", default="spectral")
    p.add_argument("--spectral-samples", type=int, default=4)
    p.add_argument("--rgb-wavelengths", default="645,525,445")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--time-limit", type=float, default=0)
    p.add_argument("--sampler", default="independent", choices=sorted(NOISE_OF_SAMPLER))
    p.add_argument("-D", action="append", default=[])
    p.add_argument("--quiet", action="store_true")
    p.add_argument("--no-png", action="store_true")
    a = p.parse_args(argv)
    defines = dict(d.split("=", 1) for d in a.D)
    if defines.get("fail") == "1":
        print(f"{a.scene}:3: error: material 'nothing' is not registered", file=sys.stderr)
        return 1
    res = int(defines.get("res", 16))
    n = a.spectral_samples if a.mode == "spectral" else 3
    rng = np.random.default_rng(a.seed * 1000003 + res)
    offset = float(defines.get("offset", 0.0))
    img = 0.5 + offset + rng.normal(0.0, NOISE_OF_SAMPLER[a.sampler] * 0.2 / np.sqrt(a.spp * n), size=(res, res, 3))
    exr.write_exr(a.out, img.astype(np.float32), metadata={
        "iris.spp": a.spp, "iris.seed": a.seed, "iris.mode": a.mode, "iris.spectral_samples": a.spectral_samples,
        "iris.render_time_s": 0.001 * a.spp * n, "iris.rays": a.spp * n * res * res, "iris.version": "fake",
        "iris.scene": a.scene})
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
