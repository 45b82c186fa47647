#pragma once
// measure_render_quality: how far a stimulus made on the fast path (the production render options, encoded
// to H.264 as a clip) is from a high-quality reference of the same frames (4x MSAA, the ground shaded with
// the shadow map every frame, and no encoding at all: the raw rendered pixels), per viewpoint and frame.
//
// Measure: SSIM of the luma planes (Wang, Bovik, Sheikh & Simoncelli, "Image quality assessment: from
// error visibility to structural similarity", IEEE TIP 13(4), 2004; OpenCV's cv::quality::QualitySSIM,
// 11x11 Gaussian window, sigma 1.5, K1 = 0.01, K2 = 0.03) and PSNR (dB). Luma is what video codecs
// measure (x264 --ssim) and it carries the edges that anti-aliasing and shadows change; the reference's
// luma is computed with the BT.709 coefficients the encoder uses (decode_luma.hpp).
#include <string>
#include <vector>

#include "stimuli/render_clip.hpp"

namespace crowdlab::stimuli {

struct QualitySample {
  std::string viewpoint;
  int frame = 0;
  double ssim = 0.0;
  double psnr_db = 0.0;
};

struct QualityReport {
  std::vector<QualitySample> samples;
  double ssim_min = 0.0, ssim_median = 0.0, psnr_min_db = 0.0;
};

/// Renders frames [0, frames) of `crowd` from each of `viewpoints` with `fast` into a temporary clip in
/// `work_dir` (deleted afterwards) and compares frames `sample_frames` (each < frames) of its decoded luma
/// with the same frames rendered with `reference`. Throws InputError when a sample frame is out of range.
QualityReport measure_render_quality(Renderer& renderer, const CrowdAnimation& crowd,
                                     const RenderOptions& fast, const RenderOptions& reference,
                                     const std::vector<ViewpointId>& viewpoints, int frames,
                                     const std::vector<int>& sample_frames, const std::string& work_dir);

/// The reference options for `fast`: the same scene, size and camera overrides with 4x MSAA.
RenderOptions reference_render_options(const RenderOptions& fast);

}  // namespace crowdlab::stimuli
