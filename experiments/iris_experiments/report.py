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


def git_revision() -> str:
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True, text=True,
                             timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=REPO,
                               capture_output=True, text=True, timeout=10).stdout.strip()
        return rev + (" (with uncommitted changes)" if dirty else "") if rev else "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def machine_info() -> dict:
    u = platform.uname()
    return {
        "uname": f"{u.system} {u.node} {u.release} {u.version} {u.machine}",
        "nproc": os.cpu_count(),
        "cpu": cpu_model(),
        "python": platform.python_version(),
        "git": git_revision(),
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
