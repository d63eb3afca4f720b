#!/usr/bin/python3
"""Checks that the reference pages under docs/ carry no history: no commit named, and a short
results page.

Every docs/*.md but docs/journal.md is a reference page: it says what is true now, and the
history of how it came to be goes to docs/journal.md or to the commits' bodies. A page fails
when it names a git commit: a lower-case hex word of 7 to 40 characters that
`git cat-file -e WORD^{commit}` accepts, where the tree is a git checkout; elsewhere (an
exported tree) any such word with at least one digit and one letter a-f counts. docs/results.md
fails when it has 400 lines or more.

  scripts/check-doc-reference.py              check this tree's docs
  scripts/check-doc-reference.py --root DIR   check DIR's docs/

Prints one line per violation, `docs/FILE.md:LINE: ...`. Exit status: 0 when there is none,
1 otherwise, 2 when DIR has no docs/*.md. Python 3 standard library only.
"""

import argparse
import glob
import os
import re
import subprocess
import sys

JOURNAL = "journal.md"
RESULTS = "results.md"
RESULTS_MAX_LINES = 400  # docs/results.md must have fewer lines than this
HEX_WORD = re.compile(r"(?<![0-9A-Za-z_])[0-9a-f]{7,40}(?![0-9A-Za-z_])")


def git_checkout(root):
    """True when root is the top of a git work tree and git can be run."""
    try:
        run = subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True, check=False)
    except OSError:
        return False
    return (run.returncode == 0 and
            os.path.realpath(run.stdout.strip()) == os.path.realpath(root))


class Commits:
    """Which hex words name a commit: asked of git in a checkout, guessed from the word
    elsewhere."""

    def __init__(self, root):
        self.root = root
        self.git = git_checkout(root)
        self.known = {}

    def names_a_commit(self, word):
        if not self.git:
            return bool(re.search(r"[0-9]", word)) and bool(re.search(r"[a-f]", word))
        if word not in self.known:
            run = subprocess.run(["git", "-C", self.root, "cat-file", "-e", word + "^{commit}"],
                                 capture_output=True, check=False)
            self.known[word] = run.returncode == 0
        return self.known[word]


def reference_pages(root):
    pages = sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    return [p for p in pages if os.path.basename(p) != JOURNAL]


def check_page(path, name, commits):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()  # the newline that ends the last line
    problems = []
    for number, line in enumerate(lines, 1):
        for word in HEX_WORD.findall(line):
            if commits.names_a_commit(word):
                what = "names commit" if commits.git else "names what looks like a commit hash,"
                problems.append(f"{name}:{number}: {what} {word}: a reference page says what is "
                                f"true now; history goes to docs/{JOURNAL}")
    if os.path.basename(path) == RESULTS and len(lines) >= RESULTS_MAX_LINES:
        problems.append(f"{name}:{len(lines)}: {len(lines)} lines, not under "
                        f"{RESULTS_MAX_LINES}: link long tables from docs/results/ and move "
                        f"history to docs/{JOURNAL}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), help="the tree whose docs/ is checked")
    args = parser.parse_args()
    pages = reference_pages(args.root)
    if not pages:
        print(f"no reference page in {os.path.join(args.root, 'docs')}", file=sys.stderr)
        return 2
    commits = Commits(args.root)
    problems = []
    for path in pages:
        problems += check_page(path, os.path.relpath(path, args.root), commits)
    for problem in problems:
        print(problem)
    print(f"doc-reference: {len(pages)} pages, {len(problems)} problems"
          + ("" if commits.git else " (not a git checkout: hex words taken for commits)"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
