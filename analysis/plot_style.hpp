#pragma once
// Shared PLplot set-up for crowdlab figures: white background, a fixed colour-blind-safe palette
// (Okabe & Ito 2008), one call per output format (PNG via pngcairo, SVG via svgcairo).
#include <functional>
#include <string>

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

}  // namespace crowdlab::analysis
