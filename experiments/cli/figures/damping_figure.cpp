#include "experiments/cli/figures/damping_figure.hpp"

#include <fmt/format.h>

#include "analysis/plot_lines.hpp"
#include "framework/pipeline/provenance.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;
namespace {
// The shove moves the pelvis by millimetres: plotted in mm so the curves are readable.
std::vector<double> millimetres(const std::vector<double>& metres) {
  std::vector<double> mm(metres.size());
  for (size_t i = 0; i < metres.size(); ++i) mm[i] = 1000.0 * metres[i];
  return mm;
}
}  // namespace

void write_damping_figure(const std::vector<DampingRun>& runs, const fs::path& dir) {
  fs::create_directories(dir);
  std::string series = "damping,time_s,position_m,target_m\n",
              summary = "damping,rms_deviation_m,max_deviation_m,overshoot_m,final_deviation_m\n";
  analysis::LinePlot plot;
  plot.title = "Recovery after a shove, per damping d";
  plot.x_label = "Time (s)";
  plot.y_label = "Pelvis x (mm)";
  plot.note = "seed 000 Figure 4";
  plot.x_markers = {3.5};
  for (const DampingRun& r : runs) {
    for (size_t i = 0; i < r.time_s.size(); ++i)
      series +=
          fmt::format("{},{:.6f},{:.6f},{:.6f}\n", r.damping, r.time_s[i], r.position_m[i], r.target_m[i]);
    summary += fmt::format("{},{:.6f},{:.6f},{:.6f},{:.6f}\n", r.damping, r.rms_deviation_m,
                           r.max_deviation_m, r.overshoot_m, r.final_deviation_m);
    plot.series.push_back({fmt::format("d = {}", r.damping), r.time_s, millimetres(r.position_m), false});
  }
  if (!runs.empty())
    plot.series.push_back({"target", runs.front().time_s, millimetres(runs.front().target_m), true});
  write_file_atomic(dir / "damping.csv", series);
  write_file_atomic(dir / "damping_summary.csv", summary);
  if (!runs.empty()) analysis::plot_lines(plot, (dir / "damping").string());
}

}  // namespace crowdlab::cli
