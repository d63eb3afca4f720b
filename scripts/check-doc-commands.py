#!/usr/bin/python3
"""Checks that every command README.md and docs/*.md show still runs as written.

Commands are the lines of fenced code blocks (no language, sh, bash, shell or console) and the
inline code spans that start with `grip`, `build/grip`, `./grip`, `mpirun ... grip`, a script
(scripts/*.sh, a .py file) or `/usr/bin/python3 SCRIPT`. For each:

- a grip command runs with GRIP_CHECK_ARGS=1, which makes grip parse and validate its command
  line (subcommand, options, values, PETSc options only where taken) and exit before any work;
  it must exit 0. `mpirun` and its options are dropped, grip runs once.
- an inline span that names a command and options without values (`grip farm`,
  `grip synth --count`) is a reference: the subcommand and each option must exist (grip's
  --help lists them).
- a script must exist (and be executable when run directly); repository paths given to grip
  (jobs/..., examples/...) must exist, unless they are an output (--out, --report, ...).

Synopses are expanded into one concrete command: optional parts `[...]` are kept, `a|b` takes
`a`, `...` is dropped, and the placeholders in PLACEHOLDERS get those values. Any other
upper-case word left is an error: give a concrete value in the doc, or add the placeholder here.

  scripts/check-doc-commands.py --grip build/grip             check this tree's docs
  scripts/check-doc-commands.py --grip build/grip --root DIR  check DIR's README.md and docs/
  scripts/check-doc-commands.py --grip build/grip -v          also list each command that passed

Exit status: 0 when every command passes, 1 otherwise, 2 when the docs hold no command.
Python 3 standard library only.
"""

import argparse
import glob
import os
import re
import shlex
import subprocess
import sys

# A documented placeholder and the value it is checked with.
PLACEHOLDERS = {
    "COMMAND": "bench linear",  # the grammar line: the one command that takes PETSc options
    "PETSc options": "-ksp_type cg",
    "[global options]": "",
    "[options]": "",
    "JOB.toml": "jobs/demo.toml",
    "job.toml": "jobs/demo.toml",
    "SCENE.toml": "examples/scenes/soft_squeeze.toml",
    "S.toml": "examples/scenes/soft_squeeze.toml",
    "A.toml": "examples/scenes/soft_squeeze.toml",
    "B.toml": "examples/scenes/box_on_incline.toml",
    "DATASET.h5": "out/demo/dataset.h5",
    "FILE": "out/file",
    "FILE.csv": "out/file.csv",
    "FILE.json": "out/file.json",
    "DIR": "out/dir",
    "IN": "mesh.obj",
    "SPEC": "cylinder",
    "OBJECT_NAME": "capsule-0",
    "G": "parallel-jaw",
    "N": "2", "T": "2", "B": "2", "S": "1", "SEED": "1", "I": "0",
    "A": "0.01", "O": "0.001", "L": "0.01", "X": "1", "F": "50", "V": "0.01",
    "E": "1e6", "NU": "0.4", "RHO": "1000", "MU": "0.5",
    "D": "host",  # --device: the data-parallel engine, on the CPU
}
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_]*(\.[a-z0-9]+)?$")
FENCE = re.compile(r"^\s*(```+|~~~+)\s*([\w-]*)")
SHELL_LANGUAGES = {"", "sh", "bash", "shell", "console"}
GRIP = re.compile(r"^(\./|build/)?grip$")
COMMAND_START = re.compile(
    r"^(\$ )?([A-Z_]+=\S*\s+)*"  # a prompt, environment settings
    r"((\./|build/)?grip(\s|$)|mpirun\s.*\bgrip(\s|$)|/usr/bin/python3\s|\S+\.(sh|py)(\s|$))")
OUTPUT_OPTIONS = {"--out", "--output", "--report", "--vtk", "--write-hard"}
REPO_FOLDERS = ("jobs/", "examples/", "assets/", "bench/", "docs/", "scripts/", "tests/")
GLOBAL_WITH_VALUE = {"--log-level"}


