#pragma once
// Shared PLplot set-up for crowdlab figures: white background, a fixed colour-blind-safe palette
// (Okabe & Ito 2008), one call per output format (PNG via pngcairo, SVG via svgcairo).
#include <functional>
#include <string>
#include <vector>

class plstream;

namespace crowdlab::analysis {

/// Number of series colours in the palette (indices 2.. of colour map 0).
constexpr int kPaletteSize = 7;

/// Calls `draw` once per format with a ready stream (page width x height pixels), writing
/// `<path_stem>.png` and `<path_stem>.svg`. Throws RuntimeError when a device is missing.
void render_figure(const std::string& path_stem, int width, int height,
                   const std::function<void(plstream&)>& draw);

/// Selects series colour i (wrapping) as the current colour.
void use_series_colour(plstream& pls, int i);
/// Black, for axes and text.
void use_axis_colour(plstream& pls);

/// The texts around the plot area of the current viewport: title above, x label below, y label left,
/// and `note` (may be empty) small above the right edge.
void draw_titles(plstream& pls, const std::string& title, const std::string& x_label,
                 const std::string& y_label, const std::string& note = "");

/// One legend row: series colour i (row order), line style (PLplot lsty, 1 = solid), marker glyph
/// (PLplot poin code; 0 = none).
struct LegendEntry {
  std::string label;
  int line_style = 1;
  int marker = 0;
};

/// The legend in its own viewport right of the plot area (x 0.80..0.99; PLplot clips drawing to the
/// current viewport), one row per entry from the top. Leaves that viewport current.
void draw_legend(plstream& pls, const std::vector<LegendEntry>& entries);

}  // namespace crowdlab::analysis
