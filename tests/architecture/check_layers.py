#!/usr/bin/env python3
"""The folder-level include graph of iris, checked against the layers of docs/architecture.md.

Every C++ file's `#include "folder/..."` lines give edges between folders, and so does every
Python file's `import pkg` / `from pkg import ...` of one of the project's own packages (a folder
with an __init__.py under a layer folder: `iris` is apps/python/iris, `iris_experiments` is
experiments/iris_experiments). A top-level folder may
include headers of its own layer or of lower layers only (the table in docs/architecture.md,
section "Layers", gives each folder its layer); and the graph of sub-folders (core/io, render/lights,
...) must have no cycle. Prints the graph (folders in layer order, each with the folders it
includes) and exits 1 listing every upward edge or cycle, with the include lines that make it.

    python3 tests/architecture/check_layers.py [--root DIR] [--dot]
"""
import argparse
import os
import re
import sys
from collections import defaultdict

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
PY_IMPORT = re.compile(r'^\s*(?:from\s+([A-Za-z_]\w*)[\w.]*\s+import\b|import\s+([A-Za-z_]\w*))', re.M)
LAYER_ROW = re.compile(r'^\|\s*(\d+)\s*\|\s*`([\w./-]+)/`\s*\|', re.M)
SOURCE_EXT = ('.h', '.hpp', '.cpp', '.cc', '.inl')


def read_layers(root):
    path = os.path.join(root, 'docs', 'architecture.md')
    with open(path, encoding='utf-8') as f:
        text = f.read()
    layers = {folder: int(rank) for rank, folder in LAYER_ROW.findall(text)}
    if not layers:
        sys.exit(f'{path}: no layer table found (rows "| <layer> | `folder/` | ... |")')
    return layers


def source_files(root, layers):
    for top in layers:
        base = os.path.join(root, top)
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = [d for d in dirnames if d not in ('results', 'corpus', '__pycache__', 'testdata')]
            for name in filenames:
                if name.endswith(SOURCE_EXT):
                    yield os.path.relpath(os.path.join(dirpath, name), root)


def python_packages(root, layers):
    """Package name -> its folder (relative to root), for every folder with an __init__.py."""
    packages = {}
    for top in layers:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = [d for d in dirnames if d not in ('results', 'corpus', '__pycache__', 'testdata', 'node_modules')]
            if '__init__.py' in filenames:
                packages[os.path.basename(dirpath)] = os.path.relpath(dirpath, root)
    return packages


def python_files(root, layers):
    for top in layers:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames[:] = [d for d in dirnames if d not in ('results', 'corpus', '__pycache__', 'testdata', 'node_modules')]
            for name in filenames:
                if name.endswith('.py'):
                    yield os.path.relpath(os.path.join(dirpath, name), root)


def folder_of(path):
    """'render/lights/area_light.h' -> 'render/lights'; 'core/math.h' -> 'core'."""
    return os.path.dirname(path) or '.'


def top_of(path):
    return path.split('/', 1)[0]


def find_cycle(graph):
    """One cycle of a directed graph as a list of nodes, or None (iterative DFS)."""
    color = {}
    for start in sorted(graph):
        if color.get(start):
            continue
        stack = [(start, iter(sorted(graph[start])))]
        color[start] = 1
        path = [start]
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                color[node] = 2
                stack.pop()
                path.pop()
                continue
            if color.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if not color.get(nxt):
                color[nxt] = 1
                path.append(nxt)
                stack.append((nxt, iter(sorted(graph.get(nxt, ())))))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--root', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
    ap.add_argument('--dot', action='store_true', help='print the top-level graph in Graphviz dot syntax')
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    layers = read_layers(root)

    top_edges = defaultdict(list)   # (from, to) -> [file:line: include]
    sub_graph = defaultdict(set)
    sub_why = defaultdict(list)
    problems = []
    for rel in source_files(root, layers):
        with open(os.path.join(root, rel), encoding='utf-8', errors='replace') as f:
            text = f.read()
        for m in INCLUDE.finditer(text):
            inc = m.group(1)
            if '/' not in inc:
                continue
            target_top = top_of(inc)
            if target_top not in layers:
                continue  # a system or third-party header written with quotes
            if not os.path.exists(os.path.join(root, inc)):
                line = text.count('\n', 0, m.start()) + 1
                problems.append(f'{rel}:{line}: includes "{inc}", which does not exist')
                continue
            line = text.count('\n', 0, m.start()) + 1
            src_top = top_of(rel)
            if src_top != target_top:
                top_edges[(src_top, target_top)].append(f'{rel}:{line}: #include "{inc}"')
            a, b = folder_of(rel), folder_of(inc)
            if a != b:
                sub_graph[a].add(b)
                sub_why[(a, b)].append(f'{rel}:{line}')

    packages = python_packages(root, layers)
    for rel in python_files(root, layers):
        with open(os.path.join(root, rel), encoding='utf-8', errors='replace') as f:
            text = f.read()
        for m in PY_IMPORT.finditer(text):
            name = m.group(1) or m.group(2)
            if name not in packages:
                continue  # the standard library, NumPy, or a module of the file's own folder
            target = packages[name]
            line = text.count('\n', 0, m.start()) + 1
            src_top, target_top = top_of(rel), top_of(target)
            if src_top != target_top:
                top_edges[(src_top, target_top)].append(f'{rel}:{line}: import {name}')

    for (a, b), why in sorted(top_edges.items()):
        if layers[b] > layers[a]:
            problems.append(f'upward edge {a}/ (layer {layers[a]}) -> {b}/ (layer {layers[b]}):\n    ' + '\n    '.join(why))
        elif layers[b] == layers[a]:
            problems.append(f'edge between two folders of layer {layers[a]}: {a}/ -> {b}/:\n    ' + '\n    '.join(why))
    cycle = find_cycle(sub_graph)
    if cycle:
        steps = [f'{x}/ -> {y}/ ({", ".join(sub_why[(x, y)][:3])})' for x, y in zip(cycle, cycle[1:])]
        problems.append('cycle between folders:\n    ' + '\n    '.join(steps))

    order = sorted(layers, key=lambda f: (layers[f], f))
    if args.dot:
        print('digraph layers {\n  rankdir=BT;')
        for (a, b) in sorted(top_edges):
            print(f'  "{a}" -> "{b}";')
        print('}')
    else:
        print('Folder include graph (layer: folder -> folders it includes):')
        for f in order:
            deps = sorted({b for (a, b) in top_edges if a == f}, key=lambda x: (layers[x], x))
            print(f'  {layers[f]}: {f + "/":14s} -> {", ".join(d + "/" for d in deps) or "(nothing)"}')
    if problems:
        print(f'\n{len(problems)} problem(s):', file=sys.stderr)
        for p in problems:
            print('  ' + p, file=sys.stderr)
        return 1
    print('OK: every include goes to the same or a lower layer; no folder cycle.')
    return 0


if __name__ == '__main__':
    sys.exit(main())