def doc_files(root):
    files = [os.path.join(root, "README.md")]
    files += sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    return [f for f in files if os.path.exists(f)]


def fenced_commands(lines):
    """(line number, text) of each command in the shell code blocks; continuations joined."""
    found, fence, language, current = [], None, "", None
    for number, line in enumerate(lines, 1):
        match = FENCE.match(line)
        if match and (fence is None or match.group(1)[0] == fence[0]):
            fence, language = (match.group(1), match.group(2)) if fence is None else (None, "")
            current = None
            continue
        if fence is None or language not in SHELL_LANGUAGES:
            continue
        # A line ending in a backslash goes on, as does an indented synopsis line (`  --out`).
        if current is not None and (current[1].endswith("\\") or re.match(r"^\s+[-\[]", line)):
            current[1] = current[1].rstrip("\\").rstrip() + " " + line.strip()
            continue
        current = None
        for part in re.split(r";|&&|\|\||\s\|\s", line.strip()):
            part = re.sub(r"^(\$|do|then|else)\s+", "", part.strip())
            if COMMAND_START.match(part):
                current = [number, part]
                found.append(current)
    return [(n, text.rstrip("\\").strip()) for n, text in found]


def inline_commands(lines):
    found, fence = [], None
    for number, line in enumerate(lines, 1):
        match = FENCE.match(line)
        if match:
            fence = match.group(1) if fence is None else None
            continue
        if fence is not None:
            continue
        for span in re.findall(r"`([^`]+)`", line):
            span = re.split(r"\s\|\s", span.strip())[0]  # a pipeline's first command
            if COMMAND_START.match(span):
                found.append((number, span))
    return found


def expand(text):
    """A synopsis as one concrete argument list, or raises ValueError naming what is unknown."""
    text = text.replace("\\|", "|")
    for phrase in ("[global options]", "[options]", "PETSc options"):
        text = text.replace(phrase, PLACEHOLDERS[phrase])
    text = re.sub(r"<(\w+)>", r"\1", text)
    words = []
    for word in shlex.split(text, comments=True):
        word = word.replace("[", "").replace("]", "")
        if "|" in word:
            word = word.split("|")[0]
        word = ",".join(w for w in word.split(",") if w != "...")
        word = word[:-3] if word.endswith("...") else word
        if not word:
            continue
        if word in PLACEHOLDERS:
            words += PLACEHOLDERS[word].split()
        elif PLACEHOLDER.match(word):
            raise ValueError(f"unknown placeholder '{word}': write a concrete value, or add it "
                             "to PLACEHOLDERS in scripts/check-doc-commands.py")
        else:
            words.append(word)
    return words


class Grip:
    """The grip executable: its command tree read from --help, and the parse-only run."""

    def __init__(self, executable):
        self.executable = executable
        self.nodes = {}

    def node(self, path):
        """(subcommand names, option names) of the command `path` (a tuple), from its --help."""
        if path not in self.nodes:
            run = subprocess.run([self.executable, *path, "--help"], capture_output=True,
                                 text=True, check=False)
            subcommands, options, section = set(), set(), None
            for line in run.stdout.splitlines():
                if line and not line.startswith(" "):
                    section = line.rstrip(":")
                elif section == "Subcommands" and line.strip():
                    subcommands.add(line.split()[0])
                elif section == "Options" and line.strip().startswith("-"):
                    names = line.split()[0]
                    options.update(n for n in names.split(",") if n.startswith("-"))
            self.nodes[path] = (subcommands, options)
        return self.nodes[path]

    def split(self, words):
        """(global options, subcommand path, the rest) of grip's arguments."""
        global_words, i = [], 0
        while i < len(words) and words[i].startswith("-") and words[i] != "--":
            take = 2 if words[i] in GLOBAL_WITH_VALUE else 1
            global_words += words[i:i + take]
            i += take
        path = ()
        while i < len(words) and words[i] in self.node(path)[0]:
            path += (words[i],)
            i += 1
        return global_words, path, words[i:]

    def check(self, words):
        """None if grip accepts the arguments, else what it said."""
        environment = dict(os.environ, GRIP_CHECK_ARGS="1")
        run = subprocess.run([self.executable, *words], capture_output=True, text=True,
                             env=environment, check=False)
        if run.returncode == 0:
            return None
        said = (run.stderr.strip() or run.stdout.strip()).splitlines()
        return f"exit {run.returncode}: {said[0] if said else '(nothing)'}"


