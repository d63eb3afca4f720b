#!/usr/bin/python3
"""Checks that only the body registry dispatches on a body's kind (solver::BodyType).

Each body kind is a solver subsystem (solver/body/), and the registry
(solver/body/body_registry.hpp, .cpp) is the one place that maps a description's BodyType to
its kind. Everywhere else code asks the model or the body's kind in the problem's words (has
it DOFs, does it deform, is it scripted) and never compares, switches or cases on BodyType.
Naming a type in a description (`body.type = BodyType::kFem`) is a description, not a dispatch,
and is allowed. This script reads every C++ file under solver/ src/ io/ farm/ bench/ tests/
app/ fuzz/ (comments and string literals left out) and prints one line per dispatch outside
the registry: file:line, what it is, the rule. Exit status: 0 when there is none, 1 otherwise.

  scripts/check-body-kinds.py              check the tree this script lives in
  scripts/check-body-kinds.py --root DIR   check another tree

Python 3 standard library only.
"""

import argparse
import os
import re
import sys

from cpp_text import strip_code

TOPS = ("solver", "src", "io", "farm", "bench", "tests", "app", "fuzz")
SUFFIXES = (".cpp", ".cc", ".cu", ".hpp", ".h", ".cuh", ".inl")
REGISTRY = ("solver/body/body_registry.hpp", "solver/body/body_registry.cpp")
KIND = r"(?:\w+\s*::\s*)*BodyType\s*::\s*\w+"
COMPARISON = re.compile(rf"(?:[!=]=\s*{KIND})|(?:{KIND}\s*[!=]=)")
CASE = re.compile(rf"\bcase\s+{KIND}")
SWITCH = re.compile(r"\bswitch\s*\(")
RULE = (f"only the body registry ({REGISTRY[1]}) dispatches on BodyType; ask the model or the "
        "body's kind (BodySubsystem) in the problem's words")


def line_of(code, offset):
    return code.count("\n", 0, offset) + 1


def switch_block(code, start):
    """The text of the braces after the switch whose `switch (` ends at start."""
    depth, i = 1, start
    while i < len(code) and depth:  # past the condition's parentheses
        depth += {"(": 1, ")": -1}.get(code[i], 0)
        i += 1
    open_brace = code.find("{", i)
    if open_brace < 0:
        return ""
    depth, j = 0, open_brace
    while j < len(code):
        depth += {"{": 1, "}": -1}.get(code[j], 0)
        if depth == 0:
            break
        j += 1
    return code[open_brace:j]


def dispatches(code):
    """(line, what) for each comparison, switch and case on BodyType in stripped code."""
    found = []
    for m in COMPARISON.finditer(code):
        found.append((line_of(code, m.start()), "compares a body's kind (BodyType)"))
    for m in SWITCH.finditer(code):
        if CASE.search(switch_block(code, m.end())):
            found.append((line_of(code, m.start()), "switches on a body's kind (BodyType)"))
    for m in CASE.finditer(code):
        found.append((line_of(code, m.start()), "a case on a body's kind (BodyType)"))
    return sorted(set(found))


def files(root):
    for top in TOPS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames.sort()
            for name in sorted(filenames):
                if name.endswith(SUFFIXES):
                    path = os.path.join(dirpath, name)
                    yield os.path.relpath(path, root).replace(os.sep, "/")


def check(root):
    violations = []
    for rel in files(root):
        if rel in REGISTRY:
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            code = strip_code(f.read())
        for line, what in dispatches(code):
            violations.append(f"{rel}:{line}: {what}: {RULE}")
    return violations


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=os.path.dirname(here),
                        help="the source tree to check (default: this script's tree)")
    args = parser.parse_args()
    violations = check(os.path.abspath(args.root))
    for v in violations:
        print(v)
    if violations:
        print(f"check-body-kinds: {len(violations)} dispatch(es) on BodyType outside the body "
              "registry", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
