#include "analysis/plot_style.hpp"

#include <plplot/plstream.h>

#include <array>
#include <filesystem>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
// Okabe & Ito (2008) colour-blind-safe palette.
constexpr std::array<std::array<int, 3>, kPaletteSize> kPalette = {
    {{0, 114, 178}, {213, 94, 0}, {0, 158, 115}, {204, 121, 167}, {230, 159, 0}, {86, 180, 233}, {0, 0, 0}}};
}  // namespace

void use_series_colour(plstream& pls, int i) {
  pls.col0(2 + (i % kPaletteSize));
}
void use_axis_colour(plstream& pls) {
  pls.col0(1);
}

void render_figure(const std::string& path_stem, int width, int height,
                   const std::function<void(plstream&)>& draw) {
  for (const char* device : {"pngcairo", "svgcairo"}) {
    const std::string path = path_stem + (std::string(device) == "pngcairo" ? ".png" : ".svg");
    {
      plstream pls;
      pls.sdev(device);
      pls.sfnam(path.c_str());
      pls.spage(0, 0, width, height, 0, 0);
      pls.scolbg(255, 255, 255);
      pls.scol0(1, 0, 0, 0);
      for (int i = 0; i < kPaletteSize; ++i)
        pls.scol0(2 + i, kPalette[static_cast<size_t>(i)][0], kPalette[static_cast<size_t>(i)][1],
                  kPalette[static_cast<size_t>(i)][2]);
      pls.init();
      pls.adv(0);
      draw(pls);
    }  // the destructor finishes the page and closes the file
    if (!std::filesystem::exists(path) || std::filesystem::file_size(path) == 0)
      throw RuntimeError("PLplot device '" + std::string(device) + "' wrote nothing to " + path +
                         " (is plplot-driver-cairo installed?)");
  }
}

void draw_titles(plstream& pls, const std::string& title, const std::string& x_label,
                 const std::string& y_label, const std::string& note) {
  use_axis_colour(pls);
  pls.mtex("b", 3.2, 0.5, 0.5, x_label.c_str());
  pls.mtex("l", 4.0, 0.5, 0.5, y_label.c_str());
  pls.mtex("t", 1.5, 0.5, 0.5, title.c_str());
  if (!note.empty()) {
    PLFLT default_mm = 0, current_mm = 0;
    pls.gchr(default_mm, current_mm);
    pls.schr(0, 0.8);
    pls.mtex("t", 0.4, 1.0, 1.0, note.c_str());
    pls.schr(0, default_mm > 0 ? current_mm / default_mm : 1.0);
  }
}

void draw_legend(plstream& pls, const std::vector<LegendEntry>& entries) {
  pls.vpor(0.80, 0.99, 0.14, 0.9);
  pls.wind(0, 1, 0, 1);
  for (size_t k = 0; k < entries.size(); ++k) {
    const double ly = 0.95 - 0.07 * static_cast<double>(k);
    use_series_colour(pls, static_cast<int>(k));
    pls.width(2.0);
    pls.lsty(entries[k].line_style);
    pls.join(0.02, ly, 0.22, ly);
    pls.lsty(1);
    if (entries[k].marker != 0) {
      PLFLT px = 0.12, py = ly;
      pls.poin(1, &px, &py, entries[k].marker);
    }
    use_axis_colour(pls);
    pls.ptex(0.27, ly, 1, 0, 0, entries[k].label.c_str());
  }
}

}  // namespace crowdlab::analysis
