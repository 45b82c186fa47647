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

}  // namespace crowdlab::analysis
