"""The command-line driver shared by every experiment script (experiments/<name>.py):

    experiments/<name>.py [--quick] [--parallel N] [--threads T] [--build-dir DIR] [--out DIR]
                          [--force] [--dry-run] [--slurm [--submit | --resubmit]] [--collect-only]

An Experiment subclass declares its scenes (SceneSpec), its sweeps for full and quick mode, and an
analysis that turns the collected rows into tables, figures and conclusions."""
from __future__ import annotations

import argparse
import dataclasses
import json
import shlex
import sys
from dataclasses import dataclass, field
from pathlib import Path

from . import collect, html_report, inprocess, report, runner, scenes, slurm, sweep, tools
from .convergence import ConvergenceStudy
from .errors import ExperimentError


@dataclass
class Context:
    """What an analysis gets: the arguments, the output folder, the jobs (by sweep), tool paths."""
    args: argparse.Namespace
    out_dir: Path
    jobs: list
    build_dir: Path
    figures: list = field(default_factory=list)

    def by_sweep(self, name: str) -> list:
        return [j for j in self.jobs if j.sweep == name]

    def compare(self, test: Path, ref: Path) -> dict:
        return collect.compare(tools.tool("compare", self.build_dir), test, ref)

    def merge(self, inputs, output: Path) -> Path:
        return collect.merge(tools.tool("merge", self.build_dir), inputs, output)


@dataclass
class Analysis:
    rows: list                          # one dict per result (written to results.csv / .json)
    columns: list                       # columns of the main report table
    conclusions: list                   # sentences computed from the data
    sections: list = field(default_factory=list)   # extra (heading, markdown) sections
    figures: list = field(default_factory=list)    # PNG paths (absolute) to embed in the report
    # Interactive image comparisons of the HTML report: {"title", "reference": EXR, "tests": [(label, EXR)]}
    comparisons: list = field(default_factory=list)

    def add_study(self, result) -> None:
        """Append a convergence study's sections, figures, conclusions and comparison."""
        self.sections += result.sections
        self.figures += result.figures
        self.conclusions += result.conclusions
        self.comparisons.append(result.comparison)


class Experiment:
    name = "experiment"
    title = "Experiment"
    question = ""
    scene_specs: dict = {}              # label -> scenes.SceneSpec

    # --- to override -------------------------------------------------------------------------
    def sweeps(self, quick: bool, args) -> list:
        raise NotImplementedError

    def analyse(self, ctx: Context) -> Analysis:
        raise NotImplementedError

    def settings(self, quick: bool) -> dict:
        return {"mode": "quick" if quick else "full"}

    # --- helpers -----------------------------------------------------------------------------
    def scene_paths(self) -> dict:
        return {label: spec.path for label, spec in self.scene_specs.items()}

    def quick_resolution(self, quick: bool, res: int = 48) -> dict:
        """Per-scene -D res=<res> in quick mode for scenes that declare a 'res' parameter."""
        if not quick:
            return {}
        return {label: {"res": res} for label, spec in self.scene_specs.items() if "res" in spec.declared}


class ConvergenceExperiment(Experiment):
    """An experiment whose renders are one ConvergenceStudy per scene (self.study, set in sweeps()),
    with a FULL and a QUICK definition {"res": ..., "ref_spp": ..., ...} as class attributes."""
    FULL: dict = {}
    QUICK: dict = {}

    def cfg(self, quick):
        return self.QUICK if quick else self.FULL

    def convergence_study(self, quick, configs: dict, baseline: str, reference: dict, **kw):
        """The ConvergenceStudy of this experiment's FULL or QUICK definition: its "convergence" block
        gives the sample counts, seeds and time limit, "ref_spp" and "ref_seeds" the reference (seeds
        1000, 1001, ...); `kw` goes to ConvergenceStudy (e.g. unavailable)."""
        c = self.cfg(quick)
        conv = c["convergence"]
        return ConvergenceStudy(configs, baseline, reference, conv["spp_levels"], conv["seeds"], c["ref_spp"],
                                [1000 + i for i in range(c["ref_seeds"])], time_limit=conv["time_limit"], **kw)

    def settings(self, quick):
        c = self.cfg(quick)
        return {"mode": "quick" if quick else "full", "resolution": f"{c['res']} (-D res)",
                "scenes": {k: v.path for k, v in self.scene_specs.items()}, **self.study.settings()}


