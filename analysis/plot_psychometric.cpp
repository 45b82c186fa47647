#include "analysis/plot_psychometric.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>

#include "analysis/plot_style.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {

void plot_psychometric(const PsychometricPlot& plot, const std::string& path_stem) {
  if (plot.curves.empty()) throw InputError("psychometric plot '" + plot.title + "': no curves");
  double xmin = INFINITY, xmax = -INFINITY;
  for (const auto& c : plot.curves)
    for (double v : c.x) {
      xmin = std::min(xmin, v);
      xmax = std::max(xmax, v);
    }
  if (!(xmax > xmin)) throw InputError("psychometric plot '" + plot.title + "': need at least two x values");
  const double pad = 0.05 * (xmax - xmin);
  xmin -= pad;
  xmax += pad;
  render_figure(path_stem, 900, 600, [&](plstream& pls) {
    pls.schr(0, 1.1);
    pls.vpor(0.12, 0.78, 0.14, 0.9);
    pls.wind(xmin, xmax, -0.05, 1.08);
    use_axis_colour(pls);
    pls.box("bcnst", 0, 0, "bcnstv", 0.2, 0);
    draw_titles(pls, plot.title, plot.x_label, plot.y_label);
    pls.lsty(3);
    pls.join(xmin, 0.5, xmax, 0.5);
    for (size_t k = 0; k < plot.curves.size(); ++k) {
      const auto& c = plot.curves[k];
      use_series_colour(pls, static_cast<int>(k));
      const int n = 200;
      std::vector<PLFLT> cx(n), cy(n);
      for (int i = 0; i < n; ++i) {
        cx[static_cast<size_t>(i)] = xmin + (xmax - xmin) * i / (n - 1.0);
        cy[static_cast<size_t>(i)] =
            1.0 / (1.0 + std::exp(-(c.intercept + c.slope * cx[static_cast<size_t>(i)])));
      }
      pls.width(2.0);
      pls.lsty(1);
      if (c.fitted) pls.line(n, cx.data(), cy.data());
      const auto m = static_cast<PLINT>(c.x.size());
      std::vector<PLFLT> lo(c.x.size()), hi(c.x.size());
      for (size_t i = 0; i < c.x.size(); ++i) {
        lo[i] = c.proportion[i] - c.se[i];
        hi[i] = c.proportion[i] + c.se[i];
      }
      pls.erry(m, c.x.data(), lo.data(), hi.data());
      pls.poin(m, c.x.data(), c.proportion.data(), k % 2 ? 5 : 17);
      if (std::isfinite(c.threshold50) && c.threshold50 > xmin && c.threshold50 < xmax) {
        pls.lsty(2);
        pls.width(1.0);
        pls.join(c.threshold50, -0.05, c.threshold50, 0.5);
        pls.lsty(1);
      }
    }
    std::vector<LegendEntry> legend;
    for (size_t k = 0; k < plot.curves.size(); ++k)
      legend.push_back({plot.curves[k].label, 1, k % 2 ? 5 : 17});
    draw_legend(pls, legend);
  });
}

}  // namespace crowdlab::analysis
