#!/usr/bin/env python3
"""One long render split across Slurm array tasks by sample ranges, merged bit for bit.

    python3 experiments/split_render.py SCENE --spp 4096 --tasks 16 --out DIR --submit [-- RENDER OPTIONS]
    python3 experiments/split_render.py SCENE --spp 4096 --tasks 16 --out DIR --status
    python3 experiments/split_render.py SCENE --spp 4096 --tasks 16 --out DIR --resubmit
    python3 experiments/split_render.py SCENE --spp 4096 --tasks 16 --out DIR --local

Task i renders `render SCENE --spp-range A_i:B_i --checkpoint DIR/shard_i.state`; a merge job that
runs after the whole array succeeded (--dependency=afterok) writes DIR/merged.exr with
`merge --spp N`, which refuses shards of another scene, seed or settings, overlapping, missing or
interrupted shards. --status lists the shards (and the log of each unfinished one); --resubmit
submits only the unfinished tasks (an interrupted shard resumes from its film state) and a new
merge job. --local runs the tasks and the merge here, one after another. Render options after `--`
(e.g. --seed 7 --mode rgb -D res=1024) are the same for every shard. docs/cluster.md.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from iris_experiments import slurm, split_render, tools  # noqa: E402
from iris_experiments.errors import ExperimentError  # noqa: E402


def parse_args(argv):
    argv = list(argv)
    render_args = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    p = argparse.ArgumentParser(prog="experiments/split_render.py", description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--spp", type=int, required=True, help="samples per pixel of the whole render")
    p.add_argument("--tasks", type=int, required=True, help="array tasks (sample ranges)")
    p.add_argument("--out", required=True, help="folder for scripts, shards, logs and merged.exr")
    p.add_argument("--build-dir", default=None, help="folder with render and merge (default $IRIS_BUILD_DIR or build/)")
    p.add_argument("--checkpoint-every", type=float, default=60.0,
                   help="seconds between film-state saves of a running shard (what a resubmission resumes from)")
    p.add_argument("--slurm-time", default="02:00:00", help="#SBATCH --time per task")
    p.add_argument("--slurm-cpus", type=int, default=8, help="#SBATCH --cpus-per-task (render uses as many threads)")
    p.add_argument("--slurm-mem", default="4G", help="#SBATCH --mem")
    p.add_argument("--slurm-partition", default=None, help="#SBATCH --partition")
    p.add_argument("--slurm-account", default=None, help="#SBATCH --account")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--submit", action="store_true", help="submit the array and the merge job")
    mode.add_argument("--resubmit", action="store_true", help="submit only unfinished tasks and a new merge job")
    mode.add_argument("--status", action="store_true", help="list the shards; exit 1 if any is unfinished")
    mode.add_argument("--local", action="store_true", help="run every task and the merge on this machine")
    args = p.parse_args(argv)
    args.render_args = render_args
    return args


def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        bdir = tools.build_dir(args.build_dir)
        threads = [] if "--threads" in args.render_args else ["--threads", str(args.slurm_cpus)]
        plan = split_render.SplitPlan(Path(args.scene).resolve(), args.spp, args.tasks, Path(args.out).resolve(),
                                      tools.tool("render", bdir), tools.tool("merge", bdir),
                                      tuple(args.render_args) + (() if args.local else tuple(threads)),
                                      args.checkpoint_every)
        plan.ranges()
        sbatch = dict(job_name="iris-split", time=args.slurm_time, cpus_per_task=args.slurm_cpus, mem=args.slurm_mem,
                      partition=args.slurm_partition, account=args.slurm_account)
        array, merge = (plan.out / "split_render.sh", plan.out / "merge.sh")
        if not args.status:
            split_render.write_scripts(plan, **sbatch)
        if args.local:
            for i in range(plan.tasks):
                subprocess.run(["bash", str(array)], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(i)},
                               check=True)
            subprocess.run(plan.merge_command(), check=True)
            print(f"wrote {plan.image}")
            return 0
        status = split_render.shard_status(plan)
        unfinished = [i for i, (s, _) in enumerate(status) if s != "complete"]
        if args.status or args.resubmit:
            for i, (s, detail) in enumerate(status):
                log = split_render.last_log(plan, i)
                print(f"task {i} {plan.ranges()[i][0]}:{plan.ranges()[i][1]}: {s} ({detail})" +
                      ("" if s == "complete" else f"; log {log or '(none)'}"))
                if s != "complete" and log:
                    for line in log.read_text(errors="replace").strip().splitlines()[-3:]:
                        print(f"    {line}")
            if args.status:
                return 1 if unfinished else 0
            if not unfinished:
                print("every shard is complete; nothing to resubmit (the merge: bash " + str(merge) + ")")
                return 0
        if args.submit or args.resubmit:
            ids = split_render.submit(plan, unfinished if args.resubmit else None, **sbatch)
            print(f"submitted array job {ids['array']} (tasks {','.join(map(str, ids['tasks']))}) and merge job "
                  f"{ids['merge']} (afterok:{ids['array']}); logs in {plan.log_dir}")
            return 0
        print(f"wrote {array} ({plan.tasks} array tasks) and {merge}\n"
              f"submit: jid=$(sbatch --parsable {array}); sbatch --dependency=afterok:$jid {merge}   (or --submit)")
        return 0
    except (ExperimentError, subprocess.CalledProcessError) as e:
        print(f"split_render: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
