#!/usr/bin/python3
"""scripts/check-body-kinds.py on this tree, and on small trees with dispatches planted in them.

Usage: test_check_body_kinds.py SOURCE_DIR
"""

import os
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR = None

PLANTED = """// if (body.type == BodyType::kFem): a comment is no dispatch
const char* note = "body.type == BodyType::kFem";
void f(solver::BodyDescription& body, bool soft) {
  if (body.type == solver::BodyType::kFem) g();
  if (solver::BodyType::kKinematic != body.type) g();
  body.type = soft ? solver::BodyType::kFem : solver::BodyType::kAffine;
  switch (body.type) {
    case solver::BodyType::kAffine:
      break;
    default:
      break;
  }
  switch (count) {
    case 1:
      break;
  }
}
"""


class CheckBodyKindsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="grip-body-kinds-")
        self.root = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def plant(self, rel, text):
        path = os.path.join(self.root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

    def run_check(self, root):
        script = os.path.join(SOURCE_DIR, "scripts", "check-body-kinds.py")
        done = subprocess.run(["/usr/bin/python3", script, "--root", root],
                              capture_output=True, text=True, check=False)
        return done.returncode, done.stdout

    def test_this_tree_passes(self):
        code, out = self.run_check(SOURCE_DIR)
        self.assertEqual(code, 0, out)

    def test_comparisons_switches_and_cases_are_named(self):
        self.plant("src/trial/planted.cpp", PLANTED)
        code, out = self.run_check(self.root)
        self.assertEqual(code, 1, out)
        lines = out.splitlines()
        self.assertEqual([line.split(": ")[0] for line in lines],
                         ["src/trial/planted.cpp:4", "src/trial/planted.cpp:5",
                          "src/trial/planted.cpp:7", "src/trial/planted.cpp:8"], out)
        self.assertIn("src/trial/planted.cpp:4: compares a body's kind (BodyType)", out)
        self.assertIn("src/trial/planted.cpp:7: switches on a body's kind (BodyType)", out)
        self.assertIn("src/trial/planted.cpp:8: a case on a body's kind (BodyType)", out)
        self.assertIn("only the body registry (solver/body/body_registry.cpp)", out)

    def test_the_solver_and_the_tests_are_checked_too(self):
        self.plant("solver/newton/planted.hpp", "bool k(T b) { return b.type != BodyType::kFem; }")
        self.plant("tests/solver/planted.cpp", "bool k(T b) { return BodyType::kFem == b.type; }")
        code, out = self.run_check(self.root)
        self.assertEqual(code, 1, out)
        self.assertIn("solver/newton/planted.hpp:1: compares", out)
        self.assertIn("tests/solver/planted.cpp:1: compares", out)

    def test_the_registry_may_dispatch(self):
        self.plant("solver/body/body_registry.cpp", PLANTED)
        code, out = self.run_check(self.root)
        self.assertEqual(code, 0, out)


if __name__ == "__main__":
    SOURCE_DIR = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
