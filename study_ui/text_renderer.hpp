#pragma once
// TextRenderer: FreeType text for the study window (cv::freetype over a TrueType font; DejaVu Sans by
// default, Debian fonts-dejavu-core), with measuring and word wrapping. Positions are the top-left
// corner of the text's line box, in pixels.
#include <opencv2/core.hpp>
#include <opencv2/freetype.hpp>
#include <string>
#include <vector>

namespace crowdlab::study {

class TextRenderer {
 public:
  /// Throws RuntimeError when the font file is missing or cannot be loaded.
  explicit TextRenderer(const std::string& font_path);
  /// Width and height of one line at `px` pixels.
  cv::Size measure(const std::string& text, int px) const;
  /// Draws one line with its line box's top-left corner at `top_left`.
  void draw(cv::Mat& canvas, const std::string& text, cv::Point top_left, int px, cv::Scalar color) const;
  /// Splits text into lines no wider than `max_width` (explicit '\n' are kept; a single word wider
  /// than max_width gets its own line).
  std::vector<std::string> wrap(const std::string& text, int px, int max_width) const;
  /// Line advance for a font size (1.3 x px: DejaVu's ascent + descent is about 1.17 em).
  static int line_height(int px) { return (px * 13 + 9) / 10; }

 private:
  cv::Ptr<cv::freetype::FreeType2> ft_;
};

}  // namespace crowdlab::study
