"""Result collection: image metrics through the `compare` tool, render metadata from the EXR
headers, merging seeds through the `merge` tool, and CSV / JSON writers."""
from __future__ import annotations

import csv
import json
import math
import subprocess
from pathlib import Path

from . import exr
from .errors import ExperimentError
from .sweep import format_value
from .tools import REPO

# EXR metadata keys copied into result rows (written by apps/render.cpp).
METADATA_KEYS = ("iris.spp", "iris.seed", "iris.mode", "iris.spectral_samples", "iris.render_time_s",
                 "iris.rays", "iris.version", "iris.scene")


def compare(compare_tool: Path, test: Path, ref: Path) -> dict:
    """Metrics of `test` against `ref` (compare --json): mse, relmse, psnr, de00_mean, de00_p99, ..."""
    proc = subprocess.run([str(compare_tool), str(test), str(ref), "--json"], cwd=REPO, capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise ExperimentError(proc.stderr.strip() or f"compare failed on {test} vs {ref}")
    out = json.loads(proc.stdout)
    return {k: (math.inf if k == "psnr" and v is None else v) for k, v in out.items()}


def band_errors(compare_tool: Path, test: Path, ref: Path) -> dict:
    """Error per wavelength band of two spectral EXRs (render --spectral-output; channels
    "S0.<nm>nm", Fichet et al. 2021): {wavelength_nm: {"mse", "relmse", "smape"}}, by wavelength."""
    proc = subprocess.run([str(compare_tool), str(test), str(ref), "--json", "--per-channel", "--no-flip"], cwd=REPO,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise ExperimentError(proc.stderr.strip() or f"compare failed on {test} vs {ref}")
    bands = {}
    for ch in json.loads(proc.stdout).get("per_channel", []):
        name = ch["name"]
        if name.startswith("S0.") and name.endswith("nm"):
            nm = float(name[3:-2].replace(",", "."))
            bands[nm] = {k: ch[k] for k in ("mse", "relmse", "smape")}
    if not bands:
        raise ExperimentError(f"{test} and {ref} share no spectral band (S0.<nm>nm channels)")
    return dict(sorted(bands.items()))


def merge(merge_tool: Path, inputs, output: Path) -> Path:
    """Sample-count-weighted merge of renders with different seeds (apps/merge.cpp)."""
    output = Path(output)
    output.parent.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run([str(merge_tool), "-o", str(output), "--quiet", *map(str, inputs)], cwd=REPO,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise ExperimentError(proc.stderr.strip() or f"merge failed for {output}")
    return output


def metadata_row(path: Path) -> dict:
    """The iris.* metadata of one EXR as row fields (spp, seed, ..., render_time_s as float)."""
    meta = exr.read_exr_metadata(str(path))
    row = {}
    for key in METADATA_KEYS:
        if key in meta:
            value = meta[key]
            short = key.split(".", 1)[1]
            try:
                row[short] = int(value) if short in ("spp", "spectral_samples", "rays") else (
                    float(value) if short == "render_time_s" else value)
            except ValueError:
                row[short] = value
    return row


def job_row(job, extra: dict | None = None) -> dict:
    """Row of a job: sweep, scene label, every setting, the EXR metadata, plus `extra`."""
    row = {"sweep": job.sweep, "scene": job.label}
    for k, v in job.settings.items():
        if not k.startswith("_"):
            row[k] = format_value(v) if isinstance(v, (list, tuple)) else v
    row["output"] = str(Path(job.output).relative_to(REPO)) if Path(job.output).is_relative_to(REPO) else str(job.output)
    if Path(job.output).exists():
        for k, v in metadata_row(job.output).items():
            row.setdefault(k, v)
    row.update(extra or {})
    return row


def columns_of(rows) -> list:
    cols = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    return cols


def _cell(v):
    if isinstance(v, float):
        return "inf" if math.isinf(v) else f"{v:.9g}"
    return v


def write_csv(rows, path: Path, columns=None) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    cols = columns or columns_of(rows)
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([_cell(r.get(c, "")) for c in cols])
    return path


def read_csv(path: Path) -> list:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write_json(data, path: Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)

    def clean(x):
        if isinstance(x, float) and not math.isfinite(x):
            return None
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [clean(v) for v in x]
        if isinstance(x, Path):
            return str(x)
        return x

    path.write_text(json.dumps(clean(data), indent=2) + "\n")
    return path
