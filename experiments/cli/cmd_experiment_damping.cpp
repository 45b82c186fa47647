// `crowdlab experiment damping --out DIR`: seed 000 Fig. 4, the recovery of a shoved character for
// several values of the Eq. 4 damping d. Writes DIR/damping.csv (columns damping,time_s,position_m,
// target_m) and DIR/damping_summary.csv (damping,rms_deviation_m,max_deviation_m).
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "experiments/cli/command_registry.hpp"
#include "experiments/cli/experiment_group.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/damping_experiment.hpp"

namespace crowdlab::cli {
namespace {

struct DampingOptions {
  std::string out_dir;
  std::vector<double> dampings{0.0, 0.006, 0.06, 0.6};
  double duration_s = 8.0;
};

void write_or_throw(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw RuntimeError("cannot write " + path.string());
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto opt = std::make_shared<DampingOptions>();
  auto* cmd = experiment_group(root)->add_subcommand(
      "damping", "Seed 000 Fig. 4: a character shoved at t = 3.5 s recovering, for several dampings d");
  cmd->add_option("-o,--out", opt->out_dir, "Output folder")->required();
  cmd->add_option("--damping", opt->dampings, "Damping values d")->capture_default_str();
  cmd->add_option("--duration", opt->duration_s, "Seconds simulated")->capture_default_str();
  cmd->callback([opt] {
    const auto runs = run_damping_experiment(opt->dampings, CorrectorParams{}, opt->duration_s);
    std::filesystem::create_directories(opt->out_dir);
    std::string series = "damping,time_s,position_m,target_m\n",
                summary = "damping,rms_deviation_m,max_deviation_m\n";
    for (const DampingRun& r : runs) {
      for (size_t i = 0; i < r.time_s.size(); ++i)
        series +=
            fmt::format("{},{:.6f},{:.6f},{:.6f}\n", r.damping, r.time_s[i], r.position_m[i], r.target_m[i]);
      summary += fmt::format("{},{:.6f},{:.6f}\n", r.damping, r.rms_deviation_m, r.max_deviation_m);
      spdlog::info("d = {}: RMS deviation after t = 3.5 s {:.2f} mm, max {:.2f} mm", r.damping,
                   1000 * r.rms_deviation_m, 1000 * r.max_deviation_m);
    }
    const std::filesystem::path dir(opt->out_dir);
    write_or_throw(dir / "damping.csv", series);
    write_or_throw(dir / "damping_summary.csv", summary);
    spdlog::info("wrote {} and {}", (dir / "damping.csv").string(), (dir / "damping_summary.csv").string());
  });
});

}  // namespace
}  // namespace crowdlab::cli
