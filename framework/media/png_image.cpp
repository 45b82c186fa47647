#include "framework/media/png_image.hpp"

#include <png.h>

#include <cstring>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

png_uint_32 format_of_channels(int channels) {
  switch (channels) {
    case 1:
      return PNG_FORMAT_GRAY;
    case 3:
      return PNG_FORMAT_BGR;
    case 4:
      return PNG_FORMAT_BGRA;
    default:
      throw InputError("PNG: " + std::to_string(channels) + " channels (1, 3 or 4 expected)");
  }
}

std::string libpng_message(const png_image& image) {
  return image.message[0] ? image.message : "libpng error";
}

}  // namespace

std::vector<std::uint8_t> encode_png(const std::uint8_t* pixels, int width, int height, int channels,
                                     std::size_t stride_bytes) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = format_of_channels(channels);
  image.flags = PNG_IMAGE_FLAG_FAST;
  // libpng counts the row stride in samples; with 8-bit samples that is the stride in bytes.
  const auto stride = static_cast<png_int_32>(stride_bytes);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, pixels, stride, nullptr))
    throw RuntimeError("PNG: cannot encode the image: " + libpng_message(image));
  std::vector<std::uint8_t> bytes(size);
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels, stride, nullptr))
    throw RuntimeError("PNG: cannot encode the image: " + libpng_message(image));
  bytes.resize(size);
  return bytes;
}

PngPixels read_png(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw RuntimeError(path + ": cannot read the PNG image: " + libpng_message(image));
  PngPixels out;
  const bool colour = (image.format & PNG_FORMAT_FLAG_COLOR) != 0;
  const bool alpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
  out.channels = colour ? (alpha ? 4 : 3) : (alpha ? 4 : 1);
  image.format = out.channels == 1 ? PNG_FORMAT_GRAY : out.channels == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_BGRA;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.bytes.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.bytes.data(), 0, nullptr)) {
    png_image_free(&image);
    throw RuntimeError(path + ": cannot decode the PNG image: " + libpng_message(image));
  }
  return out;
}

}  // namespace crowdlab