def parse_args(exp: Experiment, argv):
    argv = list(argv)
    p = argparse.ArgumentParser(prog=f"experiments/{exp.name}.py", description=f"{exp.title}. {exp.question}")
    p.add_argument("--quick", action="store_true", help="tiny images and few samples (about a minute)")
    p.add_argument("--parallel", type=int, default=1, help="render jobs run at the same time (default 1)")
    p.add_argument("--threads", type=int, default=None, help="render threads per job (default: all cores)")
    p.add_argument("--build-dir", default=None, help="folder with render/compare/merge (default $IRIS_BUILD_DIR or build/)")
    p.add_argument("--out", default=None, help="output folder (default experiments/results/<name>[/quick])")
    p.add_argument("--force", action="store_true", help="re-render images that already exist")
    p.add_argument("--timeout", type=float, default=None, help="seconds before a render job is killed")
    p.add_argument("--dry-run", action="store_true", help="print the render commands and exit")
    p.add_argument("--slurm", action="store_true", help="write a Slurm job-array script instead of rendering")
    p.add_argument("--slurm-time", default="02:00:00", help="#SBATCH --time per task")
    p.add_argument("--slurm-cpus", type=int, default=8, help="#SBATCH --cpus-per-task")
    p.add_argument("--slurm-mem", default="4G", help="#SBATCH --mem")
    p.add_argument("--slurm-partition", default=None, help="#SBATCH --partition")
    p.add_argument("--slurm-account", default=None, help="#SBATCH --account")
    p.add_argument("--submit", action="store_true",
                   help="with --slurm: submit the array with sbatch and a collect job that runs after it (afterok)")
    p.add_argument("--resubmit", action="store_true",
                   help="with --slurm: report the tasks whose image is missing or interrupted (with their logs) "
                        "and submit only those, plus a new collect job")
    p.add_argument("--scene", action="append", default=[], metavar="[LABEL=]PATH",
                   help="render PATH instead of the defined scene LABEL (or of every scene); its materials are "
                        "then checked from the file only")
    p.add_argument("--spp-scale", type=float, default=1.0,
                   help="multiply every sample count of the sweeps by this factor (a cheaper or longer run; "
                        "recorded in the report)")
    p.add_argument("--skip-missing", action="store_true",
                   help="leave out scenes that are not available (with a warning) instead of stopping")
    p.add_argument("--collect-only", action="store_true", help="only collect results of finished renders")
    p.add_argument("--in-process", action="store_true",
                   help="render through the Python module in this process (scenes loaded once, same images); "
                        "not for timings or --slurm (iris_experiments/inprocess.py)")
    p.add_argument("--shard", default=None, metavar="I/N",
                   help="render only jobs whose index is I modulo N (several machines or sessions); no report "
                        "until --collect-only after every shard")
    args = p.parse_args(argv)
    args.argv = argv
    return args


def output_dir(exp: Experiment, args) -> Path:
    if args.out:
        return Path(args.out).resolve()
    base = tools.REPO / "experiments" / "results" / exp.name
    return base / "quick" if args.quick else base


def run(exp: Experiment, argv=None) -> int:
    args = parse_args(exp, sys.argv[1:] if argv is None else argv)
    try:
        return _run(exp, args)
    except ExperimentError as e:
        print(f"{exp.name}: error: {e}", file=sys.stderr)
        return 2


def override_scenes(exp: Experiment, overrides) -> None:
    """Apply --scene [LABEL=]PATH (paths relative to the current folder or the repository)."""
    specs = {k: dataclasses.replace(v) for k, v in exp.scene_specs.items()}
    for item in overrides:
        label, _, path = item.rpartition("=")
        if label and label not in specs:
            raise ExperimentError(f"--scene {item}: no scene '{label}' in this experiment (known: {', '.join(specs)})")
        p = Path(path).resolve()
        rel = str(p.relative_to(tools.REPO)) if p.is_relative_to(tools.REPO) else str(p)
        for key in ([label] if label else list(specs)):
            specs[key] = dataclasses.replace(specs[key], path=rel, materials=())
    exp.scene_specs = specs


def parse_shard(text: str | None):
    """--shard I/N → (I, N) with 0 <= I < N, or None."""
    if not text:
        return None
    try:
        i, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise ExperimentError(f"--shard expects I/N (e.g. 0/4), got '{text}'") from None
    if not (n >= 1 and 0 <= i < n):
        raise ExperimentError(f"--shard {text}: need 0 <= I < N")
    return i, n


