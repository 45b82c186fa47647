#pragma once
// Line plots of y against a continuous x, one polyline per series (e.g. seed 000 Figure 4: a
// character's position against time for several dampings), with optional vertical marker lines.
#include <string>
#include <vector>

namespace crowdlab::analysis {

struct LineSeries {
  std::string label;      ///< legend text
  std::vector<double> x;  ///< same length as y, any order is drawn as given
  std::vector<double> y;
  bool dashed = false;  ///< e.g. a target or reference curve
};

struct LinePlot {
  std::string title, x_label, y_label, note;
  std::vector<LineSeries> series;
  std::vector<double> x_markers;  ///< dotted vertical lines (e.g. the time of a shove)
  double y_min = 0, y_max = 0;    ///< y_min == y_max: fitted to the data
};

/// Writes <path_stem>.png and <path_stem>.svg. Throws InputError for no series, an empty series,
/// mismatched x/y lengths or non-finite values.
void plot_lines(const LinePlot& plot, const std::string& path_stem);

}  // namespace crowdlab::analysis
