// `crowdlab experiment damping --out DIR`: seed 000 Fig. 4, the recovery of a shoved character for
// several values of the Eq. 4 damping d. Writes DIR/damping.csv (columns damping,time_s,position_m,
// target_m), DIR/damping_summary.csv (damping,rms_deviation_m,max_deviation_m,overshoot_m,
// final_deviation_m) and the figure
// DIR/damping.png|svg (analysis/plot_lines: pelvis x versus time, one line per d, the target dashed).
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/plot_lines.hpp"
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
                summary = "damping,rms_deviation_m,max_deviation_m,overshoot_m,final_deviation_m\n";
    for (const DampingRun& r : runs) {
      for (size_t i = 0; i < r.time_s.size(); ++i)
        series +=
            fmt::format("{},{:.6f},{:.6f},{:.6f}\n", r.damping, r.time_s[i], r.position_m[i], r.target_m[i]);
      summary += fmt::format("{},{:.6f},{:.6f},{:.6f},{:.6f}\n", r.damping, r.rms_deviation_m,
                             r.max_deviation_m, r.overshoot_m, r.final_deviation_m);
      spdlog::info(
          "d = {}: RMS deviation after t = 3.5 s {:.2f} mm, max {:.2f} mm, overshoot {:.2f} mm, last second "
          "{:.2f} mm",
          r.damping, 1000 * r.rms_deviation_m, 1000 * r.max_deviation_m, 1000 * r.overshoot_m,
          1000 * r.final_deviation_m);
    }
    const std::filesystem::path dir(opt->out_dir);
    write_or_throw(dir / "damping.csv", series);
    write_or_throw(dir / "damping_summary.csv", summary);
    analysis::LinePlot plot;
    plot.title = "Recovery after a collision at t = 3.5 s";
    plot.x_label = "Time (s)";
    plot.y_label = "Pelvis x (mm)";
    plot.note = "seed 000 Figure 4";
    plot.x_markers = {3.5};
    for (const DampingRun& r : runs) {
      analysis::LineSeries s{fmt::format("d = {}", r.damping), r.time_s, {}, false};
      for (double x : r.position_m) s.y.push_back(1000.0 * x);
      plot.series.push_back(std::move(s));
    }
    if (!runs.empty()) {
      analysis::LineSeries target{"target", runs.front().time_s, {}, true};
      for (double x : runs.front().target_m) target.y.push_back(1000.0 * x);
      plot.series.push_back(std::move(target));
    }
    analysis::plot_lines(plot, (dir / "damping").string());
    spdlog::info("wrote {}, {} and {}.png|svg", (dir / "damping.csv").string(),
                 (dir / "damping_summary.csv").string(), (dir / "damping").string());
  });
});

}  // namespace
}  // namespace crowdlab::cli
