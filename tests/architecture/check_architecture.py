#!/usr/bin/env python3
"""The layering of the library, checked from the code's own #include lines.

    python3 tests/architecture/check_architecture.py [REPO_ROOT]     check the repository (exit 1 on a violation)
    python3 tests/architecture/check_architecture.py --self-test     show that every rule catches what it forbids

Rules (docs/design.md, "Folders and layers"):
  1. A core folder of plugin/BulletBuoyancy/ includes nothing of Bullet (its headers, nor the Bullet layer).
  2. A core folder includes only core folders before it in the data flow (CORE_ORDER: state, geometry, mesh, water,
     atlas, bake, integrals, temporal, graph); the Bullet layer may include any core folder.
  3. Every include of one of the library's headers, anywhere in the repository (library, examples, tests, fuzz
     targets), is written <BulletBuoyancy/folder/File.h>.
  4. No two folders include each other, directly or around a longer circle (library and examples alike).
  5. Every test source (a .cpp below tests/ that defines Catch test cases) is named <Unit>Test.cpp.
  6. A device backend (bullet/opencl/, bullet/btOpenClBuoyancyBackend*) does not include the action: it sees bodies
     through btBuoyancyDeviceBody (bullet/btBuoyancyDeviceBackend.h).
"""
import os
import re
import sys
import tempfile

# The core, in the order of the data flow: a folder may include itself and the folders before it. `state` (the
# saved-state byte format) comes first: every later stage may save and restore through it.
CORE_ORDER = ['state', 'geometry', 'mesh', 'water', 'atlas', 'bake', 'integrals', 'temporal', 'graph']
# The Bullet layer: every file that includes Bullet lives here.
BULLET_LAYER = 'bullet'
LIBRARY_ROOT = os.path.join('plugin', 'BulletBuoyancy')
# The device backend's files (rule 6) and the header they must not include.
DEVICE_BACKEND = re.compile(r'^plugin/BulletBuoyancy/bullet/(opencl/|btOpenClBuoyancyBackend)')
ACTION_HEADER = 'BulletBuoyancy/bullet/btBuoyancyAction.h'
# Where the library's headers are included from (the library itself and everything built on it).
SCANNED = ['plugin', 'bullet_examples', 'tests', 'fuzz']
SOURCE_EXT = ('.h', '.hpp', '.cpp', '.inl')
BULLET_INCLUDE = re.compile(
    r'^(btBulletDynamicsCommon\.h|btBulletCollisionCommon\.h|LinearMath/|BulletDynamics/|BulletCollision/|'
    r'BulletSoftBody/|BulletInverseDynamics/|Bullet3[A-Za-z]*/)')
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def source_files(root, top):
    base = os.path.join(root, top)
    for d, dirs, files in os.walk(base):
        dirs[:] = sorted(x for x in dirs if not x.startswith('.'))
        for f in sorted(files):
            if f.endswith(SOURCE_EXT):
                yield os.path.join(d, f)


def library_folder(root, path):
    """'mesh' for plugin/BulletBuoyancy/mesh/X.h (the first folder below the include root), else None."""
    rel = os.path.relpath(path, os.path.join(root, LIBRARY_ROOT))
    if rel.startswith('..'):
        return None
    parts = rel.split(os.sep)
    return parts[0] if len(parts) > 1 else ''


def folder_of(root, path):
    """The folder a file counts in for the circle check: library folders by name, others by their path."""
    lib = library_folder(root, path)
    if lib is not None:
        return 'BulletBuoyancy/' + lib
    return os.path.dirname(os.path.relpath(path, root))


