#!/usr/bin/env python3
"""Regenerate every committed experiment result with one command (issue 15):

    python3 experiments/run_all.py                      # every experiment, full sample counts
    python3 experiments/run_all.py --shard 0/3          # a third of the render jobs (resumable)
    python3 experiments/run_all.py --collect-only       # reports once every shard has finished
    python3 experiments/run_all.py --estimate           # how long a full run takes, from a --quick run
    python3 experiments/run_all.py --quick              # the smoke run (results in <name>/quick/)

Each experiment runs as `experiments/<name>.py` with the options given here and writes
experiments/results/<name>/ (report.md, report.html, CSV, JSON, figures). Renders that exist are
reused, so an interrupted run resumes where it stopped; --shard I/N splits every experiment's jobs
by index so that several sessions or machines can share them. A full run refuses a working tree
with uncommitted changes (its reports could not name a commit) unless --allow-dirty; the reports
then say that they are not from any commit. The state of every experiment is written to
experiments/results/run_all.json."""
from __future__ import annotations

import argparse
import datetime
import json
import re
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from iris_experiments import exr, report, tools  # noqa: E402
from iris_experiments.errors import ExperimentError  # noqa: E402

EXPERIMENTS = ["channel_count", "per_bounce_phase", "approximation_error", "thesis_reproduction", "sampler_efficiency",
               "media_mis", "industry_thin_film", "caustics", "polarization"]


def parse_args(argv):
    p = argparse.ArgumentParser(prog="experiments/run_all.py", description=__doc__.split("\n\n")[0])
    p.add_argument("--only", default=None, help="comma-separated experiments (default: all: " + ", ".join(EXPERIMENTS) + ")")
    p.add_argument("--quick", action="store_true", help="the quick smoke run of every experiment")
    p.add_argument("--shard", default=None, metavar="I/N", help="render only jobs with index I modulo N")
    p.add_argument("--collect-only", action="store_true", help="only make the reports from finished renders")
    p.add_argument("--parallel", type=int, default=1, help="render jobs at a time (keep 1 when times matter)")
    p.add_argument("--threads", type=int, default=None, help="render threads per job")
    p.add_argument("--build-dir", default=None, help="folder with render/compare/merge (default $IRIS_BUILD_DIR or build/)")
    p.add_argument("--spp-scale", type=float, default=None, help="passed to every experiment (recorded in the reports)")
    p.add_argument("--allow-dirty", action="store_true", help="run a full run on a tree with uncommitted changes")
    p.add_argument("--dry-run", action="store_true", help="print each experiment's render commands")
    p.add_argument("--status", action="store_true",
                   help="write experiments/results/STATUS.md from the committed reports (provenance, sample "
                        "scale, conclusions) and print it")
    p.add_argument("--estimate", action="store_true",
                   help="estimate the wall time of the full run from the renders of a finished --quick run")
    return p.parse_args(argv)


def selected(args) -> list:
    names = args.only.split(",") if args.only else EXPERIMENTS
    unknown = [n for n in names if n not in EXPERIMENTS]
    if unknown:
        raise ExperimentError(f"unknown experiment(s) {', '.join(unknown)} (known: {', '.join(EXPERIMENTS)})")
    return names


def experiment_argv(args) -> list:
    argv = []
    for flag, value in (("--shard", args.shard), ("--threads", args.threads), ("--build-dir", args.build_dir),
                        ("--spp-scale", args.spp_scale)):
        if value is not None:
            argv += [flag, str(value)]
    argv += ["--parallel", str(args.parallel)]
    return argv + [f for f, on in (("--quick", args.quick), ("--collect-only", args.collect_only),
                                   ("--dry-run", args.dry_run)) if on]


# ---- estimate ---------------------------------------------------------------------------------

def load_plan(name: str, argv: list):
    """The render jobs an experiment would run with argv (nothing is run)."""
    from iris_experiments.experiment import parse_args as exp_args, plan
    mod = __import__(name)
    cls = [v for v in vars(mod).values() if isinstance(v, type) and v.__module__ == name and hasattr(v, "analyse")][0]
    exp = cls()
    _, _, jobs = plan(exp, exp_args(exp, argv + ["--dry-run"]))
    return jobs


def _key(job) -> tuple:
    """What a job's cost per sample and pixel depends on: sweep, scene and settings other than the
    sample count, seed, resolution, time limit and threads."""
    skip = {"spp", "seed", "res", "time_limit", "threads"}
    return (job.sweep, job.label, tuple(sorted((k, str(v)) for k, v in job.settings.items() if k not in skip)))


def _pixels(job) -> int:
    """Pixels of a job's image: its -D res, else the scene's <default name="res"> (square images)."""
    if "res" in job.settings:
        return int(job.settings["res"]) ** 2
    m = re.search(r'<default\s+name="res"\s+value="(\d+)"', (tools.REPO / job.scene).read_text())
    if not m:
        raise ExperimentError(f"{job.scene}: no res to price the job by")
    return int(m.group(1)) ** 2


