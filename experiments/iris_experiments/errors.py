"""Errors reported to the user as one clear line (no traceback)."""


class ExperimentError(Exception):
    """Something the user must fix: a missing tool, scene, material or parameter, a failed job."""
