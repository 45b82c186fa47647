#include "study_ui/text_renderer.hpp"

#include <filesystem>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "framework/core/error.hpp"

namespace crowdlab::study {

TextRenderer::TextRenderer(const std::string& font_path) {
  if (!std::filesystem::is_regular_file(font_path))
    throw RuntimeError(font_path +
                       ": font not found (install fonts-dejavu-core or pass another TrueType font)");
  ft_ = cv::freetype::createFreeType2();
  try {
    ft_->loadFontData(font_path, 0);
  } catch (const cv::Exception& e) {
    throw RuntimeError(font_path + ": cannot load font: " + e.what());
  }
}

cv::Size TextRenderer::measure(const std::string& text, int px) const {
  if (text.empty()) return {0, line_height(px)};
  int baseline = 0;
  const cv::Size s = ft_->getTextSize(text, px, -1, &baseline);
  return {s.width, line_height(px)};
}

void TextRenderer::draw(cv::Mat& canvas, const std::string& text, cv::Point top_left, int px,
                        cv::Scalar color) const {
  if (text.empty()) return;
  // cv::freetype places `org` on the baseline (bottomLeftOrigin = true); DejaVu's ascent is ~0.93 em,
  // centred in a 1.3 em line box.
  const int baseline_y = top_left.y + (line_height(px) - px) / 2 + (px * 93 + 50) / 100;
  ft_->putText(canvas, text, {top_left.x, baseline_y}, px, color, -1, cv::LINE_AA, true);
}

std::vector<std::string> TextRenderer::wrap(const std::string& text, int px, int max_width) const {
  std::vector<std::string> lines;
  std::stringstream paragraphs(text);
  std::string paragraph;
  while (std::getline(paragraphs, paragraph, '\n')) {
    std::stringstream words(paragraph);
    std::string word, line;
    bool any = false;
    while (words >> word) {
      any = true;
      const std::string candidate = line.empty() ? word : line + " " + word;
      if (!line.empty() && measure(candidate, px).width > max_width) {
        lines.push_back(line);
        line = word;
      } else {
        line = candidate;
      }
    }
    lines.push_back(any ? line : std::string());
  }
  return lines;
}

}  // namespace crowdlab::study
