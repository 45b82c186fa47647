#pragma once
// decode_luma: the luma (Y') planes of every frame of a video file, as libavcodec decodes them (no colour
// conversion, so nothing but the codec stands between the encoder's input and what is measured). Used to
// measure what H.264 encoding costs a stimulus (render_quality.hpp); SSIM on luma is how video coding
// reports quality (x264's --ssim, Wang et al. 2004).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace crowdlab::stimuli {

/// Every frame's Y' plane (CV_8UC1, width x height, top row first), in presentation order.
/// Throws RuntimeError when the file cannot be opened or decoded.
std::vector<cv::Mat> decode_luma(const std::string& path);

/// The BT.709 limited-range luma of an RGBA image (8 bits per channel, `bottom_up` as glReadPixels gives
/// it): Y' = 16 + 219 (0.2126 R' + 0.7152 G' + 0.0722 B') / 255, the conversion video_encoder.cpp asks
/// libswscale for (ITU-R BT.709-6, Table 3 items 3.2-3.3).
cv::Mat rgba_to_luma_bt709(const std::uint8_t* rgba, int width, int height, bool bottom_up);

}  // namespace crowdlab::stimuli
