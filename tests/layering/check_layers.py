#!/usr/bin/env python3
"""Checks that every #include in the libraries follows the declared layers.

The layers are declared once, in docs/architecture.md, section "Libraries and folders":

  * the library table (| library | folder | may use | GL |): which libraries a library may
    include from (optionally only some folders: "sylva_core: base geo model scene") and
    whether it may include GL headers (GL/, GLES*, EGL/, GLFW/, glad/, KHR/, imgui);
  * the folder table (| folder | holds |), in pipeline order: a file may include headers of
    its own folder and of the folders above it in the same library, never below.

Every C++ file under a library's folder must lie in a listed folder. Public headers are
"sylva/core/<folder>/X.h" (core/include/...), "sylva/render/<folder>/X.h" (render/include/...),
"sylva/dsl/X.h" and "sylva/bench/X.h"; a quoted include without the "sylva/" prefix is a
private header resolved against the including file's directory.

Usage: check_layers.py ROOT      exit 0 when clean, 1 with one line per violation.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
GL_HEADERS = re.compile(r'^(GL/|GLES|EGL/|GLFW/|glad/|KHR/|imgui|backends/imgui)')


def table_rows(text, header):
    """Rows (lists of cells) of the markdown table whose header row starts with `header`."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if line.lstrip().startswith('|') and cells[:len(header)] == header:
            rows = []
            for row in lines[i + 2:]:
                if not row.lstrip().startswith('|'):
                    break
                rows.append([c.strip().strip('`') for c in row.strip().strip('|').split('|')])
            return rows
    return None


def parse_layers(root):
    path = os.path.join(root, 'docs', 'architecture.md')
    with open(path, encoding='utf-8') as fh:
        text = fh.read()
    libraries = table_rows(text, ['library', 'folder', 'may use', 'GL'])
    folders = table_rows(text, ['folder', 'holds'])
    if libraries is None or folders is None:
        sys.exit(f'{path}: the library table (| library | folder | may use | GL |) or the '
                 'folder table (| folder | holds |) is missing')
    libs = {}
    for name, folder, may_use, gl in (row[:4] for row in libraries):
        uses = {}
        for part in re.split(r',\s*(?=sylva)', may_use):
            part = part.strip()
            if not part or part in ('–', '-'):
                continue
            lib, _, only = part.partition(':')
            uses[lib.strip()] = only.split() or None  # None: every folder
        libs[name] = {'folder': folder.rstrip('/'), 'uses': uses, 'gl': gl.lower() == 'yes'}
    order = [row[0].rstrip('/') for row in folders]
    return libs, order


def library_of(folder, libs):
    for name, lib in libs.items():
        if folder == lib['folder'] or folder.startswith(lib['folder'] + '/'):
            return name
    return None


def folder_of_header(include, including_dir, root):
    """The source-tree folder a quoted include belongs to, or None for non-project headers."""
    m = re.match(r'sylva/(core|render)/(.+)/[^/]+$', include)
    if m:
        return f'{m.group(1)}/{m.group(2)}'
    m = re.match(r'sylva/(dsl|bench)/[^/]+$', include)
    if m:
        return m.group(1)
    if include.startswith('sylva/'):
        return 'unknown:' + include
    local = os.path.normpath(os.path.join(including_dir, include))
    if os.path.exists(os.path.join(root, local)):
        return os.path.dirname(local)
    return None


def source_folder(path):
    """core/include/sylva/core/x/Y.h -> core/x; render/include/sylva/render/x/Y.h -> render/x."""
    m = re.match(r'(core|render)/include/sylva/\1/(.+)/[^/]+$', path)
    if m:
        return f'{m.group(1)}/{m.group(2)}'
    m = re.match(r'(dsl|bench)/include/sylva/\1/[^/]+$', path)
    if m:
        return m.group(1)
    return os.path.dirname(path)


def check(root):
    libs, order = parse_layers(root)
    position = {folder: i for i, folder in enumerate(order)}
    problems = []
    for lib in libs.values():
        base = os.path.join(root, lib['folder'])
        for directory, _, names in os.walk(base):
            for name in sorted(names):
                if not name.endswith(('.h', '.cpp')):
                    continue
                path = os.path.relpath(os.path.join(directory, name), root)
                problems += check_file(root, path, libs, position)
    return problems


def check_file(root, path, libs, position):
    problems = []
    folder = source_folder(path)
    lib = library_of(folder, libs)
    if folder not in position:
        return [f'{path}: folder {folder}/ is not in the folder table of docs/architecture.md']
    with open(os.path.join(root, path), encoding='utf-8', errors='replace') as fh:
        lines = fh.readlines()
    for number, line in enumerate(lines, 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        bracket, include = m.groups()
        where = f'{path}:{number}'
        if GL_HEADERS.match(include):
            if not libs[lib]['gl']:
                problems.append(f'{where}: {lib} may not include GL headers (<{include}>)')
            continue
        if bracket == '<':
            continue
        target = folder_of_header(include, os.path.dirname(path), root)
        if target is None:
            continue
        if target.startswith('unknown:') or target not in position:
            problems.append(f'{where}: "{include}" is in no folder of the table')
            continue
        target_lib = library_of(target, libs)
        if target_lib == lib:
            if position[target] > position[folder]:
                problems.append(f'{where}: {folder}/ includes "{include}" from {target}/, '
                                f'which comes after it in the pipeline order')
        elif target_lib not in libs[lib]['uses']:
            problems.append(f'{where}: {lib} may not use {target_lib} ("{include}")')
        else:
            only = libs[lib]['uses'][target_lib]
            short = target.split('/', 1)[1] if '/' in target else target
            if only is not None and short not in only:
                problems.append(f'{where}: {lib} may use only {", ".join(only)} of {target_lib}, '
                                f'not {target}/ ("{include}")')
    return problems


def main():
    if len(sys.argv) != 2:
        sys.exit('usage: check_layers.py ROOT')
    problems = check(sys.argv[1])
    for problem in problems:
        print(problem)
    if problems:
        print(f'{len(problems)} include(s) against the layers of docs/architecture.md')
        return 1
    print('every include follows the layers of docs/architecture.md')
    return 0


if __name__ == '__main__':
    sys.exit(main())