def plan(exp: Experiment, args):
    """(output folder, build folder, render jobs) of a run, without running anything."""
    bdir = tools.build_dir(args.build_dir)
    out = output_dir(exp, args)
    override_scenes(exp, args.scene)
    if args.skip_missing:
        available = {}
        for label, spec in exp.scene_specs.items():
            try:
                scenes.check_scenes([spec])
                available[label] = spec
            except ExperimentError as e:
                print(f"{exp.name}: warning: leaving out scene '{label}': {e}", file=sys.stderr)
        if not available:
            raise ExperimentError("no scene of this experiment is available")
        exp.scene_specs = available
    scenes.check_scenes(exp.scene_specs.values())
    render = bdir / "render" if (args.slurm or args.dry_run) else tools.tool("render", bdir)
    sweeps = exp.sweeps(args.quick, args)
    if args.spp_scale != 1.0:
        if not args.spp_scale > 0:
            raise ExperimentError(f"--spp-scale must be positive, got {args.spp_scale}")
        for s in sweeps:
            # spp 0 (render until --time-limit) stays 0.
            if s.fixed.get("spp"):
                s.fixed["spp"] = max(1, round(s.fixed["spp"] * args.spp_scale))
            if "spp" in s.axes:
                scaled = [max(1, round(v * args.spp_scale)) if v else v for v in s.axes["spp"]]
                s.axes["spp"] = list(dict.fromkeys(scaled))   # a series 1, 2, 4 halved: 1, 2
    if args.threads:
        for s in sweeps:
            s.fixed.setdefault("threads", args.threads)
    return out, bdir, sweep.expand(sweeps, out, render)


def collect_command(exp: Experiment, args, out: Path) -> list:
    """The --collect-only run that reports the renders of a Slurm array (same sweeps and options)."""
    drop = {"--slurm", "--submit", "--resubmit", "--force"}
    keep = [a for a in args.argv if a not in drop]
    return [sys.executable, str(tools.REPO / "experiments" / f"{exp.name}.py"), *keep, "--collect-only",
            *([] if args.out else ["--out", str(out)])]


def submit_slurm(exp: Experiment, args, out: Path, jobs) -> int:
    """Write the array script; with --submit/--resubmit submit it (all tasks, or only those without a
    valid image) and a collect job that runs when every task succeeded (--dependency=afterok)."""
    log_dir = out / "slurm-logs"
    script = slurm.write_slurm_script(out / f"slurm_{exp.name}.sh", jobs, job_name=f"iris-{exp.name}", log_dir=log_dir,
                                      time=args.slurm_time, cpus_per_task=args.slurm_cpus, mem=args.slurm_mem,
                                      partition=args.slurm_partition, account=args.slurm_account)
    collect_cmd = shlex.join(collect_command(exp, args, out))
    if not (args.submit or args.resubmit):
        print(f"wrote {script} ({len(jobs)} array tasks)\n"
              f"submit:  jid=$(sbatch --parsable {script})\n"
              f"collect: sbatch --dependency=afterok:$jid --wrap {shlex.quote(collect_cmd)}   (or run it after the array ends)\n"
              f"or: add --submit (both at once); --resubmit later reruns only the tasks without a valid image")
        return 0
    pending = [j for j in jobs if args.force or not args.resubmit or not runner.output_ok(j)]
    if args.resubmit:
        for j in pending:
            logs = sorted(log_dir.glob(f"slurm-*_{j.index}.out"), key=lambda p: p.stat().st_mtime)
            tail = logs[-1].read_text(errors="replace").strip().splitlines()[-3:] if logs else []
            why = "no image" if not j.output.exists() else "interrupted or unreadable image"
            print(f"{exp.name}: task {j.index} ({j.output.name}): {why}; log {logs[-1] if logs else '(none)'}"
                  + "".join(f"\n    {line}" for line in tail))
        if not pending:
            print(f"{exp.name}: every task has a valid image; nothing to resubmit (run --collect-only)")
            return 0
    extra = [f"--account={args.slurm_account}"] if args.slurm_account else []
    if args.slurm_partition:
        extra.append(f"--partition={args.slurm_partition}")
    array_id = slurm.sbatch(script, array=",".join(str(j.index) for j in pending))
    # The collect job starts in the folder sbatch was called from (Slurm's default), like the
    # command line it repeats, so relative paths mean the same.
    collect_id = slurm.sbatch(None, dependency=f"afterok:{array_id}", wrap=collect_cmd,
                              options=[f"--job-name=iris-{exp.name}-collect", f"--output={log_dir / 'collect-%j.out'}",
                                       "--cpus-per-task=1", *extra])
    record = out / "slurm_submissions.json"
    previous = json.loads(record.read_text()) if record.exists() else []
    record.write_text(json.dumps(previous + [{"array": array_id, "collect": collect_id,
                                              "tasks": [j.index for j in pending]}], indent=1))
    print(f"{exp.name}: submitted array job {array_id} ({len(pending)} of {len(jobs)} tasks) and collect job "
          f"{collect_id} (afterok:{array_id}); logs in {log_dir}")
    return 0


