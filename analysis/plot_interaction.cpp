#include "analysis/plot_interaction.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>

#include "analysis/plot_style.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {

void plot_interaction(const InteractionPlot& plot, const std::string& path_stem) {
  const size_t nx = plot.x_levels.size();
  if (nx == 0 || plot.series.empty()) throw InputError("interaction plot '" + plot.title + "': no data");
  for (const auto& s : plot.series)
    if (s.mean.size() != nx || s.error.size() != nx)
      throw InputError("interaction plot '" + plot.title + "': series '" + s.label +
                       "' length differs from x levels");
  double lo = plot.y_min, hi = plot.y_max;
  if (!(hi > lo)) {
    lo = INFINITY;
    hi = -INFINITY;
    for (const auto& s : plot.series)
      for (size_t i = 0; i < nx; ++i) {
        lo = std::min(lo, s.mean[i] - s.error[i]);
        hi = std::max(hi, s.mean[i] + s.error[i]);
      }
    const double pad = 0.1 * std::max(hi - lo, 1e-9);
    lo -= pad;
    hi += 2 * pad;
  }
  const double xmin = -0.5, xmax = static_cast<double>(nx) - 0.5;
  const double offset_step = std::min(0.08, 0.4 / static_cast<double>(plot.series.size()));
  render_figure(path_stem, 900, 600, [&](plstream& pls) {
    pls.schr(0, 1.1);
    pls.vpor(0.12, 0.78, 0.14, 0.9);
    pls.wind(xmin, xmax, lo, hi);
    use_axis_colour(pls);
    pls.box("bc", 1.0, 0, "bcnstv", 0, 0);
    for (size_t i = 0; i < nx; ++i)
      pls.mtex("b", 1.5, (static_cast<double>(i) - xmin) / (xmax - xmin), 0.5, plot.x_levels[i].c_str());
    draw_titles(pls, plot.title, plot.x_label, plot.y_label, plot.note);
    for (size_t k = 0; k < plot.series.size(); ++k) {
      const auto& s = plot.series[k];
      const double shift =
          (static_cast<double>(k) - 0.5 * static_cast<double>(plot.series.size() - 1)) * offset_step;
      std::vector<PLFLT> x(nx), y(nx), ylo(nx), yhi(nx);
      for (size_t i = 0; i < nx; ++i) {
        x[i] = static_cast<double>(i) + shift;
        y[i] = s.mean[i];
        ylo[i] = s.mean[i] - s.error[i];
        yhi[i] = s.mean[i] + s.error[i];
      }
      use_series_colour(pls, static_cast<int>(k));
      pls.width(2.0);
      pls.lsty(1 + static_cast<int>(k % 3));
      pls.line(static_cast<PLINT>(nx), x.data(), y.data());
      pls.lsty(1);
      pls.erry(static_cast<PLINT>(nx), x.data(), ylo.data(), yhi.data());
      pls.poin(static_cast<PLINT>(nx), x.data(), y.data(), k % 2 ? 5 : 17);
    }
    use_axis_colour(pls);
    pls.width(1.0);
    for (size_t i = 0; i < std::min(nx, plot.stars.size()); ++i) {
      if (plot.stars[i].empty()) continue;
      double top = -INFINITY;
      for (const auto& s : plot.series) top = std::max(top, s.mean[i] + s.error[i]);
      pls.ptex(static_cast<double>(i), top + 0.04 * (hi - lo), 1, 0, 0.5, plot.stars[i].c_str());
    }
    std::vector<LegendEntry> legend;
    for (size_t k = 0; k < plot.series.size(); ++k)
      legend.push_back({plot.series[k].label, 1 + static_cast<int>(k % 3), k % 2 ? 5 : 17});
    draw_legend(pls, legend);
  });
}

}  // namespace crowdlab::analysis
