#pragma once
// Interaction plots in the style of seed 000 Figures 9 and 10: the mean answer per level of one factor
// (x axis, categorical), one line per level of a second factor, error bars, and significance stars
// for the comparison between the lines at each x level.
#include <string>
#include <vector>

namespace crowdlab::analysis {

struct InteractionSeries {
  std::string label;          ///< legend text (e.g. "Ours")
  std::vector<double> mean;   ///< one per x level
  std::vector<double> error;  ///< half-length of the error bar, one per x level
};

struct InteractionPlot {
  std::string title;
  std::string x_label;  ///< with unit, e.g. "Density (characters/m²)"
  std::string y_label;  ///< with unit/scale, e.g. "Answer (1-6 Likert)"
  std::vector<std::string> x_levels;
  std::vector<InteractionSeries> series;
  std::vector<std::string> stars;  ///< per x level ("", "*", "**", "***"), drawn above the points
  double y_min = 0, y_max = 0;     ///< y_min == y_max: fitted to the data
  std::string note;                ///< e.g. "error bars: ±1 SD"
};

/// Writes <path_stem>.png and <path_stem>.svg. Throws InputError when series lengths differ from x_levels.
void plot_interaction(const InteractionPlot& plot, const std::string& path_stem);

}  // namespace crowdlab::analysis
