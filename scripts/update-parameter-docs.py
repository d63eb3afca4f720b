#!/usr/bin/python3
"""Writes `grip parameters`' tables into the docs, between their markers.

docs/job-format.md and docs/scene-format.md hold each table of a parameter group between
`<!-- grip parameters: NAME ... -->` and `<!-- end of grip parameters -->`; this script replaces
what lies between with what `grip parameters` prints for NAME (the test ParameterOptions.
TheDocsTablesAreTheParameterTables fails until it matches).

  scripts/update-parameter-docs.py [--grip build/grip]

Python 3 standard library only.
"""
import argparse
import os
import re
import subprocess
import sys

DOCS = ("docs/job-format.md", "docs/scene-format.md")
END = "<!-- end of grip parameters -->"


def printed_tables(grip):
    text = subprocess.run([grip, "parameters"], check=True, capture_output=True, text=True).stdout
    return {m.group(1): m.group(2).rstrip("\n") + "\n"
            for m in re.finditer(r"## \[(\w+)\]\n\n(.*?)(?=\n## |\Z)", text, re.S)}


def update(path, tables):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    pattern = re.compile(r"(<!-- grip parameters: (\w+) [^\n]*-->\n)(.*?)(" + re.escape(END) + ")",
                         re.S)
    updated = pattern.sub(lambda m: m.group(1) + tables[m.group(2)] + m.group(4), text)
    if updated != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(updated)
        print(f"updated {path}")


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--grip", default=os.path.join(root, "build", "grip"))
    args = parser.parse_args()
    tables = printed_tables(args.grip)
    for doc in DOCS:
        update(os.path.join(root, doc), tables)
    return 0


if __name__ == "__main__":
    sys.exit(main())
