#!/usr/bin/env python3
"""Docs name only what exists: every repository path and every `name()` in backticks.

Scans README.md and docs/*.md (and the other Markdown files given with --also). A backtick span
is checked when it is
  * a repository path: no spaces, a '/' in it, and its first component a top-level folder of the
    repository (or '..' from the document's folder) — it must exist. A trailing '/' means a folder;
    '*' and '<...>' are wildcards (`thin_film_airy*`, `tests/<layer>/`), `{h,cpp}` expands to each
    alternative, and a path without extension names the files it starts (`spectral/thin_film_stack`
    for thin_film_stack.h and .cpp). Paths under build/ (what a build writes) are not checked, and bare
    file names (`out.exr`, `report.md`) are outputs, not repository paths;
  * a call-like name `name()` or `Scope::name()` (arguments allowed): the last identifier must be
    defined or used somewhere in the C++ or Python sources.
Command lines (spans with spaces), URLs and option names are not paths and are skipped.
Exits 1 listing file:line: problem for each miss.

    python3 tests/architecture/check_docs.py [--root DIR]
"""
import argparse
import glob
import os
import re
import sys

SPAN = re.compile(r'(?<!`)`([^`\n]+)`(?!`)')
FENCE = re.compile(r'^\s*```')
PATH_EXT = ('.h', '.cpp', '.py', '.md', '.xml', '.exr', '.png', '.ply', '.obj', '.spd', '.csv', '.json',
            '.ocio', '.txt', '.sh', '.serialized', '.html', '.js', '.pyi', '.vol', '.cmake')
CALL = re.compile(r'^(?:[A-Za-z_]\w*(?:::|\.))*([A-Za-z_]\w*)\((?:[^()]*)\)$')
SOURCE_EXT = ('.h', '.cpp', '.py', '.pyi')
SKIP_DIRS = {'.git', 'build', 'results', '__pycache__', 'corpus', 'node_modules'}


def source_identifiers(root):
    words = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if d not in SKIP_DIRS and not d.startswith('build')]
        for name in filenames:
            if name.endswith(SOURCE_EXT) or name == 'CMakeLists.txt':
                with open(os.path.join(dirpath, name), encoding='utf-8', errors='replace') as f:
                    words.update(re.findall(r'[A-Za-z_]\w*', f.read()))
    return words


def top_folders(root):
    return {d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)) and not d.startswith('.')} | {'.ci'}


def looks_like_path(span, tops):
    if ' ' in span or '://' in span or '=' in span or '/' not in span:
        return False
    first = span.split('/', 1)[0]
    return (first in tops or first == '..') and first != 'build' and re.fullmatch(r'[\w./*<>{},+-]+', span) is not None


def expand_braces(s):
    m = re.search(r'\{([^{}]*)\}', s)
    if not m:
        return [s]
    return [x for alt in m.group(1).split(',') for x in expand_braces(s[:m.start()] + alt + s[m.end():])]


def path_exists(span, doc_dir, root):
    for rel in expand_braces(span.rstrip('/')):
        pattern = re.sub(r'<[^>]*>', '*', rel)
        found = False
        for base in (root, doc_dir):
            cand = os.path.join(base, pattern)
            has_ext = '.' in os.path.basename(pattern)
            if glob.glob(cand) or (not has_ext and glob.glob(cand + '.*')):
                found = True
                break
        if not found:
            return False
    return True


def check_file(path, root, tops, idents):
    problems = []
    doc_dir = os.path.dirname(path)
    in_fence = False
    with open(path, encoding='utf-8') as f:
        for lineno, line in enumerate(f, 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            for span in SPAN.findall(line):
                span = span.strip()
                call = CALL.match(span)
                if call and ' ' not in span.split('(')[0]:
                    if call.group(1) not in idents:
                        problems.append(f'{os.path.relpath(path, root)}:{lineno}: `{span}`: no {call.group(1)} in the sources')
                elif looks_like_path(span, tops) and not path_exists(span, doc_dir, root):
                    problems.append(f'{os.path.relpath(path, root)}:{lineno}: `{span}`: no such file or folder')
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--root', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
    ap.add_argument('--also', nargs='*', default=[], help='more Markdown files to check')
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    docs = [os.path.join(root, 'README.md')] + sorted(glob.glob(os.path.join(root, 'docs', '*.md')))
    docs += [os.path.abspath(a) for a in args.also]
    tops = top_folders(root)
    idents = source_identifiers(root)
    problems = []
    for d in docs:
        if os.path.exists(d):
            problems += check_file(d, root, tops, idents)
    if problems:
        print(f'{len(problems)} stale name(s) in the docs:', file=sys.stderr)
        for p in problems:
            print('  ' + p, file=sys.stderr)
        return 1
    print(f'OK: every path and name() in backticks in {len(docs)} documents exists.')
    return 0


if __name__ == '__main__':
    sys.exit(main())
