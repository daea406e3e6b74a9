#!/usr/bin/env python3
"""No plugin reads the scene's format version (issue 39, item 4).

The upgrade pass (render/loader/scene_upgrade.cpp) is the one place that turns a scene file's
`version` into what plugins read: spelling rewritten, defaults filled, and the choice between
Mitsuba 0.6's and Mitsuba 3's models written as `convention` parameters (core/mitsuba_convention.h).
This check lists every call of Properties::formatVersion() in the source folders of
docs/architecture.md's layer table (tests excluded: they may look at it) outside the pass and the
definition, and exits 1 naming file and line of each.

    python3 tests/architecture/check_format_version.py [--root DIR]
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_layers import read_layers, source_files  # noqa: E402

CALL = re.compile(r'\bformatVersion\s*\(\s*\)')
ALLOWED = {'render/loader/scene_upgrade.cpp', 'core/properties.h'}


def readers(root):
    layers = {folder: rank for folder, rank in read_layers(root).items() if folder != 'tests'}
    for rel in sorted(source_files(root, layers)):
        if rel.replace(os.sep, '/') in ALLOWED:
            continue
        with open(os.path.join(root, rel), encoding='utf-8', errors='replace') as f:
            for number, line in enumerate(f, 1):
                if CALL.search(line):
                    yield rel, number, line.strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--root', default=os.path.join(os.path.dirname(__file__), '..', '..'))
    args = parser.parse_args()
    found = list(readers(os.path.abspath(args.root)))
    for rel, number, line in found:
        print(f'{rel}:{number}: reads the format version ({line}); let the upgrade pass '
              f'(render/loader/scene_upgrade.cpp) write a parameter the plugin reads instead')
    if found:
        sys.exit(1)
    print('no plugin reads Properties::formatVersion()')


if __name__ == '__main__':
    main()