def estimate(names, args) -> list:
    """Seconds per experiment: each full job costs (its spp × pixels) × the cost per sample·pixel of
    the quick renders with the same settings (their iris.render_time_s; the mean over the
    experiment where no quick job matches) plus the mean per-job overhead of the quick run (process
    start, scene loading, output: the job log's wall time minus the render time); equal-time jobs
    cost their time limit plus that overhead."""
    rows = []
    extra = ["--build-dir", args.build_dir] if args.build_dir else []
    for name in names:
        quick = load_plan(name, extra + ["--quick"])
        full = load_plan(name, extra + (["--spp-scale", str(args.spp_scale)] if args.spp_scale else []))
        rates, overheads = {}, []
        for j in quick:
            if not j.output.exists() or not j.settings.get("spp"):
                continue
            t = float(exr.read_exr_metadata(str(j.output)).get("iris.render_time_s", "nan"))
            rates.setdefault(_key(j), []).append(t / (j.settings["spp"] * _pixels(j)))
            log = j.output.with_suffix(".log")
            if log.exists():
                for line in log.read_text().splitlines()[:3]:
                    if line.startswith("# exit 0, "):
                        overheads.append(max(0.0, float(line.split(", ")[1].split()[0]) - t))
        if not rates:
            raise ExperimentError(f"{name}: no finished --quick renders to calibrate from; run "
                                  f"`python3 experiments/run_all.py --quick --only {name}` first")
        mean_rate = sum(sum(v) / len(v) for v in rates.values()) / len(rates)
        overhead = sum(overheads) / len(overheads) if overheads else 1.0
        total, matched = 0.0, 0
        for j in full:
            if j.settings.get("time_limit") and not j.settings.get("spp"):
                total += float(j.settings["time_limit"]) + overhead
                continue
            r = rates.get(_key(j))
            matched += r is not None
            rate = sum(r) / len(r) if r else mean_rate
            total += rate * j.settings["spp"] * _pixels(j) + overhead
        rows.append({"experiment": name, "jobs": len(full), "matched": matched, "seconds": total,
                     "overhead_s": overhead})
    return rows


# ---- status of the committed results ------------------------------------------------------------

def _report_fields(text: str) -> dict:
    fields = {}
    for key in ("git", "date_utc", "spp scale"):
        m = re.search(rf"^- {re.escape(key)}: (.*)$", text, flags=re.M)
        fields[key] = m.group(1).strip() if m else ""
    m = re.search(r"^## Conclusions[^\n]*\n\n(.*?)(?:\n## |\Z)", text, flags=re.S | re.M)
    fields["conclusions"] = [l[2:] for l in (m.group(1) if m else "").splitlines() if l.startswith("- ")]
    m = re.search(r"^Command:\n\n    (.*)$", text, flags=re.M)
    fields["command"] = m.group(1) if m else ""
    return fields


def status_markdown(names) -> str:
    """The committed results as they are: which commit and scale made them, and their conclusions
    (copied from each report.md by this function, never typed)."""
    lines = ["# Committed experiment results", "",
             "Generated by `python3 experiments/run_all.py --status` from `experiments/results/<name>/report.md`; "
             "do not edit. A result counts as current only when it names a clean commit and the full sample counts "
             "(no `spp scale`) and no source it depends on (the renderer's folders, the experiment's script, "
             "framework and scenes) has changed since that commit; one made from a clean commit at scaled counts "
             "is SCALED (docs/experiments.md says what the scale changes); one whose sources changed since is "
             "OUTDATED; anything else is STALE.", ""]
    for name in names:
        path = HERE / "results" / name / "report.md"
        if not path.exists():
            lines += [f"## {name}", "", "no committed report", ""]
            continue
        f = _report_fields(path.read_text())
        lines += [f"## {name}", "", f"- made: {f['date_utc']} UTC, git: {f['git']}", f"- command: `{f['command']}`",
                  f"- status: {result_status(name, f)}", f"- report: [{name}/report.md]({name}/report.md)", "",
                  "Its conclusions:", ""]
        lines += [f"- {c}" for c in f["conclusions"]] + [""]
    return "\n".join(lines)


# What a result depends on: the renderer's sources (every layer below experiments/ in the layer
# table of docs/architecture.md, the same table tests/architecture/check_layers.py reads, the build
# and the shipped scenes/ that experiments render) and the experiment's own script, framework and
# scenes.
LAYER_ROW = re.compile(r"^\|\s*(\d+)\s*\|\s*`([\w./-]+)/`\s*\|", re.M)


