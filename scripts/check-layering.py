#!/usr/bin/python3
"""Checks grip's module layering: who may include whom, and that CMake links what is included.

The rule is the `layering` block of docs/architecture.md (module folder, its CMake target, the
module folders it may include). This script reads that block, every #include of a project
header under solver/ src/ io/ farm/ app/ bench/ tests/, and every CMakeLists.txt, and prints
one line per violation (file:line, the include or link, the rule broken), and the modules of an
include cycle if the includes make one. Exit status: 0 when the tree keeps the rule, 1 on a
violation, 2 when the table or the tree cannot be read.

Several module folders may share one target (the solver's folders all build grip_solver):
between them each include is checked against the block, but from a module of another target
they are one, so listing a module allows the folders under it that its target builds too
(`src/trial` lists `solver` and may include `solver/newton`).

  scripts/check-layering.py                 check the tree this script lives in
  scripts/check-layering.py --root DIR      check another tree (DIR/docs/architecture.md's table)
  scripts/check-layering.py --edges         also print the include edges found, module to module

Python 3 standard library only.
"""

import argparse
import collections
import os
import re
import sys

SOURCE_TOPS = ("solver", "src", "io", "farm", "app", "bench")  # the modules live here
TESTS = "tests"  # tests/ may include any module; only tests/ may include tests/
SOURCE_SUFFIXES = (".cpp", ".cc", ".cu")
HEADER_SUFFIXES = (".hpp", ".h", ".cuh", ".inl")
TABLE_DOC = os.path.join("docs", "architecture.md")
INCLUDE = re.compile(r'^\s*#\s*include\s*["<]([^">]+)[">]')
LINK_KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "LINK_PUBLIC", "LINK_PRIVATE",
                 "LINK_INTERFACE_LIBRARIES"}
LIBRARY_KINDS = {"STATIC", "SHARED", "MODULE", "OBJECT", "INTERFACE", "EXCLUDE_FROM_ALL"}


class TableError(Exception):
    pass


# ---- the table -------------------------------------------------------------------------------

def read_table(path):
    """The layering block: {module: (target, [allowed modules], line)} in table order."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise TableError(f"{path}: cannot read the layering table: {e.strerror}")
    start = next((i for i, l in enumerate(lines) if l.strip() == "```layering"), None)
    if start is None:
        raise TableError(f"{path}: no ```layering block (the module table this check reads)")
    table = {}
    last = None
    for i in range(start + 1, len(lines)):
        raw = lines[i]
        if raw.strip() == "```":
            break
        text = raw.split("#", 1)[0]
        if not text.strip():
            continue
        fields = text.split()
        if raw[0].isspace():  # a continuation line: more modules the previous one may include
            if last is None:
                raise TableError(f"{path}:{i + 1}: continuation line before any module")
            table[last][1].extend(f.rstrip("/") for f in fields)
            continue
        if len(fields) < 2:
            raise TableError(f"{path}:{i + 1}: want 'module target [may include ...]'")
        module = fields[0].rstrip("/")
        if module in table:
            raise TableError(f"{path}:{i + 1}: module {module} declared twice")
        allowed = [f.rstrip("/") for f in fields[2:] if f != "-"]
        table[module] = (fields[1], allowed, i + 1)
        last = module
    else:
        raise TableError(f"{path}:{start + 1}: the ```layering block is not closed")
    for module, (_, allowed, line) in table.items():
        for other in allowed:
            if other not in table:
                raise TableError(f"{path}:{line}: {module} may include {other}, "
                                 "which is not a module of the table")
            if other == module:
                raise TableError(f"{path}:{line}: {module} lists itself")
    cycle = find_cycle(allowed_edges(table))
    if cycle:
        raise TableError(f"{path}: the table has a cycle: {' -> '.join(cycle)}")
    return table


def allowed_edges(table):
    """{module: set of modules it may include}: the block's edges, and from a module of another
    target, the folders under a listed module that the listed module's target builds too."""
    edges = {}
    for module, (target, allowed, _) in table.items():
        edges[module] = set(allowed)
        for other in allowed:
            if table[other][0] == target:
                continue
            edges[module] |= {m for m, (t, _, _) in table.items()
                              if t == table[other][0] and m.startswith(other + "/")}
    return edges


