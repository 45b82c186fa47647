// The clean image's anti-aliasing on the CPU (stimuli/fxaa_rgba.hpp): which pixels it touches, that it
// brings an aliased edge closer to its area-sampled truth, and that borders and tiny images are safe.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "framework/core/error.hpp"
#include "stimuli/fxaa_rgba.hpp"

using namespace crowdlab::stimuli;

namespace {

struct AaFrame {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  AaFrame(int w, int h, std::uint8_t grey) : width(w), height(h), rgba(static_cast<size_t>(w) * h * 4, grey) {
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  }
  std::uint8_t* at(int x, int y) { return rgba.data() + offset(x, y); }
  const std::uint8_t* at(int x, int y) const { return rgba.data() + offset(x, y); }
  size_t offset(int x, int y) const { return (static_cast<size_t>(y) * width + x) * 4; }
  void set_grey(int x, int y, std::uint8_t v) { at(x, y)[0] = at(x, y)[1] = at(x, y)[2] = v; }
};

// A frame whose left `columns` columns are `left` and the rest `right`: one vertical step edge.
AaFrame aa_vertical_step(int columns, std::uint8_t left, std::uint8_t right) {
  AaFrame f(16, 12, right);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < columns; ++x) f.set_grey(x, y, left);
  return f;
}

// The dark side of the line y = y0 + slope x, as the share of each pixel it covers: `samples` x `samples`
// point samples per pixel (area sampling, the truth), or one at the pixel centre (what a rasteriser
// without multisampling draws). Dark is 40, light 220.
std::vector<double> aa_half_plane(int width, int height, double slope, double y0, int samples) {
  std::vector<double> grey(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int dark = 0;
      for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
          const double sx = x + (i + 0.5) / samples, sy = y + (j + 0.5) / samples;
          dark += sy < y0 + slope * sx;
        }
      const double share = static_cast<double>(dark) / (samples * samples);
      grey[static_cast<size_t>(y) * width + x] = 220.0 - 180.0 * share;
    }
  return grey;
}

}  // namespace

TEST_CASE("fxaa_rgba leaves flat and low-contrast frames bit for bit", "[stimuli][fast]") {
  AaFrame flat(20, 10, 128);
  const auto before = flat.rgba;
  CHECK(fxaa_edge_pixels(flat.rgba, flat.width, flat.height) == 0);
  fxaa_rgba(flat.rgba, flat.width, flat.height);
  CHECK(flat.rgba == before);
  // A ramp of 5 levels a pixel (10 over a pixel's two neighbours): under the 1/24 of full scale (10.6
  // levels) that FXAA's edge test asks for.
  AaFrame ramp(20, 10, 0);
  for (int y = 0; y < ramp.height; ++y)
    for (int x = 0; x < ramp.width; ++x) ramp.set_grey(x, y, static_cast<std::uint8_t>(5 * x));
  const auto ramp_before = ramp.rgba;
  CHECK(fxaa_edge_pixels(ramp.rgba, ramp.width, ramp.height) == 0);
  fxaa_rgba(ramp.rgba, ramp.width, ramp.height);
  CHECK(ramp.rgba == ramp_before);
}

TEST_CASE("fxaa_rgba's edge test: 11 levels of span, and at least 1/8 of the brightest", "[stimuli][fast]") {
  // Absolute floor: a step of 10 levels is no edge, 11 is (on both sides of it: two columns).
  CHECK(fxaa_edge_pixels(aa_vertical_step(8, 40, 50).rgba, 16, 12) == 0);
  CHECK(fxaa_edge_pixels(aa_vertical_step(8, 40, 51).rgba, 16, 12) == 2 * 12);
  // Relative: at 200, a span of 24 (< 200 / 8) is no edge, 25 is.
  CHECK(fxaa_edge_pixels(aa_vertical_step(8, 176, 200).rgba, 16, 12) == 0);
  CHECK(fxaa_edge_pixels(aa_vertical_step(8, 175, 200).rgba, 16, 12) == 2 * 12);
}

