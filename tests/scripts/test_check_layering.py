#!/usr/bin/python3
"""scripts/check-layering.py on copies of the source tree with one violation planted in each.

Usage: test_check_layering.py SOURCE_DIR
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR = None
COPIED = ("CMakeLists.txt", "cmake", "docs/architecture.md", "solver", "src", "io", "farm", "app",
          "bench", "tests", "scripts/check-layering.py")


class CheckLayeringTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="grip-layering-")
        self.root = self.tmp.name
        for rel in COPIED:
            source, target = os.path.join(SOURCE_DIR, rel), os.path.join(self.root, rel)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            if os.path.isdir(source):
                shutil.copytree(source, target)
            else:
                shutil.copy2(source, target)

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, rel, text):
        with open(os.path.join(self.root, rel), "w", encoding="utf-8") as f:
            f.write(text)

    def edit(self, rel, old, new):
        path = os.path.join(self.root, rel)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        self.assertIn(old, text, f"{rel} no longer holds {old!r}: update this test")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text.replace(old, new))

    def run_check(self):
        script = os.path.join(self.root, "scripts", "check-layering.py")
        done = subprocess.run([sys.executable, script, "--root", self.root],
                              capture_output=True, text=True, check=False)
        return done.returncode, done.stdout

    def test_the_copy_passes(self):
        code, out = self.run_check()
        self.assertEqual(code, 0, out)

    def test_solver_including_io_fails(self):
        self.write("solver/planted.cpp",
                   "// Planted: the solver must not know the dataset.\n"
                   "#include <vector>\n"
                   '#include "io/dataset_writer.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('solver/planted.cpp:3: #include "io/dataset_writer.hpp": '
                      "module solver may not include module io", out)

    def test_io_including_the_solver_fails(self):
        self.edit("io/dataset_plan.hpp", "#pragma once\n",
                  '#pragma once\n#include "solver/environment.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('io/dataset_plan.hpp:2: #include "solver/environment.hpp": '
                      "module io may not include module solver", out)

    def test_an_include_without_its_link_fails(self):
        self.edit("src/trial/CMakeLists.txt", " grip_io ", " ")
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('src/trial/trial_scene.hpp:12: #include "io/gripper_record.hpp": '
                      "target grip_trial", out)
        self.assertIn("does not link grip_io (module io)", out)

    def test_a_link_across_a_forbidden_edge_fails(self):
        self.edit("io/CMakeLists.txt", "PUBLIC grip_hdf5", "PUBLIC grip_solver grip_hdf5")
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertRegex(out, r"io/CMakeLists.txt:\d+: grip_io links grip_solver: "
                              r"module io may not use module solver")

    def test_sources_including_tests_fail(self):
        self.write("farm/planted.hpp", '#pragma once\n#include "tests/farm/farm_test_job.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('farm/planted.hpp:2: #include "tests/farm/farm_test_job.hpp": '
                      "only tests/ may include tests/", out)

    def test_an_include_cycle_between_solver_folders_fails(self):
        # solver/potential includes solver/contact; an include back closes a cycle.
        self.write("solver/contact/planted.hpp",
                   '#pragma once\n#include "solver/potential/stencil.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('solver/contact/planted.hpp:2: #include "solver/potential/stencil.hpp": '
                      "module solver/contact may not include module solver/potential", out)
        self.assertRegex(out, r"include cycle between modules: solver/contact -> "
                              r"solver/potential -> solver/contact \(solver/contact/planted.hpp:2, "
                              r"solver/potential/[a-z_]+\.(c|h)pp:\d+\)")

    def test_a_folder_of_a_target_is_checked_on_its_own_edges(self):
        # The model is above the bodies: a body kind may not include it, although both folders
        # build grip_solver.
        self.write("solver/body/planted.cpp", '#include "solver/model/model.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('solver/body/planted.cpp:1: #include "solver/model/model.hpp": '
                      "module solver/body may not include module solver/model", out)

    def test_listing_a_module_allows_only_its_own_targets_folders(self):
        # src/metrics lists solver/kernels alone: the solver's other folders stay closed to it.
        self.write("src/metrics/planted.cpp", '#include "solver/model/model.hpp"\n')
        code, out = self.run_check()
        self.assertEqual(code, 1, out)
        self.assertIn('src/metrics/planted.cpp:1: #include "solver/model/model.hpp": '
                      "module src/metrics may not include module solver/model", out)

    def test_a_cycle_through_a_targets_folders_in_the_table_is_refused(self):
        # src/scene lists solver, and so every folder grip_solver builds: solver/scene among them.
        self.edit("docs/architecture.md", "solver/scene      grip_solver          -",
                  "solver/scene      grip_solver          src/scene")
        code, _ = self.run_check()
        self.assertEqual(code, 2)

    def test_a_cycle_in_the_table_is_refused(self):
        self.edit("docs/architecture.md", "src/config        grip_config          -",
                  "src/config        grip_config          src/scene")
        code, _ = self.run_check()
        self.assertEqual(code, 2)


if __name__ == "__main__":
    SOURCE_DIR = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