def check(root):
    problems = []
    lib_root = os.path.join(root, LIBRARY_ROOT)
    if not os.path.isdir(lib_root):
        return ['%s: missing (the include root of the library)' % LIBRARY_ROOT]
    for folder in sorted(os.listdir(lib_root)):
        if os.path.isdir(os.path.join(lib_root, folder)) and folder not in CORE_ORDER and folder != BULLET_LAYER:
            problems.append('%s/%s: a folder the layering does not know (add it to CORE_ORDER or move it)'
                            % (LIBRARY_ROOT, folder))
    edges = {}
    for top in SCANNED:
        for path in source_files(root, top):
            rel = os.path.relpath(path, root)
            text = open(path, encoding='utf-8', errors='replace').read()
            src_lib = library_folder(root, path)
            for m in INCLUDE.finditer(text):
                quote, inc = m.group(1), m.group(2)
                line = text.count('\n', 0, m.start()) + 1
                where = '%s:%d: #include %s%s%s' % (rel, line, quote, inc, '"' if quote == '"' else '>')
                if DEVICE_BACKEND.match(rel.replace(os.sep, '/')) and inc == ACTION_HEADER:
                    problems.append('%s: a device backend includes the action; use btBuoyancyDeviceBody' % where)
                target = None
                if inc.startswith('BulletBuoyancy/'):
                    cand = os.path.join(root, 'plugin', inc)
                    if os.path.isfile(cand):
                        target = cand
                    elif src_lib is not None and not inc.endswith('KernelSource.h'):
                        problems.append('%s: no such library header' % where)
                else:
                    # Rule 3: the library's headers are never reached another way.
                    for cand in (os.path.join(lib_root, inc), os.path.join(os.path.dirname(path), inc)):
                        if os.path.isfile(cand) and library_folder(root, cand) is not None:
                            problems.append('%s: write it <%s>'
                                            % (where, os.path.relpath(cand, os.path.join(root, 'plugin'))))
                            target = cand
                            break
                if src_lib is not None and src_lib not in (BULLET_LAYER, ''):  # '' = the umbrella header
                    # Rules 1 and 2, for the core.
                    if BULLET_INCLUDE.match(inc):
                        problems.append('%s: the core (%s/) includes Bullet; move the file to %s/'
                                        % (where, src_lib, BULLET_LAYER))
                    if target is not None:
                        dst = library_folder(root, target)
                        if dst == BULLET_LAYER:
                            problems.append('%s: the core (%s/) includes the Bullet layer' % (where, src_lib))
                        elif src_lib in CORE_ORDER and dst in CORE_ORDER and \
                                CORE_ORDER.index(dst) > CORE_ORDER.index(src_lib):
                            problems.append('%s: %s/ includes %s/, a later stage of the data flow'
                                            % (where, src_lib, dst))
                if target is None:
                    local = os.path.join(os.path.dirname(path), inc)
                    for cand in (local, os.path.join(root, inc), os.path.join(root, 'bullet_examples', inc),
                                 os.path.join(root, 'tests', inc)):
                        if os.path.isfile(cand) and not inc.startswith('BulletBuoyancy/'):
                            target = cand
                            break
                if target is not None:
                    a, b = folder_of(root, path), folder_of(root, target)
                    if a != b:
                        edges.setdefault(a, {}).setdefault(b, where)
    # Rule 5: one naming style for the test sources.
    for path in source_files(root, 'tests'):
        name = os.path.basename(path)
        if name.endswith('.cpp') and not name.endswith('Test.cpp') and \
                re.search(r'^\s*(TEST_CASE|SCENARIO|TEMPLATE_TEST_CASE)\s*\(', open(path, encoding='utf-8',
                                                                             errors='replace').read(), re.M):
            problems.append('%s: a test source is named <Unit>Test.cpp' % os.path.relpath(path, root))
    # Rule 4: circles between folders (Tarjan's strongly connected components).
    for comp in strongly_connected(edges):
        if len(comp) > 1:
            ties = []
            for a in sorted(comp):
                for b, where in sorted(edges.get(a, {}).items()):
                    if b in comp:
                        ties.append('  %s -> %s (e.g. %s)' % (a, b, where))
            problems.append('folders include each other in a circle: %s\n%s' % (', '.join(sorted(comp)),
                                                                                '\n'.join(ties)))
    return problems


def strongly_connected(edges):
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    nodes = set(edges)
    for targets in edges.values():
        nodes.update(targets)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            out.append(comp)

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


