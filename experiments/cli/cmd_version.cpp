// `crowdlab version`: the version and the library versions outputs are recorded with.
#include <Eigen/Core>
#include <cstdio>

#include "crowdlab_version.hpp"
#include "experiments/cli/command_table.hpp"

namespace crowdlab::cli::cmd_version {

void add_version_command(Command& root) {
  auto* cmd = root.add_subcommand("version", "Print the crowdlab version and its library versions");
  cmd->callback([] {
    std::printf("crowdlab %s\nEigen %d.%d.%d\n", CROWDLAB_VERSION, EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                EIGEN_MINOR_VERSION);
  });
}

}  // namespace crowdlab::cli::cmd_version
