#pragma once
// PNG files of 8-bit images, written through libpng (1.6, Debian 12): the rendered frames and contact
// sheets of `crowdlab render`, the study window's snapshots.
//
// Why not cv::imencode / cv::imwrite: libopencv_imgcodecs loads about 140 shared libraries (GDAL, GDCM,
// OpenEXR, ...) at every start of the `crowdlab` binary (issue 31, session 17; docs/building.md).
//
// Pixels are packed rows of 8-bit samples in OpenCV's order: 1 channel grey, 3 BGR, 4 BGRA; `stride_bytes`
// between rows. Encoding uses OpenCV's PNG settings (zlib level 1, run-length, the Sub filter): the same
// bytes as the cv::imencode it replaced, at its speed (frames are written per clip).
// Errors: InputError for a channel count or size it cannot write; RuntimeError with libpng's message, or
// (write_png_file) naming the file and the OS's reason, e.g. a full disk (issue 21).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace crowdlab {

/// The PNG file bytes of an image (`channels` 1, 3 or 4).
std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels,
                                     std::size_t stride_bytes);

/// encode_png, then the bytes written to `path` (write_text_file).
void write_png_file(const std::string& path, const std::uint8_t* pixels, int width, int height, int channels,
                    std::size_t stride_bytes);

}  // namespace crowdlab
