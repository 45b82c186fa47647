#include "stimuli/fxaa_rgba.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {

namespace {

constexpr std::size_t kChannels = 4;

// A colour as four floats (R, G, B, A on the 0-255 scale), one SIMD register: a bilinear tap is then a few
// vector instructions instead of three scalar channels (GCC/Clang vector extension; no FMA on the target,
// so the results are the same on every x86-64 machine).
using Colour = float __attribute__((vector_size(16)));
using Texel = std::uint8_t __attribute__((vector_size(4)));

// The four bytes of a pixel as floats. SSE2 (every x86-64) does it in four instructions; the compiler's own
// conversion of a byte vector goes through four scalar conversions, which made each tap three times slower.
Colour colour_of(const std::uint8_t* pixel) {
#if defined(__SSE2__)
  std::int32_t word;
  std::memcpy(&word, pixel, sizeof word);
  const __m128i zero = _mm_setzero_si128();
  const __m128i words = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(word), zero), zero);
  return reinterpret_cast<Colour>(_mm_cvtepi32_ps(words));
#else
  Texel t;
  std::memcpy(&t, pixel, sizeof t);
  return __builtin_convertvector(t, Colour);
#endif
}

float luma(const Colour& c) {
  return 0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2];
}

// The 8-bit luma of rows [first_row, last_row] of the frame, a band with a row either side: the Rec. 601
// weights in 8.8 fixed point (77 + 150 + 29 = 256), rounded. The sum stays below 2^16, and written in
// 16-bit terms the compiler vectorises it with 16-bit multiplies (SSE2 has no 32-bit one): 2.3x faster.
struct BandLuma {
  std::vector<std::uint8_t> rows;
  int first_row = 0;
};

void fill_band_luma(const std::vector<std::uint8_t>& rgba, int width, int first_row, int last_row,
                    BandLuma& band) {
  const std::size_t begin = static_cast<std::size_t>(first_row) * width;
  const std::size_t count = static_cast<std::size_t>(last_row - first_row + 1) * width;
  band.first_row = first_row;
  band.rows.resize(count);
  const std::uint8_t* src = rgba.data() + kChannels * begin;
  std::uint8_t* out = band.rows.data();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = src + kChannels * i;
    const auto sum = static_cast<std::uint16_t>(static_cast<std::uint16_t>(77 * p[0]) +
                                                static_cast<std::uint16_t>(150 * p[1]) +
                                                static_cast<std::uint16_t>(29 * p[2]) + 128);
    out[i] = static_cast<std::uint8_t>(sum >> 8);
  }
}

// FXAA's early exit in 8-bit luma: a pixel is filtered when the luma of it and its four edge neighbours
// spans at least max(1/24, 1/8 of their maximum) of full scale, i.e. span >= 11 and 8 span >= max. In
// bytes only, so that the compiler vectorises the row loop 16 pixels at a time (this test is what every
// pixel pays): 8 span >= max is span > (max - 1) / 8 for max >= 1 (max = 0 wraps to 31, and span is 0).
std::uint8_t edge_flag(std::uint8_t m, std::uint8_t below, std::uint8_t above, std::uint8_t left,
                       std::uint8_t right) {
  const std::uint8_t lo = std::min(std::min(std::min(m, below), std::min(above, left)), right);
  const std::uint8_t hi = std::max(std::max(std::max(m, below), std::max(above, left)), right);
  const auto span = static_cast<std::uint8_t>(hi - lo);
  const auto relative = static_cast<std::uint8_t>(static_cast<std::uint8_t>(hi - 1) >> 3);
  return static_cast<std::uint8_t>(span > std::max(static_cast<std::uint8_t>(10), relative));
}

// One row's edge flags (1 = filter), the image's border repeated beyond it.
void edge_flags_of_row(const std::uint8_t* below, const std::uint8_t* row, const std::uint8_t* above,
                       int width, std::uint8_t* flags) {
  const int last = width - 1;
  flags[0] = edge_flag(row[0], below[0], above[0], row[0], row[std::min(1, last)]);
  for (int x = 1; x < last; ++x) flags[x] = edge_flag(row[x], below[x], above[x], row[x - 1], row[x + 1]);
  if (last > 0) flags[last] = edge_flag(row[last], below[last], above[last], row[last - 1], row[last]);
}

// The frame and one band's luma, read by the filter. Interior pixels (at least kReach from every border, all
// of them but a thin frame) read their neighbours unclamped; the rest clamp to the border, as a
// GL_CLAMP_TO_EDGE texture does.
class Image {
 public:
  // The farthest any tap of an edge pixel reaches: half the 8-pixel span, plus the bilinear footprint.
  static constexpr int kReach = 6;
  static constexpr float kFloorShift = 16.0f;

  Image(const std::vector<std::uint8_t>& rgba, const BandLuma& luma, int width, int height)
      : rgba_(rgba), luma_(luma), width_(width), height_(height) {}

