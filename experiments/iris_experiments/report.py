"""Markdown reports: machine, settings, result tables and conclusions computed from the data."""
from __future__ import annotations

import datetime
import math
import os
import platform
import subprocess
from pathlib import Path

from .tools import REPO


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _git(*args) -> str:
    return subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True, timeout=10).stdout.strip()


def provenance(results_dirs: tuple = ("experiments/results",)) -> dict:
    """Which commit the results come from. A working tree with uncommitted or untracked changes
    (outside `results_dirs`, where the results themselves are written) is not a commit: then no
    commit is named. {"state": "clean" | "dirty" | "unknown", "commit": hash or None, "text"}."""
    try:
        rev = _git("rev-parse", "HEAD")
        changes = _git("status", "--porcelain", "--", ".", *(f":(exclude){d}" for d in results_dirs))
    except (OSError, subprocess.SubprocessError):
        rev, changes = "", ""
    if not rev:
        return {"state": "unknown", "commit": None, "text": "not made from a git checkout: no commit to name"}
    if changes:
        n = len(changes.splitlines())
        return {"state": "dirty", "commit": None,
                "text": f"made from a working tree with {n} uncommitted or untracked change(s): these results are "
                        "not the results of any commit and cannot be reproduced from one"}
    return {"state": "clean", "commit": rev, "text": f"commit {rev} (clean working tree)"}


def machine_info(prov: dict | None = None) -> dict:
    u = platform.uname()
    return {
        "uname": f"{u.system} {u.node} {u.release} {u.version} {u.machine}",
        "nproc": os.cpu_count(),
        "cpu": cpu_model(),
        "python": platform.python_version(),
        "git": (prov or provenance())["text"],
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S"),
    }


def fmt(v, digits: int = 4) -> str:
    if isinstance(v, float):
        if math.isinf(v):
            return "inf"
        if math.isnan(v):
            return "nan"
        return f"{v:.{digits}g}"
    return str(v)


def markdown_table(rows, columns, headers=None, digits: int = 4) -> str:
    headers = headers or columns
    out = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in columns) + "|"]
    for r in rows:
        out.append("| " + " | ".join(fmt(r.get(c, ""), digits).replace("|", "\\|") for c in columns) + " |")
    return "\n".join(out)


def write_report(path: Path, *, title: str, question: str, machine: dict, settings: dict, sections,
                 conclusions, figures=(), command: str = "") -> Path:
    """sections: list of (heading, markdown text); conclusions: sentences computed from the data;
    figures: paths (relative to the report) of PNGs to embed."""
    path = Path(path)
    lines = [f"# {title}", "", question, ""]
    if command:
        lines += ["Command:", "", f"    {command}", ""]
    lines += ["## Machine", ""]
    lines += [f"- {k}: {v}" for k, v in machine.items()]
    lines += ["", "## Settings", ""]
    lines += [f"- {k}: {fmt(v) if isinstance(v, float) else v}" for k, v in settings.items()]
    lines += ["", "## Conclusions (computed from the data below)", ""]
    lines += [f"- {c}" for c in conclusions] or ["- (no conclusions: no results)"]
    for heading, text in sections:
        lines += ["", f"## {heading}", "", text]
    for fig in figures:
        lines += ["", f"![{Path(fig).stem}]({fig})"]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path
