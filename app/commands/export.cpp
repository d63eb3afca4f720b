// `grip export --layout grip DATASET.h5 DIR`: a grip dataset in GRIP's released layout, one
// HDF5 file per gripper and object (io/grip_layout.hpp), so that code written for GRIP's data
// reads grip's. Reads with serial HDF5; needs no MPI.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "app/dataset_probe.hpp"
#include "io/dataset_reader.hpp"
#include "io/grip_layout.hpp"

namespace grip::commands {

void declare_export(cli::Command& root) {
  struct ExportArgs {
    std::string layout;
    std::string dataset;
    std::string folder;
    bool all = false;
  };
  auto args = std::make_shared<ExportArgs>();
  cli::Command command =
      root.subcommand("export", "Write a dataset in another layout: GRIP's, one file per object");
  command.option("--layout", args->layout, "The layout to write: grip (GRIP_Dataset's)")
      .required()
      .check(cli::Check::one_of({"grip"}));
  command.option("dataset", args->dataset, "The dataset (.h5)").required();
  command.option("folder", args->folder, "The folder to write the files into").required();
  command.flag("--all", args->all,
               "Every committed candidate with a trajectory, its verdict in "
               "trajectories/success and trajectories/failure (default: the successes, as GRIP)");
  command.on_run([args] {
    check_dataset_readable(args->dataset);
    const io::DatasetReader dataset(args->dataset);
    const std::vector<io::GripLayoutFile> files =
        io::export_grip_layout(dataset, args->folder, {args->all});
    std::uint64_t poses = 0;
    for (const io::GripLayoutFile& file : files) {
      spdlog::debug("{}: {} grasps", file.path.string(), file.poses);
      poses += file.poses;
    }
    spdlog::info("{} grasps in {} files in {}", poses, files.size(), args->folder);
    return 0;
  });
}

}  // namespace grip::commands
