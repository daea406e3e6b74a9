"""Local execution of render jobs, N at a time. Existing outputs are kept (resume) unless forced;
each job's stdout/stderr goes to <output>.log."""
from __future__ import annotations

import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

from . import exr
from .tools import REPO


def output_ok(job) -> bool:
    """Whether a job's output counts as done: it exists, is a readable EXR (render writes EXRs
    atomically, so a killed task leaves none or a whole one) and is not an interrupted render
    (iris.interrupted = 1: render stopped by a signal writes the samples done so far)."""
    if not job.output.exists():
        return False
    if job.output.suffix != ".exr":
        return True
    try:
        return exr.read_exr_metadata(str(job.output)).get("iris.interrupted", "0") != "1"
    except (exr.ExrError, OSError, ValueError):
        return False


@dataclass
class JobResult:
    job: object
    returncode: int
    seconds: float
    skipped: bool = False
    message: str = ""       # last stderr line of a failed job

    @property
    def ok(self) -> bool:
        return self.returncode == 0


def run_job(job, force: bool = False, timeout: float | None = None) -> JobResult:
    if output_ok(job) and not force:
        return JobResult(job, 0, 0.0, skipped=True)
    job.output.parent.mkdir(parents=True, exist_ok=True)
    log = job.output.with_suffix(".log")
    start = time.monotonic()
    try:
        proc = subprocess.run(job.command, cwd=REPO, capture_output=True, text=True, timeout=timeout)
        code, out, err = proc.returncode, proc.stdout, proc.stderr
    except subprocess.TimeoutExpired as e:
        code, out, err = 124, str(e.stdout or ""), f"timed out after {timeout} s"
    except OSError as e:
        code, out, err = 127, "", f"{job.command[0]}: {e.strerror}"
    seconds = time.monotonic() - start
    log.write_text(f"$ {job.shell()}\n# exit {code}, {seconds:.2f} s\n{out}{err}")
    lines = [l for l in err.strip().splitlines() if l.strip()]
    message = lines[-1] if lines else ""
    if code == 0 and not job.output.exists():
        code, message = 1, f"{job.output}: the command succeeded but wrote no image"
    return JobResult(job, code, seconds, message=message)


def run_local(jobs, parallel: int = 1, force: bool = False, timeout: float | None = None, log=print) -> list:
    """Run every job (parallel at a time); returns JobResults in job order."""
    results = [None] * len(jobs)

    def work(i):
        r = run_job(jobs[i], force, timeout)
        status = "skip (exists)" if r.skipped else ("ok" if r.ok else f"FAILED ({r.returncode}): {r.message}")
        log(f"[{i + 1}/{len(jobs)}] {jobs[i].output.name} {jobs[i].label}: {status} {r.seconds:.1f} s")
        results[i] = r

    with ThreadPoolExecutor(max_workers=max(1, parallel)) as pool:
        list(pool.map(work, range(len(jobs))))
    return results
