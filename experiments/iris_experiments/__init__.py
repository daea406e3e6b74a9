"""iris experiment framework: sweeps of render jobs, local and Slurm execution, result collection,
reports and image grids. See docs/experiments.md."""

from .errors import ExperimentError  # noqa: F401