  bool interior(int x, int y) const {
    return x >= kReach && y >= kReach && x < width_ - kReach && y < height_ - kReach;
  }

  // The 8-bit luma at (x, y).
  template <bool kClamp>
  int luma_at(int x, int y) const {
    if constexpr (kClamp) {
      x = std::clamp(x, 0, width_ - 1);
      y = std::clamp(y, 0, height_ - 1);
    }
    return luma_.rows[static_cast<std::size_t>(y - luma_.first_row) * width_ + x];
  }

  // Bilinear colour at (x, y) in pixel units (pixel centres on integers): what a GL_LINEAR texture tap reads.
  template <bool kClamp>
  Colour bilinear(float x, float y) const {
    // Truncation floors a positive number: shifted by more than a tap reaches below 0 (no floorf call).
    int x0 = static_cast<int>(x + kFloorShift) - static_cast<int>(kFloorShift), x1 = x0 + 1;
    int y0 = static_cast<int>(y + kFloorShift) - static_cast<int>(kFloorShift), y1 = y0 + 1;
    const float tx = x - static_cast<float>(x0), ty = y - static_cast<float>(y0);
    if constexpr (kClamp) {
      x0 = std::clamp(x0, 0, width_ - 1);
      x1 = std::clamp(x1, 0, width_ - 1);
      y0 = std::clamp(y0, 0, height_ - 1);
      y1 = std::clamp(y1, 0, height_ - 1);
    }
    const Colour a = colour_of(texel(x0, y0)), b = colour_of(texel(x1, y0));
    const Colour c = colour_of(texel(x0, y1)), d = colour_of(texel(x1, y1));
    const Colour bottom = a + tx * (b - a), top = c + tx * (d - c);
    return bottom + ty * (top - bottom);
  }

  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }

 private:
  const std::uint8_t* texel(int x, int y) const { return rgba_.data() + kChannels * index(x, y); }

  const std::vector<std::uint8_t>& rgba_;
  const BandLuma& luma_;
  int width_, height_;
};

Colour mean(const Colour& a, const Colour& b) {
  return 0.5f * (a + b);
}

// The filtered colour of edge pixel (x, y): blended along the edge through it (see the header). Lumas stay
// integers (0-255) until the direction is scaled; every sum below is exact.
template <bool kClamp>
Colour filter_edge_pixel(const Image& image, int x, int y) {
  const int m = image.luma_at<kClamp>(x, y);
  const int n = image.luma_at<kClamp>(x, y + 1), s = image.luma_at<kClamp>(x, y - 1);
  const int e = image.luma_at<kClamp>(x + 1, y), w = image.luma_at<kClamp>(x - 1, y);
  const int nw = image.luma_at<kClamp>(x - 1, y + 1), ne = image.luma_at<kClamp>(x + 1, y + 1);
  const int sw = image.luma_at<kClamp>(x - 1, y - 1), se = image.luma_at<kClamp>(x + 1, y - 1);
  const int lo = std::min({m, n, s, e, w, nw, ne, sw, se});
  const int hi = std::max({m, n, s, e, w, nw, ne, sw, se});
  // The corners of the pixel as four times the 2x2 means around them.
  const int cnw = nw + n + w + m, cne = ne + n + e + m, csw = sw + s + w + m, cse = se + s + e + m;
  float dx = 0.25f * static_cast<float>((csw + cse) - (cnw + cne));
  float dy = 0.25f * static_cast<float>((cnw + csw) - (cne + cse));
  // Luma is on the 0-255 scale here, so the whitepaper's 1/128 floor of the reduction is 255/128.
  const float reduce =
      std::max(static_cast<float>(cnw + cne + csw + cse) * (0.25f * 0.25f / 8.0f), 255.0f / 128.0f);
  const float scale = 1.0f / (std::min(std::abs(dx), std::abs(dy)) + reduce);
  dx = std::clamp(dx * scale, -8.0f, 8.0f);
  dy = std::clamp(dy * scale, -8.0f, 8.0f);
  const float px = static_cast<float>(x), py = static_cast<float>(y);
  const Colour near = mean(image.bilinear<kClamp>(px - dx / 6.0f, py - dy / 6.0f),
                           image.bilinear<kClamp>(px + dx / 6.0f, py + dy / 6.0f));
  const Colour far = mean(image.bilinear<kClamp>(px - dx * 0.5f, py - dy * 0.5f),
                          image.bilinear<kClamp>(px + dx * 0.5f, py + dy * 0.5f));
  const Colour wide = mean(near, far);
  const float lw = luma(wide);
  return lw < static_cast<float>(lo) || lw > static_cast<float>(hi) ? near : wide;
}