def check_script(root, words, inline):
    """Problems with a script command: `scripts/demo.sh`, `/usr/bin/python3 x.py ARGS`."""
    direct = words[0] != "/usr/bin/python3"
    script = words[0] if direct else (words[1] if len(words) > 1 else "")
    if inline and "/" not in script:
        return []  # a file named in prose, not a path from the repository's root
    path = os.path.join(root, script)
    if not os.path.isfile(path):
        return [f"no such script '{script}'"]
    if direct and not inline and not os.access(path, os.X_OK):
        return [f"'{script}' is run directly but is not executable"]
    return []


def check_grip(root, grip, words, inline):
    """Problems with a grip command (words start after the executable)."""
    global_words, path, rest = grip.split(words)
    problems = []
    previous = ""
    for word in rest:
        if word == "--":
            break
        if word.startswith(REPO_FOLDERS) and previous not in OUTPUT_OPTIONS:
            if not os.path.exists(os.path.join(root, word)):
                problems.append(f"no such file in the repository: '{word}'")
        previous = word
    if inline and all(w.startswith("-") and w != "--" for w in rest):
        # A reference to a command and its options, not a command to run.
        known = grip.node(path)[1] | grip.node(())[1]
        problems += [f"'grip {' '.join(path)}' has no option '{w.split('=')[0]}'"
                     for w in global_words + rest if w.startswith("-")
                     and w.split("=")[0] not in known]
        return problems
    said = grip.check(words)
    if said:
        problems.append(said)
    return problems


def check_command(root, grip, text, inline):
    try:
        words = expand(text)
    except ValueError as error:
        return str(error), ""
    while words and re.match(r"^[A-Z_]+=", words[0]):
        words = words[1:]  # an environment setting before the command
    if words and words[0] == "mpirun":
        at = next((i for i, w in enumerate(words) if GRIP.match(os.path.basename(w))), None)
        words = words[at:] if at is not None else []
    if not words:
        return None, ""
    if GRIP.match(words[0]):
        problems = check_grip(root, grip, words[1:], inline)
    else:
        problems = check_script(root, words, inline)
    return ("; ".join(problems) or None), " ".join(shlex.quote(w) for w in words)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--grip", required=True, help="the grip executable")
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), help="the tree whose README.md and docs/ are checked")
    parser.add_argument("-v", "--verbose", action="store_true", help="also list what passed")
    args = parser.parse_args()
    grip = Grip(os.path.abspath(args.grip))
    os.chdir(args.root)
    checked, failed = 0, 0
    for path in doc_files(args.root):
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        name = os.path.relpath(path, args.root)
        commands = [(n, t, False) for n, t in fenced_commands(lines)]
        commands += [(n, t, True) for n, t in inline_commands(lines)]
        for number, text, inline in sorted(commands):
            problem, ran = check_command(args.root, grip, text, inline)
            checked += 1
            if problem:
                failed += 1
                print(f"{name}:{number}: `{text}`\n    checked as: {ran}\n    {problem}")
            elif args.verbose:
                print(f"{name}:{number}: ok: {ran}")
    if checked == 0:
        print("no command found in README.md or docs/*.md", file=sys.stderr)
        return 2
    print(f"doc-commands: {checked - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
