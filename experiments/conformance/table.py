#!/usr/bin/env python3
"""The conformance table (scene, mode, p-min, threshold, verdict, Mitsuba's own test, mean ratios)
of a run of experiments/conformance/run.py, printed from its results.json (no numpy needed:
docs/conformance.md embeds it through tests/architecture/doc_tables.py); with --diagnosis, the
table of the failing renders compared at their failing block with both of Mitsuba's references.

    python3 experiments/conformance/table.py experiments/results/conformance/results.json
    python3 experiments/conformance/table.py --diagnosis experiments/results/conformance/results.json
    python3 experiments/conformance/table.py --polarized-diagnosis experiments/results/conformance/results.json
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
              "at": scale(r), "verdict": short_verdict(r["verdict"]), "Mitsuba's test": r.get("mitsuba_ztest", ""),
              "X ratio": f"{r['ratio_X']:.4f}" if "ratio_X" in r else "", "Y ratio": f"{r['ratio_Y']:.4f}" if "ratio_Y" in r else "",
              "Z ratio": f"{r['ratio_Z']:.4f}" if "ratio_Z" in r else ""} for r in rows]
    cols = ["scene", "mode", "p-min", "threshold", "at", "verdict", "Mitsuba's test", "X ratio", "Y ratio", "Z ratio"]
    return markdown_table(cells, cols)


def cell(d, key, channel):
    """Ratio and Welch t of one comparison of a diagnosis, in one XYZ channel."""
    c = "XYZ".index(channel)
    return f"{d[key]['ratio'][c]:.5f} (t {d[key]['t'][c]:+.1f})"


def failing_block(d) -> str:
    """Where a diagnosis looked: the whole image, a pixel or a block of the failing scale."""
    if d["scale"] == 0:
        return "image"
    if d["scale"] == 1:
        return f"pixel ({d['block_x']}, {d['block_y']})"
    return f"{d['scale']}x{d['scale']} block ({d['block_x']}, {d['block_y']})"


def diagnosis_table(rows) -> str:
    """One line per failing render: at its failing block and channel, t and ratio of iris against
    Mitsuba's reference of the same variant, of Mitsuba's spectral reference against its RGB one,
    of iris's spectral render against its RGB one, and of iris against Mitsuba's reference of the
    other variant."""
    cells = []
    for r in rows:
        d = r.get("diagnosis")
        if not d or "mitsuba_spectral_vs_rgb" not in d:
            continue
        where = failing_block(d)
        cells.append({"scene": r["scene"].removeprefix("test_"), "mode": r["mode"], "where": f"{where}, {d['channel']}",
                      "iris / Mitsuba same variant": cell(d, "iris_vs_same", d["channel"]),
                      "Mitsuba spectral / Mitsuba RGB": cell(d, "mitsuba_spectral_vs_rgb", d["channel"]),
                      "iris spectral / iris RGB": cell(d, "iris_spectral_vs_rgb", d["channel"]),
                      "iris / Mitsuba other variant": cell(d, "iris_vs_other", d["channel"])})
    return markdown_table(cells, ["scene", "mode", "where", "iris / Mitsuba same variant",
                                  "Mitsuba spectral / Mitsuba RGB", "iris spectral / iris RGB", "iris / Mitsuba other variant"])


def polarized_diagnosis_table(rows) -> str:
    """The same for failing polarized renders, whose other variant is Mitsuba's spectral one: t and
    ratio of iris against the polarized reference, of Mitsuba's polarized reference against its
    spectral one, of iris's polarized render against its spectral one, and of iris against
    Mitsuba's spectral reference."""
    cells = []
    for r in rows:
        d = r.get("diagnosis")
        if not d or "mitsuba_polarized_vs_spectral" not in d:
            continue
        where = failing_block(d)
        cells.append({"scene": r["scene"].removeprefix("test_"), "where": f"{where}, {d['channel']}",
                      "iris / Mitsuba polarized": cell(d, "iris_vs_same", d["channel"]),
                      "Mitsuba polarized / Mitsuba spectral": cell(d, "mitsuba_polarized_vs_spectral", d["channel"]),
                      "iris polarized / iris spectral": cell(d, "iris_polarized_vs_spectral", d["channel"]),
                      "iris / Mitsuba spectral": cell(d, "iris_vs_other", d["channel"])})
    return markdown_table(cells, ["scene", "where", "iris / Mitsuba polarized", "Mitsuba polarized / Mitsuba spectral",
                                  "iris polarized / iris spectral", "iris / Mitsuba spectral"])


if __name__ == "__main__":
    args = sys.argv[1:]
    kind = args[0] if args[:1] in (["--diagnosis"], ["--polarized-diagnosis"]) else ""
    args = args[1:] if kind else args
    if len(args) != 1:
        sys.exit(f"usage: {sys.argv[0]} [--diagnosis | --polarized-diagnosis] results.json")
    rows = json.loads(Path(args[0]).read_text())["rows"]
    print({"--diagnosis": diagnosis_table, "--polarized-diagnosis": polarized_diagnosis_table}.get(kind, table)(rows))
