#pragma once
// Test stimuli and specs for the study tests: tiny MP4 clips written with OpenCV (mp4v, 160x90,
// 10 frames, each clip a different flat colour with a moving bar), a manifest.csv via
// write_manifest() with real sha256 values, and typed specs built in code.
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "tests/support/test_paths.hpp"

namespace crowdlab::test {

inline void write_test_clip(const std::string& path, int variant, int frames = 10) {
  cv::VideoWriter w(path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 30.0, cv::Size(160, 90));
  REQUIRE(w.isOpened());
  for (int f = 0; f < frames; ++f) {
    cv::Mat img(90, 160, CV_8UC3, cv::Scalar(40 + 25 * (variant % 8), 90, 200 - 20 * (variant % 8)));
    cv::rectangle(img, cv::Rect(10 + 14 * f, 30, 12, 30), cv::Scalar(250, 250, 250), cv::FILLED);
    w.write(img);
  }
}

/// A manifest over the crossing of `factors` (one clip per cell) plus `practice` practice clips.
/// Clip files are shared between cells with the same variant to keep tests fast.
inline StimulusManifest make_stimuli(
    const std::filesystem::path& dir,
    const std::vector<std::pair<std::string, std::vector<std::string>>>& factors, int practice = 0) {
  std::filesystem::create_directories(dir / "clips");
  StimulusManifest m;
  for (const auto& f : factors) m.factor_names.push_back(f.first);
  size_t cells = 1;
  for (const auto& f : factors) cells *= f.second.size();
  auto add = [&](const std::string& id, std::map<std::string, std::string> levels, int variant,
                 bool is_practice) {
    const std::string file = "clips/v" + std::to_string(variant) + ".mp4";
    if (!std::filesystem::exists(dir / file)) write_test_clip((dir / file).string(), variant);
    StimulusEntry e;
    e.id = id;
    e.factors = std::move(levels);
    e.file = file;
    e.duration_s = 10.0 / 30.0;
    e.frames = 10;
    e.width = 160;
    e.height = 90;
    e.sha256 = sha256_file_hex((dir / file).string());
    e.practice = is_practice;
    m.entries.push_back(std::move(e));
  };
  for (size_t c = 0; c < cells; ++c) {
    std::map<std::string, std::string> levels;
    std::string id;
    size_t rest = c;
    for (size_t i = factors.size(); i-- > 0;) {
      const auto& f = factors[i];
      levels[f.first] = f.second[rest % f.second.size()];
      rest /= f.second.size();
    }
    for (const auto& f : factors) id += (id.empty() ? "" : "_") + f.first + "-" + levels[f.first];
    add(id, levels, static_cast<int>(c % 4), false);
  }
  for (int p = 0; p < practice; ++p) {
    std::map<std::string, std::string> levels;
    for (const auto& f : factors) levels[f.first] = f.second[static_cast<size_t>(p) % f.second.size()];
    add("practice_" + std::to_string(p + 1), levels, 4 + p % 2, true);
  }
  write_manifest(m, (dir / "manifest.csv").string());
  return m;
}

inline ExperimentSpec likert_spec() {
  ExperimentSpec s;
  s.name = "test-likert";
  s.source_hash = "hash-likert";
  s.seed = 1234;
  s.protocol.type = ProtocolType::likert;
  s.protocol.composites = {{"Q_CR", {"Q1", "Q2"}}, {"Q_CA", {"Q3", "Q4"}}, {"Q_OR", {"Q5", "Q6"}}};
  return s;
}

inline ExperimentSpec afc_spec() {
  ExperimentSpec s;
  s.name = "test-2afc";
  s.source_hash = "hash-2afc";
  s.seed = 99;
  s.protocol.type = ProtocolType::two_afc;
  s.protocol.loop_video = false;
  return s;
}

}  // namespace crowdlab::test
