#pragma once
// Psychometric curves in the style of seed 001 Figure 5: the proportion of "collision" answers per
// stimulus level (points with error bars: ±1 SE over participants), the fitted logistic per condition
// (one colour each), and the 50 % threshold marked by a dashed vertical line.
#include <string>
#include <vector>

namespace crowdlab::analysis {

struct PsychometricCurve {
  std::string label;                      ///< condition, e.g. "shoulder 1"
  std::vector<double> x, proportion, se;  ///< observed points
  double intercept = 0, slope = 0;        ///< fitted logistic (plain model)
  double threshold50 = 0;                 ///< marked with a dashed line (NaN: not drawn)
  bool fitted = true;                     ///< false: the points alone (the answers could not be fitted)
};

struct PsychometricPlot {
  std::string title, x_label, y_label = "P(answer = collision)";
  std::vector<PsychometricCurve> curves;
};

/// Writes <path_stem>.png and .svg.
void plot_psychometric(const PsychometricPlot& plot, const std::string& path_stem);

}  // namespace crowdlab::analysis
