#pragma once
// Line plots of numeric series against a numeric x axis (e.g. position versus time, seed 000
// Figure 4): one coloured line per series, an optional dashed reference series drawn on top, optional
// vertical marker lines, and a legend to the right.
#include <string>
#include <vector>

namespace crowdlab::analysis {

struct LineSeries {
  std::string label;      ///< legend text
  std::vector<double> x;  ///< abscissae, in the x axis unit
  std::vector<double> y;  ///< ordinates, same length as x
  bool dashed = false;    ///< draw dashed (e.g. a target or reference)
};

struct LinePlot {
  std::string title;
  std::string x_label;  ///< with unit, e.g. "Time (s)"
  std::string y_label;  ///< with unit, e.g. "Root x (m)"
  std::vector<LineSeries> series;
  std::vector<double> x_markers;  ///< vertical dotted lines (e.g. the collision time)
  double y_min = 0, y_max = 0;    ///< y_min == y_max: fitted to the data
  std::string note;               ///< small text top right
};

/// Writes <path_stem>.png and <path_stem>.svg. Throws InputError when there are no series, a series
/// has x and y of different lengths or fewer than two points, or holds a non-finite value.
void plot_lines(const LinePlot& plot, const std::string& path_stem);

}  // namespace crowdlab::analysis
