#!/usr/bin/env python3
"""CTest checks of the glTF test assets (tests/data/gltf/, docs/gltf.md "Test assets"):

    check_assets.py current     the committed files are exactly what make_assets.py writes
    check_assets.py validate    the Khronos glTF-Validator accepts every valid asset and finds
                                errors in every hostile one (bad_*); exit 77 (CTest: skipped)
                                when node is not installed, an error when it is but
                                `npm ci` was not run in tests/gltf
"""
import filecmp
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ASSETS = HERE.parent / "data" / "gltf"
SKIP = 77


def current() -> int:
    sys.path.insert(0, str(HERE))
    import make_assets
    with tempfile.TemporaryDirectory() as tmp:
        make_assets.main_into(tmp)
        made = sorted(p.name for p in Path(tmp).iterdir())
        committed = sorted(p.name for p in ASSETS.iterdir())
        if made != committed:
            print(f"tests/data/gltf differs from make_assets.py's output: made {made}, committed {committed}")
            return 1
        match, mismatch, errors = filecmp.cmpfiles(tmp, ASSETS, made, shallow=False)
        if mismatch or errors:
            print(f"stale assets (run python3 tests/gltf/make_assets.py): {mismatch + errors}")
            return 1
    print(f"{len(made)} passed, 0 failed")
    return 0


def validate() -> int:
    node = shutil.which("node")
    if not node:
        print("skipped: node is not installed, so the Khronos glTF-Validator cannot run")
        return SKIP
    if not (HERE / "node_modules" / "gltf-validator").is_dir():
        print("tests/gltf/node_modules/gltf-validator is missing: run `npm ci` in tests/gltf (.ci/run does)")
        return 1
    files = sorted(ASSETS.glob("*.gl*"))
    valid = [str(p) for p in files if not p.name.startswith("bad_")]
    hostile = [str(p) for p in files if p.name.startswith("bad_")]
    rc = subprocess.call([node, str(HERE / "validate.mjs"), *valid])
    rc |= subprocess.call([node, str(HERE / "validate.mjs"), "--expect-errors", *hostile])
    return rc


if __name__ == "__main__":
    sys.exit({"current": current, "validate": validate}[sys.argv[1]]())