def renderer_sources(root: Path = HERE.parent) -> list:
    """CMakeLists.txt, scenes/ and the folders of the layers below experiments/ (docs/architecture.md)."""
    table = root / "docs" / "architecture.md"
    layers = {folder: int(rank) for rank, folder in LAYER_ROW.findall(table.read_text())} if table.exists() else {}
    if "experiments" not in layers:
        raise SystemExit(f"{table}: no layer table with a row for experiments/ (rows \"| <layer> | `folder/` | ...\")")
    return ["CMakeLists.txt", "scenes"] + sorted(f for f, rank in layers.items() if rank < layers["experiments"])


def sources_changed(commit: str, name: str, root: Path = HERE.parent) -> list | None:
    """Files of the renderer or of experiment `name` that differ between `commit` and HEAD in the
    repository at `root` (None when `commit` is not in its history, e.g. in a shallow clone, so
    nothing can be compared)."""
    paths = renderer_sources(root) + [f"experiments/{name}.py", "experiments/iris_experiments", "experiments/scenes"]
    known = subprocess.run(["git", "cat-file", "-e", f"{commit}^{{commit}}"], cwd=root, capture_output=True)
    if known.returncode != 0:
        return None
    out = subprocess.run(["git", "diff", "--name-only", commit, "HEAD", "--", *paths], cwd=root, capture_output=True,
                         text=True, check=True).stdout
    return out.split()


def result_status(name, f, root: Path = HERE.parent) -> str:
    """current (clean commit, full counts, with the HTML report, and no source it depends on changed
    since), SCALED (the same at scaled sample counts), OUTDATED (made from a clean commit whose
    renderer or experiment sources have changed since: its numbers describe older code) or STALE
    (and why), from a report's fields."""
    problems = []
    if not f["git"] or "uncommitted" in f["git"] or "not from any commit" in f["git"]:
        problems.append("not made from a clean commit")
    if not (HERE / "results" / name / "report.html").exists():
        problems.append("made before the convergence curves and the HTML report existed")
    scale = f["spp scale"].split(" ")[0] if f["spp scale"] else ""
    if problems:
        return "STALE: " + "; ".join(problems + ([f"sample counts scaled ({scale})"] if scale else []))
    m = re.match(r"commit ([0-9a-f]+)", f["git"])
    changed = sources_changed(m.group(1), name, root) if m else None
    scaled = f" (at sample counts x {scale})" if scale else ""
    if changed:
        shown = ", ".join(changed[:3]) + (", ..." if len(changed) > 3 else "")
        return (f"OUTDATED: {len(changed)} source files of the renderer or of this experiment changed since "
                f"commit {m.group(1)[:7]} ({shown}){scaled}; regenerate it")
    unchecked = "" if changed is not None else " (its commit is not in this checkout: sources not compared)"
    if scale:
        return f"SCALED: sample counts x {scale} of the experiment's definition, from a clean commit{unchecked}"
    return "current" + unchecked


# ---- run ----------------------------------------------------------------------------------------

def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        names = selected(args)
        if args.status:
            text = status_markdown(names)
            (HERE / "results" / "STATUS.md").write_text(text)
            print(text)
            return 0
        if args.estimate:
            rows = estimate(names, args)
            for r in rows:
                print(f"{r['experiment']}: {r['jobs']} jobs, ~{r['seconds'] / 3600:.2f} h "
                      f"({r['matched']} priced from matching quick renders, {r['overhead_s']:.2f} s overhead per job)")
            print(f"total: ~{sum(r['seconds'] for r in rows) / 3600:.2f} h, one job at a time on this machine")
            return 0
        prov = report.provenance()
        if prov["state"] != "clean" and not (args.quick or args.dry_run or args.allow_dirty):
            raise ExperimentError(f"{prov['text']}; commit first (or pass --allow-dirty: the reports will say "
                                  "that they are not from any commit)")
        tools.tool("render", tools.build_dir(args.build_dir))
    except ExperimentError as e:
        print(f"run_all: error: {e}", file=sys.stderr)
        return 2
    state_path = HERE / "results" / ("run_all_quick.json" if args.quick else "run_all.json")
    state = json.loads(state_path.read_text()) if state_path.exists() else {}
    state.update({"provenance": prov["text"], "argv": sys.argv[1:] if argv is None else argv})
    failures = 0
    for name in names:
        cmd = [sys.executable, str(HERE / f"{name}.py"), *experiment_argv(args)]
        print(f"run_all: {' '.join(cmd[1:])}", flush=True)
        start = time.time()
        code = subprocess.run(cmd, cwd=tools.REPO).returncode
        entry = {"exit": code, "seconds": round(time.time() - start, 1), "shard": args.shard,
                 "collect_only": args.collect_only,
                 "finished_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")}
        state.setdefault("experiments", {})[name] = entry
        if not args.dry_run:
            state_path.parent.mkdir(parents=True, exist_ok=True)
            state_path.write_text(json.dumps(state, indent=2) + "\n")
        failures += code != 0
    print(f"run_all: {len(names) - failures} of {len(names)} experiments finished" +
          (f"; state in {state_path}" if not args.dry_run else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