// A filtered colour rounded to bytes (R, G, B, A in memory order; the channels lie within 0-255 already).
std::uint32_t bytes_of(const Colour& c) {
  const Colour rounded = c + 0.5f;
#if defined(__SSE2__)
  const __m128i words = _mm_cvttps_epi32(reinterpret_cast<__m128>(rounded));
  const __m128i halves = _mm_packs_epi32(words, words);
  return static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_packus_epi16(halves, halves)));
#else
  std::uint32_t out = 0;
  for (int k = 3; k >= 0; --k) out = (out << 8) | static_cast<std::uint32_t>(rounded[k]);
  return out;
#endif
}

// The luma of the band of rows [y_begin, y_end) with a row either side (inside the frame). A band's luma is
// computed where it is used, so the filter's taps find the band's pixels still in the cache.
BandLuma band_luma(const std::vector<std::uint8_t>& rgba, int width, int height, int y_begin, int y_end) {
  BandLuma luma;
  fill_band_luma(rgba, width, std::max(0, y_begin - 1), std::min(height - 1, y_end), luma);
  return luma;
}

// Calls visit(x, y) for every pixel of rows [y_begin, y_end) that passes the edge test, row by row, from
// `luma` (band_luma of those rows). Edge pixels are few (7 % of a dense 1080p crowd frame), so the flags
// are scanned eight at a time.
template <class Visit>
void for_each_edge_pixel(const BandLuma& luma, int width, int height, int y_begin, int y_end, Visit&& visit) {
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(width) + sizeof(std::uint64_t));
  const auto row = [&](int y) {
    return luma.rows.data() + static_cast<std::size_t>(std::clamp(y, 0, height - 1) - luma.first_row) * width;
  };
  for (int y = y_begin; y < y_end; ++y) {
    edge_flags_of_row(row(y - 1), row(y), row(y + 1), width, flags.data());
    for (int x = 0; x < width; x += 8) {
      std::uint64_t eight;
      std::memcpy(&eight, flags.data() + x, sizeof eight);
      if (eight == 0) continue;
      for (int k = x; k < std::min(x + 8, width); ++k)
        if (flags[static_cast<std::size_t>(k)]) visit(k, y);
    }
  }
}

// The frame is filtered in bands of rows, in parallel: on a GPU machine the filter would otherwise hold the
// encoder's thread for longer than the GPU takes to draw a frame. Each band's results are its own, so the
// output does not depend on the number of threads.
constexpr int kBandRows = 32;

// Throws unless `rgba` holds width * height pixels (whose indices fit 32 bits).
void check_frame(const std::vector<std::uint8_t>& rgba, int width, int height) {
  const std::size_t pixels =
      static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0));
  if (width < 1 || height < 1 || rgba.size() != pixels * kChannels || pixels > UINT32_MAX)
    throw RuntimeError("fxaa_rgba: " + std::to_string(rgba.size()) + " bytes are not a " +
                       std::to_string(width) + " x " + std::to_string(height) + " RGBA frame");
}

}  // namespace

void fxaa_rgba(std::vector<std::uint8_t>& rgba, int width, int height) {
  check_frame(rgba, width, height);
  // Reused across frames (per calling thread). Named through a reference, because a thread_local named
  // inside the parallel loop would be the worker thread's own.
  thread_local std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> filtered_buffer;
  auto& filtered = filtered_buffer;  // per band: the filtered pixels' indices and RGBA bytes
  const int bands = (height + kBandRows - 1) / kBandRows;
  filtered.resize(static_cast<std::size_t>(bands));
  tbb::parallel_for(0, bands, [&](int band) {
    auto& out = filtered[static_cast<std::size_t>(band)];
    out.clear();
    const int y_begin = band * kBandRows, y_end = std::min(height, y_begin + kBandRows);
    const BandLuma luma = band_luma(rgba, width, height, y_begin, y_end);
    const Image image(rgba, luma, width, height);
    for_each_edge_pixel(luma, width, height, y_begin, y_end, [&](int x, int y) {
      const Colour c =
          image.interior(x, y) ? filter_edge_pixel<false>(image, x, y) : filter_edge_pixel<true>(image, x, y);
      out.emplace_back(static_cast<std::uint32_t>(image.index(x, y)), bytes_of(c));
    });
  });
  // Written once every band is done, so that every tap read the unfiltered frame.
  tbb::parallel_for(0, bands, [&](int band) {
    for (const auto& [i, bytes] : filtered[static_cast<std::size_t>(band)])
      std::memcpy(rgba.data() + kChannels * i, &bytes, 3);  // alpha kept
  });
}

std::size_t fxaa_edge_pixels(const std::vector<std::uint8_t>& rgba, int width, int height) {
  check_frame(rgba, width, height);
  std::size_t count = 0;
  for_each_edge_pixel(band_luma(rgba, width, height, 0, height), width, height, 0, height,
                      [&](int, int) { ++count; });
  return count;
}

}  // namespace crowdlab::stimuli