TEST_CASE("fxaa_rgba softens only the stair steps of an edge, keeps alpha, and leaves straight edges",
          "[stimuli][fast]") {
  // A straight vertical edge is not aliased: FXAA blends along the edge, i.e. within each side.
  AaFrame straight = aa_vertical_step(8, 30, 230);
  const auto straight_before = straight.rgba;
  fxaa_rgba(straight.rgba, straight.width, straight.height);
  CHECK(straight.rgba == straight_before);
  // A staircase: dark below y = 2 + x / 4 (rounded down), light above, one alpha that must survive.
  AaFrame f(24, 12, 230);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      if (y < 2 + x / 4) f.set_grey(x, y, 30);
      f.at(x, y)[3] = static_cast<std::uint8_t>(100 + x);
    }
  const AaFrame before = f;
  fxaa_rgba(f.rgba, f.width, f.height);
  int changed = 0;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      INFO("pixel " << x << ", " << y);
      const std::uint8_t* p = f.at(x, y);
      CHECK(p[3] == before.at(x, y)[3]);
      CHECK((p[0] == p[1] && p[1] == p[2]));           // grey stays grey
      const int distance = std::abs(y - (2 + x / 4));  // rows from the first light row of this column
      if (p[0] == before.at(x, y)[0]) continue;
      ++changed;
      CHECK(distance <= 1);  // only pixels beside the edge
    }
  CHECK(changed >= f.width);  // every step softened
}

TEST_CASE("fxaa_rgba brings an aliased shallow edge closer to its area-sampled truth", "[stimuli][fast]") {
  const int w = 64, h = 32;
  // A shallow line (1 px up every 7): the long stair steps that FXAA is made for.
  const std::vector<double> truth = aa_half_plane(w, h, 1.0 / 7.0, 10.3, 16);
  const std::vector<double> aliased = aa_half_plane(w, h, 1.0 / 7.0, 10.3, 1);
  AaFrame f(w, h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      f.set_grey(x, y, static_cast<std::uint8_t>(aliased[static_cast<size_t>(y) * w + x]));
  fxaa_rgba(f.rgba, w, h);
  double error_before = 0.0, error_after = 0.0;
  int edge_pixels = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (std::abs(truth[i] - aliased[i]) < 1.0 && f.at(x, y)[0] == static_cast<std::uint8_t>(aliased[i]))
        continue;
      ++edge_pixels;
      error_before += std::abs(aliased[i] - truth[i]);
      error_after += std::abs(f.at(x, y)[0] - truth[i]);
    }
  INFO("edge pixels " << edge_pixels << ", mean error " << error_before / edge_pixels << " -> "
                      << error_after / edge_pixels << " levels");
  REQUIRE(edge_pixels > w);
  CHECK(error_after < 0.75 * error_before);
}

TEST_CASE("fxaa_rgba at the image's borders and on tiny images", "[stimuli][fast]") {
  // An edge along every border (a bright frame around dark): taps beyond the image repeat its border.
  for (const auto& [w, h] :
       std::vector<std::pair<int, int>>{{1, 1}, {1, 7}, {7, 1}, {2, 2}, {3, 3}, {13, 9}}) {
    INFO(w << " x " << h);
    AaFrame f(w, h, 20);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (x == 0 || y == 0 || x == w - 1 || y == h - 1) f.set_grey(x, y, 240);
    fxaa_rgba(f.rgba, w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        CHECK(f.at(x, y)[0] >= 20);
        CHECK(f.at(x, y)[0] <= 240);
        CHECK(f.at(x, y)[3] == 255);
      }
  }
}

TEST_CASE("fxaa_rgba refuses a buffer that is not the frame it is told", "[stimuli][fast]") {
  AaFrame f(8, 4, 100);
  CHECK_THROWS_AS(fxaa_rgba(f.rgba, 8, 5), crowdlab::RuntimeError);
  CHECK_THROWS_AS(fxaa_rgba(f.rgba, 0, 4), crowdlab::RuntimeError);
  CHECK_THROWS_AS(fxaa_edge_pixels(f.rgba, 9, 4), crowdlab::RuntimeError);
  CHECK_NOTHROW(fxaa_rgba(f.rgba, 8, 4));
}