def self_test():
    """Builds small trees, each breaking one rule, and checks that exactly that rule is reported."""
    def tree(files):
        d = tempfile.mkdtemp(prefix='architecture-')
        for rel, text in files.items():
            p = os.path.join(d, rel)
            os.makedirs(os.path.dirname(p), exist_ok=True)
            open(p, 'w').write(text)
        return d
    good = {
        'plugin/BulletBuoyancy/mesh/TriangleMesh.h': '#pragma once\n#include <vector>\n',
        'plugin/BulletBuoyancy/integrals/Sum.h': '#include <BulletBuoyancy/mesh/TriangleMesh.h>\n',
        'plugin/BulletBuoyancy/bullet/btAction.h':
            '#include <BulletBuoyancy/integrals/Sum.h>\n#include <LinearMath/btVector3.h>\n',
        'bullet_examples/cli/Main.cpp': '#include <BulletBuoyancy/bullet/btAction.h>\n',
    }
    cases = {
        'core includes Bullet': ({'plugin/BulletBuoyancy/mesh/Bad.cpp': '#include <btBulletDynamicsCommon.h>\n'},
                                 'the core (mesh/) includes Bullet'),
        'core includes the Bullet layer': ({'plugin/BulletBuoyancy/integrals/Bad.cpp':
                                            '#include <BulletBuoyancy/bullet/btAction.h>\n'},
                                           'the core (integrals/) includes the Bullet layer'),
        'later stage': ({'plugin/BulletBuoyancy/mesh/Bad.cpp': '#include <BulletBuoyancy/integrals/Sum.h>\n'},
                        'mesh/ includes integrals/, a later stage'),
        'integrals includes temporal': ({'plugin/BulletBuoyancy/temporal/History.h':
                                         '#include <BulletBuoyancy/integrals/Sum.h>\n',
                                         'plugin/BulletBuoyancy/integrals/Bad.cpp':
                                         '#include <BulletBuoyancy/temporal/History.h>\n'},
                                        'integrals/ includes temporal/, a later stage'),
        'state includes a stage': ({'plugin/BulletBuoyancy/state/Bad.cpp':
                                    '#include <BulletBuoyancy/mesh/TriangleMesh.h>\n'},
                                   'state/ includes mesh/, a later stage'),
        'device backend includes the action': ({'plugin/BulletBuoyancy/bullet/btBuoyancyAction.h': '#pragma once\n',
                                                'plugin/BulletBuoyancy/bullet/opencl/Bad.cpp':
                                                '#include <BulletBuoyancy/bullet/btBuoyancyAction.h>\n'},
                                               'a device backend includes the action'),
        'include root': ({'tests/mesh/BadTest.cpp': '#include "mesh/TriangleMesh.h"\n'},
                         'write it <BulletBuoyancy/mesh/TriangleMesh.h>'),
        'same-folder include': ({'plugin/BulletBuoyancy/mesh/Bad.cpp': '#include "TriangleMesh.h"\n'},
                                'write it <BulletBuoyancy/mesh/TriangleMesh.h>'),
        'unknown folder': ({'plugin/BulletBuoyancy/misc/X.h': '#pragma once\n'}, 'a folder the layering does not know'),
        'circle': ({'bullet_examples/a/A.h': '#include "b/B.h"\n', 'bullet_examples/b/B.h': '#include "a/A.h"\n'},
                   'folders include each other in a circle'),
        'test naming': ({'tests/mesh/test_mesh.cpp': 'TEST_CASE("a mesh", "[mesh]") {}\n'},
                        'a test source is named <Unit>Test.cpp'),
    }
    failures = 0
    base = check(tree(good))
    if base:
        print('self-test: the good tree is reported:\n' + '\n'.join(base))
        failures += 1
    for name, (extra, expected) in cases.items():
        files = dict(good)
        files.update(extra)
        found = check(tree(files))
        if not any(expected in p for p in found):
            print('self-test: %s: expected a report containing %r, got %r' % (name, expected, found))
            failures += 1
    print('self-test: %d of %d cases caught' % (len(cases) + 1 - failures, len(cases) + 1))
    return 1 if failures else 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == '--self-test':
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
    problems = check(os.path.abspath(root))
    for p in problems:
        print(p)
    print('architecture: %d problem(s)' % len(problems))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
