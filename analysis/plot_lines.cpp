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
    pls.mtex("b", 3.2, 0.5, 0.5, plot.x_label.c_str());
    pls.mtex("l", 4.0, 0.5, 0.5, plot.y_label.c_str());
    pls.mtex("t", 1.5, 0.5, 0.5, plot.title.c_str());
    if (!plot.note.empty()) {
      pls.schr(0, 0.8);
      pls.mtex("t", 0.4, 1.0, 1.0, plot.note.c_str());
      pls.schr(0, 1.1);
    }
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
    // Legend in its own viewport right of the plot (PLplot clips drawing to the current viewport).
    pls.vpor(0.80, 0.99, 0.14, 0.9);
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
