#pragma once
// PNG files of 8-bit images, through libpng's simplified API (libpng 1.6, Debian 12): the rendered frames
// and contact sheets of `crowdlab render`, the study window's snapshots.
//
// Why not cv::imencode / cv::imwrite: libopencv_imgcodecs loads about 140 shared libraries (GDAL, GDCM,
// OpenEXR, ...) at every start of the `crowdlab` binary (issue 31, session 17; docs/building.md).
//
// Pixels are packed rows of 8-bit samples in OpenCV's order: 1 channel grey, 3 BGR, 4 BGRA; `stride_bytes`
// between rows. Encoding uses OpenCV's PNG settings (zlib level 1, run-length, the Sub filter): the same
// bytes as the cv::imencode it replaced, at its speed (frames are written per clip).
// Errors: RuntimeError naming the file (or "PNG" in memory) and libpng's message.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace crowdlab {

struct PngPixels {
  int width = 0;
  int height = 0;
  int channels = 0;                 ///< 1 grey, 3 BGR, 4 BGRA
  std::vector<std::uint8_t> bytes;  ///< height rows of width * channels bytes, no padding
};

/// The PNG file bytes of an image (`channels` 1, 3 or 4).
std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels,
                                     std::size_t stride_bytes);

/// Reads a PNG file as 8-bit grey (a grey file), BGR (colour) or BGRA (with alpha).
PngPixels read_png(const std::string& path);

}  // namespace crowdlab
