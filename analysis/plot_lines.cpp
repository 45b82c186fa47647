#include "analysis/plot_lines.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>

#include "analysis/plot_style.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {

void plot_lines(const LinePlot& plot, const std::string& path_stem) {
  if (plot.series.empty()) throw InputError("line plot '" + plot.title + "': no series");
  double xmin = INFINITY, xmax = -INFINITY, lo = INFINITY, hi = -INFINITY;
  for (const auto& s : plot.series) {
    if (s.x.size() != s.y.size() || s.x.size() < 2)
      throw InputError("line plot '" + plot.title + "': series '" + s.label +
                       "' needs x and y of the same length (>= 2)");
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        throw InputError("line plot '" + plot.title + "': series '" + s.label + "' has a non-finite value");
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      lo = std::min(lo, s.y[i]);
      hi = std::max(hi, s.y[i]);
    }
  }
  if (plot.y_max > plot.y_min) {
    lo = plot.y_min;
    hi = plot.y_max;
  } else {
    const double pad = 0.08 * std::max(hi - lo, 1e-9);
    lo -= pad;
    hi += pad;
  }
  if (!(xmax > xmin)) xmax = xmin + 1.0;
  render_figure(path_stem, 900, 600, [&](plstream& pls) {
    pls.schr(0, 1.1);
    pls.vpor(0.12, 0.76, 0.14, 0.9);
    pls.wind(xmin, xmax, lo, hi);
    use_axis_colour(pls);
    pls.box("bcnst", 0, 0, "bcnstv", 0, 0);
    pls.mtex("b", 3.2, 0.5, 0.5, plot.x_label.c_str());
    pls.mtex("l", 4.5, 0.5, 0.5, plot.y_label.c_str());
    pls.mtex("t", 1.5, 0.5, 0.5, plot.title.c_str());
    if (!plot.note.empty()) {
      pls.schr(0, 0.8);
      pls.mtex("t", 0.4, 1.0, 1.0, plot.note.c_str());
      pls.schr(0, 1.1);
    }
    pls.lsty(3);
    for (double m : plot.x_markers)
      if (m > xmin && m < xmax) pls.join(m, lo, m, hi);
    // Solid series first, dashed (reference) series on top so that they stay visible.
    for (int pass = 0; pass < 2; ++pass)
      for (size_t k = 0; k < plot.series.size(); ++k) {
        const auto& s = plot.series[k];
        if (s.dashed != (pass == 1)) continue;
        use_series_colour(pls, static_cast<int>(k));
        pls.width(s.dashed ? 2.5 : 2.0);
        pls.lsty(s.dashed ? 2 : 1);
        pls.line(static_cast<PLINT>(s.x.size()), s.x.data(), s.y.data());
      }
    pls.lsty(1);
    // Legend in its own viewport right of the plot (PLplot clips drawing to the current viewport).
    pls.vpor(0.78, 0.99, 0.14, 0.9);
    pls.wind(0, 1, 0, 1);
    for (size_t k = 0; k < plot.series.size(); ++k) {
      const double ly = 0.95 - 0.07 * static_cast<double>(k);
      use_series_colour(pls, static_cast<int>(k));
      pls.width(2.0);
      pls.lsty(plot.series[k].dashed ? 2 : 1);
      pls.join(0.02, ly, 0.22, ly);
      pls.lsty(1);
      use_axis_colour(pls);
      pls.ptex(0.27, ly, 1, 0, 0, plot.series[k].label.c_str());
    }
  });
}

}  // namespace crowdlab::analysis