def _run(exp: Experiment, args) -> int:
    prov = report.provenance()   # before anything is written
    shard = parse_shard(args.shard)
    out, bdir, jobs = plan(exp, args)

    if args.dry_run:
        for j in jobs:
            print(j.shell())
        return 0
    if args.in_process and (args.slurm or shard):
        raise ExperimentError("--in-process renders here and now: it cannot be combined with --slurm or --shard")
    if args.slurm:
        return submit_slurm(exp, args, out, jobs)
    if args.submit or args.resubmit:
        raise ExperimentError("--submit and --resubmit need --slurm")

    if shard and not args.collect_only:
        mine = [j for j in jobs if j.index % shard[1] == shard[0]]
        print(f"{exp.name}: shard {shard[0]}/{shard[1]}: {len(mine)} of {len(jobs)} render jobs -> {out}")
        failed = [r for r in runner.run_local(mine, parallel=args.parallel, force=args.force, timeout=args.timeout)
                  if not r.ok]
        if failed:
            raise ExperimentError(f"{len(failed)} of {len(mine)} renders of this shard failed (first: "
                                  f"{failed[0].job.output.with_suffix('.log')}: {failed[0].message})")
        missing = sum(1 for j in jobs if not runner.output_ok(j))
        print(f"{exp.name}: shard done; {missing} renders of other shards missing" +
              ("" if missing else "; all renders exist: run again with --collect-only for the report"))
        return 0
    if not args.collect_only:
        print(f"{exp.name}: {len(jobs)} render jobs -> {out}")
        if args.in_process:
            results = inprocess.run_inprocess(jobs, bdir, force=args.force)
        else:
            results = runner.run_local(jobs, parallel=args.parallel, force=args.force, timeout=args.timeout)
        failed = [r for r in results if not r.ok]
        if failed:
            lines = [f"{r.job.output.with_suffix('.log')}: {r.message}" for r in failed[:5]]
            raise ExperimentError(f"{len(failed)} of {len(jobs)} renders failed:\n  " + "\n  ".join(lines))
    missing = [j for j in jobs if not runner.output_ok(j)]
    if missing:
        raise ExperimentError(f"{len(missing)} renders are missing (first: {missing[0].output}); "
                              "run without --collect-only or wait for the Slurm array")

    run_settings = dict(exp.settings(args.quick))
    run_settings["parallel jobs"] = f"{args.parallel} (render times are only comparable when 1)"
    run_settings["threads per job"] = args.threads or "all cores"
    run_settings["render jobs"] = len(jobs)
    if args.spp_scale != 1.0:
        run_settings["spp scale"] = f"{args.spp_scale:g} (every sample count above is multiplied by this)"
    ctx = Context(args, out, jobs, bdir)
    analysis = exp.analyse(ctx)
    csv_path = collect.write_csv(analysis.rows, out / "results.csv")
    collect.write_json({"experiment": exp.name, "settings": run_settings, "rows": analysis.rows},
                       out / "results.json")
    table = report.markdown_table(analysis.rows, analysis.columns)
    # The command that renders and reports (a --collect-only run reports renders made by it).
    command = shlex.join(["python3", f"experiments/{exp.name}.py", *[a for a in args.argv if a != "--collect-only"]])
    machine = report.machine_info(prov)
    figures = [str(Path(f).relative_to(out)) if Path(f).is_relative_to(out) else str(f) for f in analysis.figures]
    sections = [("Results", table + f"\n\nAll columns: [{csv_path.name}]({csv_path.name})")] + analysis.sections
    rep = report.write_report(
        out / "report.md", title=exp.title, question=exp.question, machine=machine, settings=run_settings,
        conclusions=analysis.conclusions, sections=sections, figures=figures, command=command)
    page = html_report.write_html_report(
        out / "report.html", title=exp.title, question=exp.question, provenance=prov, machine=machine,
        settings=run_settings, conclusions=analysis.conclusions, sections=sections,
        figures=[Path(f) if Path(f).is_absolute() else out / f for f in analysis.figures],
        comparisons=analysis.comparisons, command=command)
    print(f"{exp.name}: wrote {page}")
    print(f"{exp.name}: wrote {rep}")
    for c in analysis.conclusions:
        print(f"  - {c}")
    return 0
