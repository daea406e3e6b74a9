#!/usr/bin/env python3
"""Docs name only what exists: every repository path (in backticks or in prose) and every
`name()` / `Scope::name` in backticks.

Scans README.md and docs/*.md (and the other Markdown files given with --also). A backtick span
is checked when it is
  * a repository path: no spaces, a '/' in it, and its first component a top-level folder of the
    repository (or '..' from the document's folder) — it must exist. A trailing '/' means a folder;
    '*' and '<...>' are wildcards (`thin_film_airy*`, `tests/<layer>/`), `{h,cpp}` expands to each
    alternative, and a path without extension names the files it starts (`spectral/thin_film_stack`
    for thin_film_stack.h and .cpp). Paths under build/ (what a build writes) are not checked, and bare
    file names (`out.exr`, `report.md`) are outputs, not repository paths;
  * a call-like name `name()` (arguments allowed): the identifier must be defined or used somewhere
    in the C++ or Python sources;
  * a scoped name `Scope::name` or `Scope::name()`: `name` must occur in a file that declares the
    class, struct, enum or namespace `Scope` (or the text `Scope::name` must occur in a source), so
    that a free function is not documented as a member.
Outside backticks, a word that starts with a top-level folder and a '/' (`render/film.h` written as
render/film.h in a sentence) is checked as a path too.
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
SCOPED = re.compile(r'^((?:[A-Za-z_]\w*::)+)([A-Za-z_]\w*)(?:\((?:[^()]*)\))?$')
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


def scope_index(root):
    """For each class/struct/enum/namespace name, the set of identifiers of the files declaring it;
    and the text of all sources (for a literal `Scope::name`)."""
    decl = re.compile(r'\b(?:class|struct|enum(?:\s+class)?|namespace)\s+([A-Za-z_]\w*)')
    scopes, texts = {}, []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if d not in SKIP_DIRS and not d.startswith('build')]
        for name in filenames:
            if name.endswith(SOURCE_EXT):
                with open(os.path.join(dirpath, name), encoding='utf-8', errors='replace') as f:
                    text = f.read()
                if not name.endswith('.py'):  # comments may mention a name without declaring it
                    text = re.sub(r'//[^\n]*|/\*.*?\*/', ' ', text, flags=re.S)
                texts.append(text)
                words = None
                for scope in set(decl.findall(text)):
                    words = words if words is not None else set(re.findall(r'[A-Za-z_]\w*', text))
                    scopes.setdefault(scope, set()).update(words)
    return scopes, '\n'.join(texts)


def scoped_name_exists(scope_chain, name, scopes, all_text):
    """True when the name is there, or when the scope is not iris's (std::, another project's class:
    such names are cited, not checked)."""
    if f'{scope_chain}{name}' in all_text:
        return True
    innermost = scope_chain.rstrip(':').split('::')[-1]
    return innermost not in scopes or name in scopes[innermost]


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


def prose_paths(line, tops):
    """Paths written outside backticks: words starting with a top-level folder and a '/'."""
    text = SPAN.sub(' ', line)
    text = re.sub(r'\]\([^)]*\)', ' ', text)   # Markdown link targets (relative to the document)
    text = re.sub(r'https?://\S+', ' ', text)
    pattern = re.compile(r'(?<![\w/.`-])((?:' + '|'.join(re.escape(t) for t in sorted(tops)) + r')/[\w./*<>{},+-]*)')
    out = []
    for m in pattern.finditer(text):
        span = m.group(1).rstrip('.,;:)')
        if looks_like_path(span, tops):
            out.append(span)
    return out


def check_file(path, root, tops, idents, scopes=None, all_text=''):
    problems = []
    doc_dir = os.path.dirname(path)
    in_fence = False
    with open(path, encoding='utf-8') as f:
        for lineno, line in enumerate(f, 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence or line.startswith('    '):  # fenced or indented code: examples, not references
                continue
            for span in prose_paths(line, tops):
                if not path_exists(span, doc_dir, root):
                    problems.append(f'{os.path.relpath(path, root)}:{lineno}: {span}: no such file or folder')
            for span in SPAN.findall(line):
                span = span.strip()
                call = CALL.match(span)
                scoped = SCOPED.match(span)
                if scoped and scopes is not None:
                    if not scoped_name_exists(scoped.group(1), scoped.group(2), scopes, all_text):
                        problems.append(f'{os.path.relpath(path, root)}:{lineno}: `{span}`: no {scoped.group(2)} in '
                                        f'{scoped.group(1).rstrip(":")}')
                elif call and ' ' not in span.split('(')[0]:
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
    scopes, all_text = scope_index(root)
    problems = []
    for d in docs:
        if os.path.exists(d):
            problems += check_file(d, root, tops, idents, scopes, all_text)
    if problems:
        print(f'{len(problems)} stale name(s) in the docs:', file=sys.stderr)
        for p in problems:
            print('  ' + p, file=sys.stderr)
        return 1
    print(f'OK: every path, name() and Scope::name in {len(docs)} documents exists.')
    return 0


if __name__ == '__main__':
    sys.exit(main())
