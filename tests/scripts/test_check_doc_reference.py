#!/usr/bin/python3
"""scripts/check-doc-reference.py fails, naming the line, on docs whose reference pages name a
git commit or whose results.md has 400 lines or more, passes on the docs as they are, and
leaves docs/journal.md alone.

The docs are copied into a temporary folder made a git repository of its own (when git is
there), so that the planted hash names a real commit; a copy that is not a git checkout is
checked too, where any hex word with a digit and a letter a-f counts.

  test_check_doc_reference.py SOURCE_DIR
"""
import glob
import os
import shutil
import subprocess
import sys
import tempfile

NOT_A_COMMIT = "deadbeef01"  # hex, but no commit of the temporary repository


def copy_docs(source, folder):
    os.makedirs(os.path.join(folder, "docs"))
    for path in glob.glob(os.path.join(source, "docs", "*.md")):
        shutil.copy(path, os.path.join(folder, "docs"))


def git(folder, *args):
    return subprocess.run(["git", "-C", folder, "-c", "user.name=test", "-c",
                           "user.email=test@localhost", "-c", "commit.gpgsign=false", *args],
                          capture_output=True, text=True, check=True).stdout.strip()


def make_repository(folder):
    """The folder as a git repository with one commit; that commit's hash, or None without git."""
    if shutil.which("git") is None:
        return None
    git(folder, "init", "-q")
    git(folder, "add", "-A")
    git(folder, "commit", "-q", "-m", "docs")
    return git(folder, "rev-parse", "HEAD")


def append(path, text):
    with open(path, "a", encoding="utf-8") as f:
        f.write(text)


def line_count(path):
    with open(path, encoding="utf-8") as f:
        return len(f.read().rstrip("\n").split("\n"))


def plant(folder, commit):
    """Plants the commit in a reference page and in the journal, and lengthens results.md; returns
    the (line of farm.md, line of results.md) the check must name."""
    farm = os.path.join(folder, "docs", "farm.md")
    append(farm, f"\nMeasured at {commit[:7]}, and {NOT_A_COMMIT} is not a commit.\n")
    journal = os.path.join(folder, "docs", "journal.md")
    append(journal, f"\nThe run at {commit[:7]}.\n")
    results = os.path.join(folder, "docs", "results.md")
    append(results, "A line.\n" * max(0, 400 - line_count(results)))
    return line_count(farm), line_count(results)


def check(source, folder):
    return subprocess.run(
        ["/usr/bin/python3", os.path.join(source, "scripts", "check-doc-reference.py"),
         "--root", folder], capture_output=True, text=True, check=False)


def expect_caught(source, folder, commit, failures, what):
    farm_line, results_line = plant(folder, commit)
    run = check(source, folder)
    found = []
    if run.returncode != 1:
        found.append(f"{what}: exit {run.returncode}, not 1")
    if f"docs/farm.md:{farm_line}: " not in run.stdout or commit[:7] not in run.stdout:
        found.append(f"{what}: the commit {commit[:7]} at docs/farm.md:{farm_line} not named")
    if f"docs/results.md:{results_line}: " not in run.stdout:
        found.append(f"{what}: the {results_line} lines of docs/results.md not named")
    if "journal.md:" in run.stdout:
        found.append(f"{what}: the journal was checked")
    if found:
        found.append(f"the check printed:\n{run.stdout}{run.stderr}")
    failures += found
    return run


def main():
    source = sys.argv[1]
    failures = []

    with tempfile.TemporaryDirectory() as folder:
        copy_docs(source, folder)
        commit = make_repository(folder)
        if commit is not None:
            run = check(source, folder)
            if run.returncode != 0:
                failures.append(f"the docs as they are were refused:\n{run.stdout}{run.stderr}")
            run = expect_caught(source, folder, commit, failures, "git checkout")
            if NOT_A_COMMIT in run.stdout:
                failures.append(f"{NOT_A_COMMIT}, no commit, was named in a git checkout")
        else:
            print("git not found: the git checkout case is skipped")

    with tempfile.TemporaryDirectory() as folder:
        copy_docs(source, folder)
        run = check(source, folder)
        if run.returncode != 0:
            failures.append(f"the docs as they are, not a git checkout, were refused:\n"
                            f"{run.stdout}{run.stderr}")
        run = expect_caught(source, folder, "4f1f19d", failures, "not a git checkout")
        if NOT_A_COMMIT not in run.stdout:
            failures.append(f"{NOT_A_COMMIT} not named where the tree is not a git checkout")

    with tempfile.TemporaryDirectory() as folder:
        run = check(source, folder)
        if run.returncode != 2:
            failures.append(f"a tree without docs: exit {run.returncode}, not 2")

    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
