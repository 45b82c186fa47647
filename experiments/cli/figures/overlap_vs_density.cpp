#include "experiments/cli/figures/overlap_vs_density.hpp"

#include <cmath>
#include <limits>

#include "analysis/plot_interaction.hpp"
#include "framework/core/csv.hpp"
#include "framework/pipeline/provenance.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;

void write_overlap_vs_density(const std::vector<OverlapRow>& rows, const fs::path& dir) {
  fs::create_directories(dir);
  std::string csv = csv_line({"scenario", "characters", "density", "method", "mean_overlap_l"});
  for (const OverlapRow& r : rows)
    csv += csv_line({r.scenario, std::to_string(r.characters), csv_number(r.density), r.method,
                     csv_number(r.mean_overlap_l)});
  write_file_atomic(dir / "overlap_vs_density.csv", csv);

  for (const std::string scenario : {"stationary", "corridor"}) {
    analysis::InteractionPlot plot;
    plot.title = "Mean per-character overlap (" + scenario + ")";
    plot.x_label = "Density (characters/m^2)";
    plot.y_label = "Overlap volume (L per character)";
    plot.note = "seed 000 Figure 3";
    analysis::InteractionSeries base{"Baseline", {}, {}}, ours{"Ours", {}, {}};
    for (const OverlapRow& r : rows) {
      if (r.scenario != scenario || r.method != "baseline") continue;
      plot.x_levels.push_back(csv_number(r.density));
      base.mean.push_back(r.mean_overlap_l);
      base.error.push_back(0);
      ours.mean.push_back(overlap_of(rows, scenario, r.density, "ours"));
      ours.error.push_back(0);
    }
    if (plot.x_levels.empty()) continue;
    plot.series = {base, ours};
    plot.stars.assign(plot.x_levels.size(), "");
    analysis::plot_interaction(plot, (dir / ("overlap_vs_density_" + scenario)).string());
  }
}

double overlap_of(const std::vector<OverlapRow>& rows, const std::string& scenario, double density,
                  const std::string& method) {
  for (const OverlapRow& r : rows)
    if (r.scenario == scenario && r.method == method && std::abs(r.density - density) < 1e-9)
      return r.mean_overlap_l;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace crowdlab::cli
