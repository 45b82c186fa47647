#include "stimuli/decode_luma.hpp"

#include "framework/media/video_reader.hpp"

namespace crowdlab::stimuli {

std::vector<cv::Mat> decode_luma(const std::string& path) {
  VideoReader reader(path);
  std::vector<cv::Mat> frames;
  while (reader.next()) {
    frames.emplace_back(reader.height(), reader.width(), CV_8UC1);
    reader.copy_luma(frames.back().data, frames.back().step);
  }
  return frames;
}

cv::Mat rgba_to_luma_bt709(const std::uint8_t* rgba, int width, int height, bool bottom_up) {
  cv::Mat y(height, width, CV_8UC1);
  for (int row = 0; row < height; ++row) {
    const std::uint8_t* src = rgba + static_cast<size_t>(bottom_up ? height - 1 - row : row) * 4 * width;
    std::uint8_t* dst = y.ptr<std::uint8_t>(row);
    for (int x = 0; x < width; ++x, src += 4) {
      const double luma = 0.2126 * src[0] + 0.7152 * src[1] + 0.0722 * src[2];
      dst[x] = static_cast<std::uint8_t>(16.0 + 219.0 * luma / 255.0 + 0.5);
    }
  }
  return y;
}

}  // namespace crowdlab::stimuli
