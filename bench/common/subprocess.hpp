#pragma once
// Programs the benchmarks start: a run of grip under mpirun, a plot script with Debian's python3.
#include <filesystem>
#include <string>
#include <vector>

namespace grip::bench {

// Runs a program (args[0] is its path) with stdout and stderr into `log`; its exit status
// (128 + the signal's number when a signal ended it).
int run_process(const std::vector<std::string>& args, const std::filesystem::path& log);

// Runs the plot script `script` (a path relative to the source tree, e.g.
// "bench/hard/plot_hard.py") with /usr/bin/python3 on `arguments`, its output into
// out/plot.log, which is removed when the script succeeds. False, with a warning that names
// the fix (python3-matplotlib), when python3 or the script is missing or the script fails.
bool plot(const std::string& script, const std::vector<std::string>& arguments,
          const std::filesystem::path& out);

}  // namespace grip::bench
