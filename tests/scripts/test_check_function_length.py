#!/usr/bin/env python3
"""The function length check passes a short function and names a long one (a planted file)."""
import os
import subprocess
import sys
import tempfile

script = os.path.join(sys.argv[1], "scripts", "check-function-length.py")
short_body = "  int x = 0;\n" * 10
long_body = "  int x = 0;\n  // { a brace in a comment\n  const char* s = \"}\";\n" * 20
with tempfile.TemporaryDirectory() as root:
    with open(os.path.join(root, "short.cpp"), "w") as f:
        f.write("#include <cstdio>\nnamespace a {\nstruct S {\n  int f() const {\n" + short_body +
                "    return 1;\n  }\n};\n}  // namespace a\n")
    ok = subprocess.run([sys.executable, script, root], capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    with open(os.path.join(root, "long.cpp"), "w") as f:
        f.write("namespace a {\nvoid g(int y) {\n" + long_body + "}\n}  // namespace a\n")
    bad = subprocess.run([sys.executable, script, root], capture_output=True, text=True)
    assert bad.returncode == 1, bad.stdout + bad.stderr
    expected = os.path.join(root, "long.cpp") + ":2: function of 62 lines (limit 60)"
    assert bad.stdout.strip() == expected, bad.stdout
print("check-function-length: passes a short function, names a long one")
