#!/usr/bin/python3
"""scripts/check-doc-commands.py fails, naming each line, on docs whose commands no longer run
as written, passes on docs whose commands do, and refuses docs that show no command at all.

  test_check_doc_commands.py GRIP_EXECUTABLE SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile

GOOD = """# A tree whose docs are right

```sh
scripts/demo.sh
build/grip farm jobs/demo.toml --threads 1     # a comment
mpirun -np 2 build/grip bench linear --cells 0.01 -- -ksp_type cg
grip synth --object SPEC --gripper fin-ray|leap [--bimanual] --count N --seed S
           --out FILE
grip trial --candidates c.txt \\
    --index 0-3 --threads 2
```

`grip farm`, `grip synth --count`, `grip --version` and `grip inspect DATASET.h5 [--job]`.
"""

# Line number (in docs/bad.md) -> a command that must be reported there.
BAD = {
    3: "grip synth --object box --gripper fin-ray --count 1 --seed 1 --out c.txt -- -ksp_type cg",
    4: "grip farm --no-such-option",
    5: "grip frm jobs/demo.toml",
    6: "grip inspect WHATEVER.h5",
    7: "scripts/no-such.sh",
    10: "build/grip synth --object cylinder --gripper pincer --count 2 --seed 1 --out c.txt",
    11: "build/grip synth --object cylinder --gripper leap --count 0 --seed 1 --out c.txt",
    12: "build/grip farm jobs/missing.toml",
    13: "grip trial --candidates c.txt --youngs 1e6",
}


def bad_doc():
    lines = ["# A tree whose docs drifted", ""]
    for number in range(3, 8):
        lines.append(f"Inline: `{BAD[number]}`.")
    lines += ["", "```sh"]
    for number in range(10, 14):
        lines.append(BAD[number])
    lines.append("```")
    return "\n".join(lines) + "\n"


def make_tree(folder, docs):
    os.makedirs(os.path.join(folder, "docs"))
    os.makedirs(os.path.join(folder, "jobs"))
    os.makedirs(os.path.join(folder, "scripts"))
    with open(os.path.join(folder, "jobs", "demo.toml"), "w", encoding="utf-8") as f:
        f.write("[job]\nname = \"demo\"\n")
    demo = os.path.join(folder, "scripts", "demo.sh")
    with open(demo, "w", encoding="utf-8") as f:
        f.write("#!/bin/sh\n")
    os.chmod(demo, 0o755)
    for name, text in docs.items():
        with open(os.path.join(folder, name), "w", encoding="utf-8") as f:
            f.write(text)


def check(source, grip, folder):
    return subprocess.run(
        ["/usr/bin/python3", os.path.join(source, "scripts", "check-doc-commands.py"),
         "--grip", grip, "--root", folder], capture_output=True, text=True, check=False)


def main():
    grip, source = sys.argv[1], sys.argv[2]
    failures = []
    with tempfile.TemporaryDirectory() as folder:
        make_tree(folder, {"README.md": GOOD})
        run = check(source, grip, folder)
        if run.returncode != 0:
            failures.append(f"good docs were refused:\n{run.stdout}{run.stderr}")

    with tempfile.TemporaryDirectory() as folder:
        make_tree(folder, {"README.md": GOOD, "docs/bad.md": bad_doc()})
        run = check(source, grip, folder)
        if run.returncode != 1:
            failures.append(f"drifted docs: exit {run.returncode}, not 1")
        for number, command in BAD.items():
            if f"docs/bad.md:{number}: `{command}`" not in run.stdout:
                failures.append(f"not reported: docs/bad.md:{number}: {command}")
        if "README.md:" in run.stdout:
            failures.append("a good command was reported")
        if failures:
            failures.append(f"the check printed:\n{run.stdout}{run.stderr}")

    with tempfile.TemporaryDirectory() as folder:
        make_tree(folder, {"README.md": "# No commands here\n"})
        run = check(source, grip, folder)
        if run.returncode != 2:
            failures.append(f"docs without a command: exit {run.returncode}, not 2")

    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
