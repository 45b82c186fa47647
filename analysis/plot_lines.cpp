#include "analysis/plot_lines.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>

#include "analysis/plot_style.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  /// Widened by `pad` of its span (a flat range gets a unit-sized span).
  void pad(double fraction) {
    const double span = hi > lo ? hi - lo : std::max(1.0, std::abs(hi));
    lo -= fraction * span;
    hi += fraction * span;
  }
};

void check_series(const LinePlot& plot) {
  if (plot.series.empty()) throw InputError("line plot '" + plot.title + "': no series");
  for (const auto& s : plot.series) {
    if (s.x.empty() || s.x.size() != s.y.size())
      throw InputError("line plot '" + plot.title + "': series '" + s.label +
                       "' is empty or has x and y of different lengths");
    for (size_t i = 0; i < s.x.size(); ++i)
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        throw InputError("line plot '" + plot.title + "': series '" + s.label + "' has a non-finite value");
  }
}

}  // namespace

void plot_lines(const LinePlot& plot, const std::string& path_stem) {
  check_series(plot);
  Range xr, yr;
  for (const auto& s : plot.series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
  if (plot.y_max > plot.y_min) {
    yr.lo = plot.y_min;
    yr.hi = plot.y_max;
  } else {
    yr.pad(0.08);
  }
  if (!(xr.hi > xr.lo)) xr.pad(0.5);
  render_figure(path_stem, 900, 600, [&](plstream& pls) {
    pls.schr(0, 1.1);
    pls.vpor(0.12, 0.78, 0.14, 0.9);
    pls.wind(xr.lo, xr.hi, yr.lo, yr.hi);
    use_axis_colour(pls);
    pls.box("bcnst", 0, 0, "bcnstv", 0, 0);
    draw_titles(pls, plot.title, plot.x_label, plot.y_label, plot.note);
    pls.lsty(3);
    for (double m : plot.x_markers) pls.join(m, yr.lo, m, yr.hi);
    for (size_t k = 0; k < plot.series.size(); ++k) {
      const auto& s = plot.series[k];
      use_series_colour(pls, static_cast<int>(k));
      pls.width(2.0);
      pls.lsty(s.dashed ? 2 : 1);
      pls.line(static_cast<PLINT>(s.x.size()), s.x.data(), s.y.data());
    }
    pls.lsty(1);
    std::vector<LegendEntry> legend;
    for (const auto& series : plot.series) legend.push_back({series.label, series.dashed ? 2 : 1, 0});
    draw_legend(pls, legend);
  });
}

}  // namespace crowdlab::analysis
