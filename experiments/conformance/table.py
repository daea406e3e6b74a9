#!/usr/bin/env python3
"""The conformance table (scene, mode, p-min, threshold, verdict, mean ratios) of a run of
experiments/conformance/run.py, printed from its results.json (no numpy needed: docs/conformance.md
embeds it through tests/architecture/doc_tables.py).

    python3 experiments/conformance/table.py experiments/results/conformance/results.json
"""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from iris_experiments.report import markdown_table  # noqa: E402


def short_verdict(verdict: str) -> str:
    """The verdict with scene paths relative to the scene folder (the table is machine-independent)."""
    verdict = re.sub(r"\S*/bsdf_spheres/", "", verdict)
    verdict = re.sub(r" \((supported|known parameters): [^)]*\)", "", verdict)   # the lists are in results.json
    return verdict.replace("|", "\\|")


def table(rows) -> str:
    def scale(r):
        return "" if "scale" not in r else ("image" if r["scale"] == 0 else f"{r['scale']}x{r['scale']}")
    cells = [{"scene": r["scene"].removeprefix("test_"), "mode": r["mode"],
              "p-min": f"{r['p_min']:.3g}" if "p_min" in r else "", "threshold": f"{r['threshold']:.3g}" if "threshold" in r else "",
              "at": scale(r), "verdict": short_verdict(r["verdict"]),
              "X ratio": f"{r['ratio_X']:.4f}" if "ratio_X" in r else "", "Y ratio": f"{r['ratio_Y']:.4f}" if "ratio_Y" in r else "",
              "Z ratio": f"{r['ratio_Z']:.4f}" if "ratio_Z" in r else ""} for r in rows]
    cols = ["scene", "mode", "p-min", "threshold", "at", "verdict", "X ratio", "Y ratio", "Z ratio"]
    return markdown_table(cells, cols)



if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(f"usage: {sys.argv[0]} results.json")
    print(table(json.loads(Path(sys.argv[1]).read_text())["rows"]))
