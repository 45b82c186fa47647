// `crowdlab export-csv CROWD.glb --out FILE.csv`: root trajectories of a crowd file as CSV.
#include <spdlog/spdlog.h>

#include <string>

#include "experiments/cli/command_table.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_root_trajectories_csv.hpp"

namespace crowdlab::cli::cmd_export_csv {
namespace {

struct ExportCsvOptions {
  std::string crowd_path;
  std::string out_path;
};

}  // namespace

void add_export_csv_command(Command& root) {
  auto opt = std::make_shared<ExportCsvOptions>();
  auto* cmd = root.add_subcommand(
      "export-csv",
      "Write the root trajectories of a crowd file (.glb) as CSV, one row per character per frame: "
      "character,frame,time_s,x,z,heading_rad (metres on the ground plane, seconds, radians; heading 0 "
      "faces +Z, pi/2 faces +X)");
  cmd->add_option("crowd", opt->crowd_path, "Crowd file written by crowdlab (.glb)")->required();
  cmd->add_option("-o,--out", opt->out_path, "CSV file to write")->required();
  cmd->callback([opt] {
    const CrowdAnimation crowd = read_crowd_glb(opt->crowd_path);
    write_root_trajectories_csv(crowd, opt->out_path);
    spdlog::info("wrote {} rows ({} characters x {} frames) to {}",
                 crowd.characters.size() * crowd.frame_count(), crowd.characters.size(), crowd.frame_count(),
                 opt->out_path);
  });
}

}  // namespace crowdlab::cli::cmd_export_csv
