"""Shared by the Python module's tests: the build folder, the package and the C++ reference."""
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("IRIS_BUILD_DIR", REPO / "build"))
if str(BUILD / "python") not in sys.path:
    sys.path.insert(0, str(BUILD / "python"))

import numpy as np  # noqa: E402

import iris  # noqa: E402


def reference(queries):
    """Exact C++ values (tests/python/reference/python_reference.cpp) for a list of query lines."""
    proc = subprocess.run([str(BUILD / "python_reference")], input="\n".join(queries) + "\n", capture_output=True,
                          text=True, check=False)
    lines = proc.stdout.splitlines()
    if proc.returncode != 0:
        raise RuntimeError(f"python_reference failed: {lines[-1] if lines else proc.stderr}")
    return [np.array([float.fromhex(x) for x in line.split()]) for line in lines]


def num(x) -> str:
    """A number as text that parses back to the same double (repr is the shortest round trip)."""
    return repr(float(x))