def find_cycle(graph):
    state = {}
    stack = []

    def visit(node):
        state[node] = 1
        stack.append(node)
        for nxt in graph.get(node, ()):
            if state.get(nxt) == 1:
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = 2
        return None

    for node in graph:
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def include_cycles(edges, first_include):
    """A line naming the modules of an include cycle, and an include of each edge, if any."""
    graph = collections.defaultdict(list)
    for (a, b) in sorted(edges):
        graph[a].append(b)
    cycle = find_cycle(graph)
    if not cycle:
        return []
    sites = ", ".join(first_include[(a, b)] for a, b in zip(cycle, cycle[1:]))
    return [f"include cycle between modules: {' -> '.join(cycle)} ({sites})"]


def module_of(path, modules):
    """The longest table module that is a prefix folder of path, else None."""
    best = None
    for m in modules:
        if (path == m or path.startswith(m + "/")) and (best is None or len(m) > len(best)):
            best = m
    return best


# ---- CMake ----------------------------------------------------------------------------------

Target = collections.namedtuple("Target", "name folder sources links")
COMMAND = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\s*\(")


def cmake_commands(text):
    """(command, [arguments], line) for each top-level command call of a CMake file."""
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        if c == "#":
            bracket = re.match(r"#\[(=*)\[", text[i:])
            if bracket:
                close = text.find("]" + bracket.group(1) + "]", i)
                close = n if close < 0 else close
                line += text.count("\n", i, close)
                i = close + 1
            else:
                while i < n and text[i] != "\n":
                    i += 1
            continue
        m = COMMAND.match(text, i)
        if not m or (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_")):
            i += 1
            continue
        command, start = m.group(0).rstrip("( \t\n").lower(), line
        args, word, depth, quoted = [], "", 1, False
        i = m.end()
        line += m.group(0).count("\n")
        while i < n and depth:
            c = text[i]
            if c == "\n":
                line += 1
            if quoted:
                if c == "\\" and i + 1 < n:
                    word += text[i:i + 2]
                    i += 2
                    continue
                if c == '"':
                    quoted = False
                else:
                    word += c
            elif c == '"':
                quoted = True
            elif c == "#":
                while i < n and text[i] != "\n":
                    i += 1
                continue
            elif c in "()" or c.isspace():
                depth += {"(": 1, ")": -1}.get(c, 0)
                if word:
                    args.append(word)
                    word = ""
            else:
                word += c
            i += 1
        yield command, args, start


def read_targets(root):
    """Every target the project's CMakeLists.txt define, with its sources and its links."""
    targets = {}
    links = collections.defaultdict(list)  # name -> [(visibility, library, cmake, line)]
    for folder in ("",) + SOURCE_TOPS + (TESTS, "cmake"):
        top = os.path.join(root, folder)
        if not os.path.isdir(top):
            continue
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames.sort()
            if folder == "":
                dirnames[:] = []
            for name in sorted(filenames):
                if name != "CMakeLists.txt" and not name.endswith(".cmake"):
                    continue
                path = os.path.join(dirpath, name)
                rel_dir = os.path.relpath(dirpath, root).replace(os.sep, "/")
                rel_dir = "" if rel_dir == "." else rel_dir
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                cmake = os.path.relpath(path, root).replace(os.sep, "/")
                for command, args, line in cmake_commands(text):
                    add_command(command, args, line, rel_dir, cmake, targets, links)
    for name, entries in links.items():
        if name in targets:
            targets[name].links.extend(entries)
    return targets


def source_path(arg, rel_dir):
    for var in ("${PROJECT_SOURCE_DIR}/", "${CMAKE_SOURCE_DIR}/"):
        if arg.startswith(var):
            return arg[len(var):]
    if arg.startswith("${CMAKE_CURRENT_SOURCE_DIR}/"):
        arg = arg[len("${CMAKE_CURRENT_SOURCE_DIR}/"):]
    if "${" in arg or "$<" in arg:
        return None
    return os.path.normpath(os.path.join(rel_dir, arg)).replace(os.sep, "/")


def add_command(command, args, line, rel_dir, cmake, targets, links):
    if not args or "${" in args[0]:
        return  # a target named by a variable: the body of a function, not a target
    name = args[0]
    if command in ("add_library", "add_executable"):
        if "IMPORTED" in args or "ALIAS" in args:
            return
        sources = [source_path(a, rel_dir) for a in args[1:] if a not in LIBRARY_KINDS]
        targets[name] = Target(name, rel_dir, [s for s in sources if s], [])
    elif command in ("grip_add_test", "grip_add_mpi_test"):
        sources, libs, key = [], [], None
        for a in args[1:]:
            if a in ("SOURCES", "LIBS", "NP"):
                key = a
            elif key == "SOURCES":
                sources.append(source_path(a, rel_dir))
            elif key == "LIBS":
                libs.append(a)
        if command == "grip_add_mpi_test":
            sources.append("tests/mpi/gtest_mpi_main.cpp")
        targets[name] = Target(name, rel_dir, [s for s in sources if s], [])
        links[name].extend(("PRIVATE", lib, cmake, line) for lib in libs)
    elif command == "target_sources":
        sources = [source_path(a, rel_dir) for a in args[1:] if a not in LINK_KEYWORDS]
        if name in targets:
            targets[name].sources.extend(s for s in sources if s)
    elif command == "target_link_libraries":
        visibility = "PUBLIC"  # the plain signature propagates like PUBLIC
        for a in args[1:]:
            if a in LINK_KEYWORDS:
                visibility = {"LINK_PUBLIC": "PUBLIC", "LINK_PRIVATE": "PRIVATE",
                              "LINK_INTERFACE_LIBRARIES": "INTERFACE"}.get(a, a)
            else:
                links[name].append((visibility, a, cmake, line))


def interface_closure(name, targets, memo):
    """name and every target whose usage requirements reach users of name."""
    if name in memo:
        return memo[name]
    memo[name] = {name}
    result = {name}
    if name in targets:
        for visibility, lib, _, _ in targets[name].links:
            if visibility != "PRIVATE":
                result |= interface_closure(lib, targets, memo)
    memo[name] = result
    return result


def compile_closure(name, targets, memo):
    """Every target whose usage requirements reach name's own sources."""
    result = {name}
    for _, lib, _, _ in targets[name].links:
        result |= interface_closure(lib, targets, memo)
    return result


# ---- the checks -----------------------------------------------------------------------------

def project_files(root):
    for top in SOURCE_TOPS + (TESTS,):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames.sort()
            for name in sorted(filenames):
                if name.endswith(SOURCE_SUFFIXES + HEADER_SUFFIXES):
                    yield os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/")


def read_includes(root, path):
    includes = []
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        for number, text in enumerate(f, 1):
            m = INCLUDE.match(text)
            if m and m.group(1).split("/", 1)[0] in SOURCE_TOPS + (TESTS,):
                includes.append((number, m.group(1)))
    return includes


def check(root, table_path):
    table = read_table(table_path)
    table_rel = os.path.relpath(table_path, root).replace(os.sep, "/")
    modules = list(table)
    violations = []
    table_errors = []  # the table against the tree: a folder or a target that is not there

    for module, (target, _, line) in table.items():
        if not os.path.isdir(os.path.join(root, module)):
            table_errors.append(f"{table_rel}:{line}: module {module}: no such folder")

    files = list(project_files(root))
    includes = {f: read_includes(root, f) for f in files}
    edges = collections.Counter()
    first_include = {}  # (module, module) -> where the first include across that edge is
    allowed = allowed_edges(table)

    # 1. Every include follows an edge of the table.
    for path in files:
        here = module_of(path, modules)
        in_tests = path.startswith(TESTS + "/")
        if here is None and not in_tests:
            violations.append(f"{path}:1: in no module of the table ({table_rel}): "
                              "add its folder to the table")
            continue
        for number, header in includes[path]:
            there = module_of(header, modules)
            where = f'{path}:{number}: #include "{header}"'
            if header.startswith(TESTS + "/"):
                if not in_tests:
                    violations.append(f"{where}: only tests/ may include tests/")
                continue
            if there is None:
                violations.append(f"{where}: the header is in no module of the table")
                continue
            if in_tests or there == here:
                continue
            edges[(here, there)] += 1
            first_include.setdefault((here, there), f"{path}:{number}")
            if there not in allowed[here]:
                violations.append(f"{where}: module {here} may not include module {there} "
                                  f"({table_rel}, layering block)")
    violations.extend(include_cycles(edges, first_include))

    # 2. Every target links (directly, or through PUBLIC dependencies) the target of each module
    #    whose headers its sources reach, and links across allowed edges only.
    try:
        targets = read_targets(root)
    except (OSError, UnicodeDecodeError) as e:
        raise TableError(f"cannot read the CMake files: {e}")
    provider = collections.defaultdict(list)  # target -> its modules, in table order
    for module, (target, _, line) in table.items():
        if target not in targets:
            table_errors.append(f"{table_rel}:{line}: module {module}: target {target} is "
                                "defined by no CMakeLists.txt")
        provider[target].append(module)
    # A header belongs to the target that compiles its .cpp (src/app has several targets);
    # a header without one to its module's target.
    header_target = {}
    for name, t in targets.items():
        for source in t.sources:
            stem = os.path.splitext(source)[0]
            for suffix in HEADER_SUFFIXES:
                header_target.setdefault(stem + suffix, name)
    memo = {}
    reported = set()
    for name in sorted(targets):
        t = targets[name]
        owners = provider.get(name) or [m for m in [module_of(t.folder, modules)] if m]
        if not owners and not (t.folder + "/").startswith(TESTS + "/"):
            continue  # e.g. cmake/'s wrappers of third-party libraries
        for _, lib, cmake, line in t.links if owners else ():
            others = provider.get(lib, [])
            if others and not any(w in others or o in allowed[w] for w in owners for o in others):
                owner, other = min(owners, key=len), min(others, key=len)
                violations.append(f"{cmake}:{line}: {name} links {lib}: module {owner} may "
                                  f"not use module {other} ({table_rel}, layering block)")
        reach = compile_closure(name, targets, memo)
        for source in t.sources:
            if source not in includes:
                continue
            seen = set()
            stack = [source]
            while stack:
                path = stack.pop()
                if path in seen:
                    continue
                seen.add(path)
                for number, header in includes.get(path, ()):
                    if header in includes:
                        stack.append(header)
                    there = module_of(header, modules)
                    if there is None or there in owners:
                        continue
                    need = header_target.get(header, table[there][0])
                    key = (path, number, name)
                    if need not in reach and key not in reported:
                        reported.add(key)
                        via = "" if path == source else f" (reached from {source})"
                        violations.append(
                            f'{path}:{number}: #include "{header}": target {name}{via} does not '
                            f"link {need} (module {there}), directly or through PUBLIC links")
    return table_errors + violations, edges


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=os.path.dirname(here),
                        help="the source tree to check (default: this script's tree)")
    parser.add_argument("--table", help=f"the file holding the layering block "
                        f"(default: ROOT/{TABLE_DOC})")
    parser.add_argument("--edges", action="store_true",
                        help="also print the include edges found, module to module")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    try:
        violations, edges = check(root, args.table or os.path.join(root, TABLE_DOC))
    except TableError as e:
        print(f"check-layering: {e}", file=sys.stderr)
        return 2
    if args.edges:
        for (a, b), n in sorted(edges.items()):
            print(f"edge {a} -> {b} ({n} includes)")
    for v in violations:
        print(v)
    if violations:
        print(f"check-layering: {len(violations)} violation(s) of the module layering "
              f"({TABLE_DOC})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
