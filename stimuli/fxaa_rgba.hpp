#pragma once
// fxaa_rgba: fast approximate anti-aliasing of a finished 8-bit RGBA frame, on the CPU (the clean image's
// anti-aliasing, docs/stimuli.md "Clean image").
//
// Method: FXAA's console variant (T. Lottes, "FXAA", NVIDIA whitepaper, 2009/2011). A pixel whose luma and
// that of its four edge neighbours span less than max(1/24, 1/8 of their maximum) is left alone (most
// pixels). Elsewhere the edge direction comes from the luma of the pixel's four corners (the 2x2 means
// around them); the pixel becomes the mean of two bilinear taps at +-1/6 of the direction's span (clamped
// to 8 px), or of four taps (+-1/2 as well) unless their luma leaves the 3x3 neighbourhood's luma range.
// Luma: Rec. 601 weights (0.299, 0.587, 0.114) on the stored (gamma-encoded) values.
//
// Why on the CPU (session 28): the same filter as a full-screen OpenGL pass cost llvmpipe 20 ms of a 1080p
// frame (about 10 ns a pixel, most of it the early-exit test every pixel pays). Here the test runs over
// 8-bit luma rows that the compiler vectorises, and only edge pixels pay for the filter (SSE2 for its
// bilinear taps); it runs on the encoder's thread beside the next frame's draw (render_clip.cpp), over
// bands of rows in parallel.
//
// Input/output: `rgba`, width * height pixels of 4 bytes (rows in either order: the filter treats up and
// down alike, up to rounding), filtered in place; alpha is kept. Deterministic: a pure function of the
// input, whatever the number of threads.
#include <cstdint>
#include <vector>

namespace crowdlab::stimuli {

/// Anti-aliases `rgba` (width * height * 4 bytes, width and height >= 1) in place. RuntimeError when the
/// buffer is not that size (a caller's bug: frames come from the renderer).
void fxaa_rgba(std::vector<std::uint8_t>& rgba, int width, int height);

/// The number of pixels fxaa_rgba() would filter (its edge test passed), for benchmarks and tests.
std::size_t fxaa_edge_pixels(const std::vector<std::uint8_t>& rgba, int width, int height);

}  // namespace crowdlab::stimuli
