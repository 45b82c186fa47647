#include "stimuli/render_quality.hpp"

#include <algorithm>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/quality/qualityssim.hpp>

#include "framework/core/error.hpp"
#include "stimuli/decode_luma.hpp"

namespace crowdlab::stimuli {
namespace {

cv::Mat reference_luma(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& reference,
                       const Camera& camera, int frame) {
  prepare_renderer(renderer, crowd, reference);
  renderer.draw(frame, camera, reference.scene);
  std::vector<std::uint8_t> rgba;
  renderer.read_rgba(rgba);
  return rgba_to_luma_bt709(rgba.data(), reference.width, reference.height, true);
}

}  // namespace

RenderOptions reference_render_options(const RenderOptions& fast) {
  RenderOptions reference = fast;
  reference.scene.msaa_samples = 4;
  reference.frames_png_dir.clear();
  return reference;
}

QualityReport measure_render_quality(Renderer& renderer, const CrowdAnimation& crowd,
                                     const RenderOptions& fast, const RenderOptions& reference,
                                     const std::vector<ViewpointId>& viewpoints, int frames,
                                     const std::vector<int>& sample_frames, const std::string& work_dir) {
  frames = std::min(frames, crowd.frame_count());
  for (int f : sample_frames)
    if (f < 0 || f >= frames)
      throw InputError("render quality: sample frame " + std::to_string(f) + " is outside [0, " +
                       std::to_string(frames) + ")");
  QualityReport report;
  const std::filesystem::path clip = std::filesystem::path(work_dir) / "crowdlab_quality_fast.mp4";
  for (const ViewpointId id : viewpoints) {
    RenderOptions o = fast;
    o.max_frames = frames;
    render_clip(renderer, crowd, o, id, clip.string());
    const std::vector<cv::Mat> decoded = decode_luma(clip.string());
    std::filesystem::remove(clip);
    const Viewpoint view(id, crowd, fast.width, fast.height, fast.viewpoint_overrides);
    for (int f : sample_frames) {
      if (static_cast<size_t>(f) >= decoded.size())
        throw RuntimeError("render quality: the clip decoded to " + std::to_string(decoded.size()) +
                           " frames");
      const cv::Mat ref = reference_luma(renderer, crowd, reference, view.at(f), f);
      const double ssim =
          cv::quality::QualitySSIM::compute(ref, decoded[static_cast<size_t>(f)], cv::noArray())[0];
      report.samples.push_back({view.name(), f, ssim, cv::PSNR(ref, decoded[static_cast<size_t>(f)])});
    }
  }
  std::vector<double> ssim;
  for (const QualitySample& s : report.samples) ssim.push_back(s.ssim);
  if (!ssim.empty()) {
    std::sort(ssim.begin(), ssim.end());
    report.ssim_min = ssim.front();
    report.ssim_median = ssim[ssim.size() / 2];
    report.psnr_min_db = std::min_element(report.samples.begin(), report.samples.end(), [](auto& a, auto& b) {
                           return a.psnr_db < b.psnr_db;
                         })->psnr_db;
  }
  return report;
}

}  // namespace crowdlab::stimuli
