#!/usr/bin/env python3
"""Fails when a function in the given folders is longer than a limit (lines, braces included).

Usage: check-function-length.py [--limit N] FOLDER...

A function is a brace block at namespace or class level whose head has a parameter list; a
block's length counts from the line of its opening brace to the line of its closing one.
Comments and string literals are ignored when braces are matched. Prints one
`file:line: function of N lines (limit L)` line per offender and exits 1, or exits 0.
"""
import argparse
import os
import re
import sys

from cpp_text import strip_code

HEAD_IS_TYPE = re.compile(r"^\s*(template\s*<.*>\s*)?(class|struct|union|enum|namespace|extern)\b")


def long_functions(path, limit):
    code = strip_code(open(path, encoding="utf-8").read())
    # Preprocessor lines are no part of a declaration's head.
    code = re.sub(r"(?m)^[ \t]*#.*$", "", code)
    stack = []  # (is_function_or_type_scope, start line)
    head, line = "", 1
    found = []
    for ch in code:
        if ch == "\n":
            line += 1
        if ch == "{":
            outer = all(kind == "scope" for kind, _ in stack)
            if HEAD_IS_TYPE.match(head):
                stack.append(("scope" if outer else "block", line))
            elif outer and ")" in head:
                stack.append(("function", line))
            else:
                stack.append(("block", line))
            head = ""
        elif ch == "}":
            if stack:
                kind, start = stack.pop()
                if kind == "function" and line - start + 1 > limit:
                    found.append((start, line - start + 1))
            head = ""
        elif ch == ";":
            head = ""
        else:
            head += ch
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=60)
    parser.add_argument("folders", nargs="+")
    args = parser.parse_args()
    offenders = 0
    for folder in args.folders:
        for root, _, files in sorted(os.walk(folder)):
            for name in sorted(files):
                if not name.endswith((".cpp", ".hpp", ".h", ".cu")):
                    continue
                path = os.path.join(root, name)
                for start, length in long_functions(path, args.limit):
                    print(f"{path}:{start}: function of {length} lines (limit {args.limit})")
                    offenders += 1
    return 1 if offenders else 0


if __name__ == "__main__":
    sys.exit(main())
