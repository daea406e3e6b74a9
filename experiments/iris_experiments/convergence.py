"""Convergence studies: error against wall time, as rendering papers report it.

A ConvergenceStudy renders every configuration of an experiment (e.g. N wavelengths per path, RGB
mode, a thin-film phase mode) at a geometric series of sample counts with several seeds, and
optionally with an equal wall-time budget (render --spp 0 --time-limit T). Every image is compared
with one converged reference (several seeds merged; its own error is estimated from its two
halves). The analysis fits the convergence slope, finds for each configuration the time to reach a
common error and the error reached at a common time, both against a named baseline, and writes
log-log plots with error bars over seeds. Every sentence of the conclusions is computed from the
numbers (docs/experiments.md, "Convergence studies")."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from .collect import job_row, write_csv, write_json
from .errors import ExperimentError
from .report import fmt, markdown_table
from .sweep import Sweep

# Metrics of `compare --json` that the studies follow, with their labels.
METRICS = {"relmse": "relMSE", "smape": "SMAPE", "flip_hdr_mean": "HDR-FLIP", "de00_mean": "mean ΔE00"}


@dataclass
class ConvergenceStudy:
    configs: dict                 # label -> settings applied together (render options, -D parameters)
    baseline: str                 # the label the speed-ups are measured against
    reference: dict               # settings of the reference renders
    spp_levels: list              # geometric series, e.g. [1, 2, 4, ..., 256]
    seeds: list                   # seeds of every test render (error bars over them)
    ref_spp: int
    ref_seeds: list               # at least 2: the halves estimate the reference's own error
    fixed: dict = field(default_factory=dict)     # settings of every render (scene parameters)
    time_limit: float | None = None               # equal-time renders, seconds (None: none)
    name: str = "convergence"
    metrics: tuple = tuple(METRICS)
    unavailable: dict = field(default_factory=dict)   # label -> why it is left out (set by the experiment)
    # Use the renders of another sweep of the experiment as the reference instead of rendering one:
    # (sweep name, {setting: value} the jobs must have). ref_spp / ref_seeds / reference then
    # describe those renders.
    reuse_reference: tuple | None = None

    def active_configs(self) -> dict:
        return {k: v for k, v in self.configs.items() if k not in self.unavailable}

    def variants(self) -> list:
        return [{"name": k, **v} for k, v in self.active_configs().items()]

    def sweeps(self, scenes: dict, per_scene: dict) -> list:
        if len(self.ref_seeds) < 2:
            raise ValueError("a convergence reference needs at least 2 seeds (its halves estimate its error)")
        out = [] if self.reuse_reference else [
            Sweep(f"{self.name}_reference", scenes, axes={"seed": list(self.ref_seeds)},
                  fixed={**self.fixed, **self.reference, "spp": self.ref_spp}, per_scene=per_scene)]
        out += [
            Sweep(self.name, scenes, axes={"variant": self.variants(), "spp": list(self.spp_levels),
                                           "seed": list(self.seeds)}, fixed=dict(self.fixed), per_scene=per_scene),
        ]
        if self.time_limit:
            out.append(Sweep(f"{self.name}_equal_time", scenes, axes={"variant": self.variants(), "seed": list(self.seeds)},
                             fixed={**self.fixed, "spp": 0, "time_limit": self.time_limit}, per_scene=per_scene))
        return out

    def settings(self) -> dict:
        return {"convergence configurations": list(self.active_configs()),
                "convergence baseline": self.baseline,
                "convergence spp levels": self.spp_levels, "convergence seeds": self.seeds,
                "convergence reference": f"{len(self.ref_seeds)} seeds x {self.ref_spp} spp, {self.reference}, merged",
                "equal-time budget [s]": self.time_limit or "none",
                **({"left out": self.unavailable} if self.unavailable else {})}

    def analyse(self, ctx, label: str) -> "StudyResult":
        return analyse_study(self, ctx, label)


@dataclass
class StudyResult:
    rows: list                 # one per test render
    summary: dict              # per config and metric: slope, time to target, speed-up, error at equal time
    sections: list             # (heading, markdown)
    figures: list
    conclusions: list
    comparison: dict           # for the interactive image comparison of the HTML report


# ---- numbers ----------------------------------------------------------------------------------

def mean_relmse_at_spp(rows, study_name: str, config: str, spp: int) -> float:
    """Mean over seeds of the relMSE of one configuration's fixed-spp renders in a study's rows."""
    return mean_sem([r["relmse"] for r in rows if r.get("config") == config and r.get("spp") == spp
                     and r.get("study") == study_name and not r.get("time_limit")])[0]


def mean_sem(values):
    """Mean and standard error of the mean (0 for one value); NaN for none."""
    v = [x for x in values if x is not None and math.isfinite(x)]
    if not v:
        return math.nan, math.nan
    m = sum(v) / len(v)
    if len(v) < 2:
        return m, 0.0
    var = sum((x - m) ** 2 for x in v) / (len(v) - 1)
    return m, math.sqrt(var / len(v))


def fit_loglog(xs, ys):
    """Least-squares slope and intercept of log10 y against log10 x (points with x, y > 0)."""
    pts = [(math.log10(x), math.log10(y)) for x, y in zip(xs, ys) if x > 0 and y > 0 and math.isfinite(x * y)]
    if len(pts) < 2:
        return math.nan, math.nan
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return math.nan, math.nan
    slope = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    return slope, my - slope * mx


def loglog_at(xs, ys, x, fit=None):
    """y at x on the piecewise log-log line through (xs, ys) sorted by xs; outside the measured range
    the fitted power law (slope, intercept) extrapolates. Returns (y, extrapolated)."""
    pts = sorted((a, b) for a, b in zip(xs, ys) if a > 0 and b > 0)
    if not pts or not x > 0:
        return math.nan, True
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1 and x1 > x0:
            t = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0))), False
    if len(pts) == 1 and x == pts[0][0]:
        return pts[0][1], False
    if fit and math.isfinite(fit[0]):
        return 10 ** (fit[1] + fit[0] * math.log10(x)), True
    return math.nan, True


def common_value(lows, highs):
    """A value inside every range [low_i, high_i]: the geometric middle of their intersection; if
    they do not all overlap, the largest low (every curve reaches it; the others extrapolate)."""
    lo = [x for x in lows if math.isfinite(x) and x > 0]
    hi = [x for x in highs if math.isfinite(x) and x > 0]
    if not lo or not hi:
        return math.nan
    a, b = max(lo), min(hi)
    return math.sqrt(a * b) if a <= b else a


def time_to_error(times, errors, target, fit=None):
    """Wall time at which the curve (times, errors) by increasing time first reaches `target`:
    log-log interpolation between the bracketing levels, else the fitted power law (extrapolated)."""
    pts = sorted((t, e) for t, e in zip(times, errors) if t > 0 and e > 0)
    for i, (t, e) in enumerate(pts):
        if e <= target:
            if i == 0:
                break
            (t0, e0) = pts[i - 1]
            if e0 == e:
                return t, False
            s = (math.log(target) - math.log(e0)) / (math.log(e) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t) - math.log(t0))), False
    if fit and math.isfinite(fit[0]) and fit[0] < 0:
        return 10 ** ((math.log10(target) - fit[1]) / fit[0]), True
    return math.nan, True


# ---- analysis ---------------------------------------------------------------------------------

def _curves(rows, configs, metrics):
    """{config: {"spp": [...], "time": [(mean, sem)], metric: [(mean, sem)]}} over the seeds."""
    curves = {}
    for cfg in configs:
        mine = [r for r in rows if r["config"] == cfg]
        levels = sorted({r["spp"] for r in mine})
        c = {"spp": levels, "time": [mean_sem([r["render_time_s"] for r in mine if r["spp"] == s]) for s in levels]}
        for m in metrics:
            c[m] = [mean_sem([r[m] for r in mine if r["spp"] == s]) for s in levels]
        curves[cfg] = c
    return curves


def _summary(study, curves, metrics, equal_time_rows):
    summary = {}
    for m in metrics:
        per = {}
        for cfg, c in curves.items():
            times, errs = [t for t, _ in c["time"]], [e for e, _ in c[m]]
            slope_t, icpt_t = fit_loglog(times, errs)
            slope_s, _ = fit_loglog(c["spp"], errs)
            fe = [e for e in errs if math.isfinite(e) and e > 0]
            ft = [t for t in times if math.isfinite(t) and t > 0]
            per[cfg] = {"slope_time": slope_t, "intercept_time": icpt_t, "slope_spp": slope_s,
                        "min_error": min(fe, default=math.nan), "max_error": max(fe, default=math.nan),
                        "min_time": min(ft, default=math.nan), "max_time": max(ft, default=math.nan)}
        target = common_value([v["min_error"] for v in per.values()], [v["max_error"] for v in per.values()])
        equal_time = common_value([v["min_time"] for v in per.values()], [v["max_time"] for v in per.values()])
        for cfg, c in curves.items():
            times, errs = [t for t, _ in c["time"]], [e for e, _ in c[m]]
            fit = (per[cfg]["slope_time"], per[cfg]["intercept_time"])
            per[cfg]["time_to_target"], per[cfg]["time_extrapolated"] = time_to_error(times, errs, target, fit)
            per[cfg]["error_at_equal_time"], per[cfg]["error_extrapolated"] = loglog_at(times, errs, equal_time, fit)
            measured = [r[m] for r in equal_time_rows if r["config"] == cfg]
            per[cfg]["equal_time_measured"], per[cfg]["equal_time_sem"] = mean_sem(measured)
        base = per.get(study.baseline)
        for cfg, v in per.items():
            v["speedup"] = (base["time_to_target"] / v["time_to_target"]) if base and v["time_to_target"] > 0 else math.nan
            v["error_ratio"] = (v["error_at_equal_time"] / base["error_at_equal_time"]) if base and base[
                "error_at_equal_time"] > 0 else math.nan
            v["measured_ratio"] = (v["equal_time_measured"] / base["equal_time_measured"]) if base and base[
                "equal_time_measured"] > 0 else math.nan
        summary[m] = {"target": target, "equal_time": equal_time, "configs": per}
    return summary


def _conclusions(study, summary, label, ref_error, metrics):
    out = []
    base = study.baseline
    for m in metrics:
        s = summary[m]
        per = s["configs"]
        name = METRICS.get(m, m)
        timed = {k: v for k, v in per.items() if math.isfinite(v["time_to_target"])}
        if timed and math.isfinite(s["target"]):
            fast = min(timed, key=lambda k: timed[k]["time_to_target"])
            slow = max(timed, key=lambda k: timed[k]["time_to_target"])
            ext = [k for k, v in timed.items() if v["time_extrapolated"]]
            out.append(
                f"{label}, equal {name} ({fmt(s['target'])}): fastest is "
                f"{fast} ({fmt(timed[fast]['time_to_target'])} s, {fmt(timed[fast]['speedup'], 3)}x the speed of {base}), "
                f"slowest {slow} ({fmt(timed[slow]['time_to_target'])} s, {fmt(timed[slow]['speedup'], 3)}x)" +
                (f"; extrapolated with the fitted slope for {', '.join(ext)}" if ext else "") + ".")
        errs = {k: v for k, v in per.items() if math.isfinite(v["error_at_equal_time"])}
        if errs and math.isfinite(s["equal_time"]):
            best = min(errs, key=lambda k: errs[k]["error_at_equal_time"])
            out.append(f"{label}, equal time ({fmt(s['equal_time'])} s): lowest {name} is {best}'s "
                       f"({fmt(errs[best]['error_at_equal_time'])}, {fmt(errs[best]['error_ratio'], 3)}x {base}'s).")
        measured = {k: v for k, v in per.items() if math.isfinite(v["equal_time_measured"])}
        if measured and study.time_limit:
            best = min(measured, key=lambda k: measured[k]["equal_time_measured"])
            out.append(f"{label}, rendered for {study.time_limit:g} s each (--time-limit): lowest {name} is {best}'s "
                       f"({fmt(measured[best]['equal_time_measured'])} ± {fmt(measured[best]['equal_time_sem'], 2)}, "
                       f"{fmt(measured[best]['measured_ratio'], 3)}x {base}'s).")
    if "relmse" in summary:
        per = summary["relmse"]["configs"]
        slopes = {k: v["slope_time"] for k, v in per.items() if math.isfinite(v["slope_time"])}
        if slopes:
            flat = [k for k, v in slopes.items() if v > -0.5]
            out.append(f"{label}: relMSE falls with wall time at slopes {fmt(min(slopes.values()), 3)} .. "
                       f"{fmt(max(slopes.values()), 3)} on log-log axes (−1 is the Monte Carlo rate of an unbiased "
                       f"estimator); " + (f"flatter than −0.5 (bias or the reference's own error dominates): "
                                          f"{', '.join(flat)}." if flat else "none is flatter than −0.5."))
        lowest = min((v["min_error"] for v in per.values() if math.isfinite(v["min_error"])), default=math.nan)
        if math.isfinite(ref_error) and math.isfinite(lowest) and lowest > 0:
            share = ref_error / lowest
            out.append(f"{label}: the reference's own relMSE, estimated from its two halves, is {fmt(ref_error)} = "
                       f"{100 * share:.3g} % of the lowest measured relMSE" +
                       (" (converged enough for these curves)." if share < 0.1 else
                        "; the lowest points of the curves are limited by the reference (render a longer reference)."))
    return out


def _plot(study, curves, summary, metrics, ref_error, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(metrics)
    cols = 2 if n > 1 else 1
    rows_ = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows_, cols, figsize=(5.2 * cols, 3.8 * rows_), squeeze=False)
    for i, m in enumerate(metrics):
        ax = axes[i // cols][i % cols]
        for cfg, c in curves.items():
            t = [x for x, _ in c["time"]]
            e = [x for x, _ in c[m]]
            ax.errorbar(t, e, yerr=[s for _, s in c[m]], xerr=[s for _, s in c["time"]], marker="o", ms=3,
                        capsize=2, label=cfg, lw=1.2 if cfg != study.baseline else 2.4)
        s = summary[m]
        if math.isfinite(s["target"]):
            ax.axhline(s["target"], color="grey", ls=":", lw=1)
        if math.isfinite(s["equal_time"]):
            ax.axvline(s["equal_time"], color="grey", ls="--", lw=1)
        if m == "relmse" and math.isfinite(ref_error) and ref_error > 0:
            ax.axhline(ref_error, color="black", ls="-.", lw=1, label="reference's own relMSE")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time per image [s]")
        ax.set_ylabel(METRICS.get(m, m))
        ax.grid(True, which="both", alpha=0.25)
        if i == 0:
            ax.legend(fontsize=7)
    for j in range(n, rows_ * cols):
        axes[j // cols][j % cols].axis("off")
    fig.suptitle(title + " (mean ± s.e.m. over seeds; dotted: equal error, dashed: equal time)", fontsize=9)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)


def _tables(study, summary, metrics):
    sections = []
    for m in metrics:
        s = summary[m]
        rows = []
        for cfg, v in s["configs"].items():
            rows.append({
                "configuration": cfg + (" (baseline)" if cfg == study.baseline else ""),
                "slope vs time": v["slope_time"], "slope vs spp": v["slope_spp"],
                "time to target [s]": fmt(v["time_to_target"]) + (" (extrapolated)" if v["time_extrapolated"] else ""),
                "speed-up": v["speedup"],
                "error at equal time": fmt(v["error_at_equal_time"]) + (" (extrapolated)" if v["error_extrapolated"] else ""),
                "ratio": v["error_ratio"],
                "measured at time limit": (f"{fmt(v['equal_time_measured'])} ± {fmt(v['equal_time_sem'], 2)}"
                                           if math.isfinite(v["equal_time_measured"]) else ""),
            })
        cols = ["configuration", "slope vs time", "slope vs spp", "time to target [s]", "speed-up",
                "error at equal time", "ratio"] + (["measured at time limit"] if study.time_limit else [])
        text = (f"Target {METRICS.get(m, m)} = {fmt(s['target'])} and equal time = {fmt(s['equal_time'])} s: the "
                f"geometric middle of the range every configuration's curve covers (if the ranges do not all overlap: "
                f"the largest of the lowest errors, and the largest of the shortest times; other curves are then "
                f"extrapolated with their fitted slope); speed-up = "
                f"time of {study.baseline} / time of the configuration at the target; ratio = error / {study.baseline}'s "
                f"error at equal time.\n\n" + markdown_table(rows, cols))
        sections.append((f"Convergence: {METRICS.get(m, m)}", text))
    return sections


def analyse_study(study: ConvergenceStudy, ctx, label: str) -> StudyResult:
    metrics = list(study.metrics)
    ref_sweep, ref_match = study.reuse_reference or (f"{study.name}_reference", {})
    refs = [j.output for j in ctx.by_sweep(ref_sweep)
            if j.label == label and all(j.settings.get(k) == v for k, v in ref_match.items())]
    if len(refs) < 2:
        raise ExperimentError(f"{label}: the convergence reference needs at least 2 renders, found {len(refs)}")
    base = ctx.out_dir / "reference" / study.name
    ref = ctx.merge(refs, base / f"{label}.exr")
    halves = ctx.compare(ctx.merge(refs[0::2], base / f"{label}_half_a.exr"),
                         ctx.merge(refs[1::2], base / f"{label}_half_b.exr"))
    # Two independent halves of n/2 spp each: E relMSE(a, b) ≈ 2 · 2σ²/n = 4 × the relMSE of the
    # merged n-spp reference (variance σ²/n), so the reference's own relMSE ≈ relMSE(a, b) / 4.
    ref_error = halves["relmse"] / 4.0

    def measure(jobs):
        rows = []
        for j in jobs:
            m = ctx.compare(j.output, ref)
            row = job_row(j, {k: m.get(k) for k in metrics})
            row["config"] = j.settings["variant"]
            rows.append(row)
        return rows

    rows = measure([j for j in ctx.by_sweep(study.name) if j.label == label])
    equal_rows = measure([j for j in ctx.by_sweep(f"{study.name}_equal_time") if j.label == label])
    configs = list(study.active_configs())
    curves = _curves(rows, configs, metrics)
    summary = _summary(study, curves, metrics, equal_rows)
    fig = _plot(study, curves, summary, metrics, ref_error, ctx.out_dir / f"{label}_{study.name}.png",
                f"{label}: error vs wall time")
    sections = _tables(study, summary, metrics)
    sections.insert(0, (f"Convergence reference ({label})",
                        f"{len(refs)} seeds × {study.ref_spp} spp merged ({study.reference}); relMSE between its two "
                        f"halves {fmt(halves['relmse'])}, so its own relMSE ≈ {fmt(ref_error)}; HDR-FLIP between the "
                        f"halves {fmt(halves.get('flip_hdr_mean'))} (an upper bound of the reference's own)."))
    conclusions = _conclusions(study, summary, label, ref_error, metrics)
    top = max(j.settings["spp"] for j in ctx.by_sweep(study.name) if j.label == label)
    pick = {}
    for j in ctx.by_sweep(study.name):
        if j.label == label and j.settings["spp"] == top:
            pick.setdefault(j.settings["variant"], j.output)
    comparison = {"title": f"{label}: {top} spp per configuration against the reference", "reference": ref,
                  "tests": [(f"{cfg} ({top} spp)", path) for cfg, path in pick.items()]}
    for r in rows + equal_rows:
        r["study"] = study.name
    summary_all = {"reference_relmse": ref_error, "halves": halves, "metrics": summary}
    csv_path = write_csv(rows + equal_rows, ctx.out_dir / f"{study.name}_{label}.csv")
    write_json({"settings": study.settings(), "summary": summary_all}, ctx.out_dir / f"{study.name}_{label}.json")
    sections[0] = (sections[0][0], sections[0][1] + f" Every render: [{csv_path.name}]({csv_path.name}).")
    return StudyResult(rows + equal_rows, summary_all, sections, [fig], conclusions, comparison)
