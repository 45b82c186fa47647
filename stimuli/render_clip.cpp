#include "stimuli/render_clip.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/media/png_image.hpp"
#include "stimuli/elapsed_ms.hpp"
#include "stimuli/fxaa_rgba.hpp"
#include "stimuli/video_encoder.hpp"

namespace crowdlab::stimuli {
namespace {

using Clock = std::chrono::steady_clock;
/// Writes an 8-bit `image` (grey, BGR or BGRA) as a PNG (write_png_file: a full disk names the file and
/// the OS's reason, issue 21).
void write_png(const std::string& path, const cv::Mat& image) {
  if (image.depth() != CV_8U) throw RuntimeError(path + ": only 8-bit images are written as PNG");
  write_png_file(path, image.data, image.cols, image.rows, image.channels(), image.step);
}

cv::Mat bottom_up_rgba_to_bgr(const std::vector<std::uint8_t>& rgba, int width, int height) {
  const cv::Mat view(height, width, CV_8UC4, const_cast<std::uint8_t*>(rgba.data()));
  cv::Mat flipped, bgr;
  cv::flip(view, flipped, 0);
  cv::cvtColor(flipped, bgr, cv::COLOR_RGBA2BGR);
  return bgr;
}

/// A frame read back, on its way to the encoder thread.
struct QueuedFrame {
  int index = 0;
  bool needs_aa = false;  ///< the clean image's anti-aliasing is still to run (Renderer::finish_read_rgba)
  std::vector<std::uint8_t> rgba;
};

/// A bounded single-producer single-consumer queue of frames for the encoder thread.
struct FrameQueue {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<QueuedFrame> items;
  std::vector<std::vector<std::uint8_t>> free_buffers;
  bool done = false, failed = false;
  static constexpr size_t kCapacity = 2;
};

}  // namespace

void prepare_renderer(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options) {
  // Always (re)load: cheap with the mesh cache, and a crowd's address says nothing about its content.
  renderer.set_character_files(options.character_files);
  renderer.load_crowd(crowd);
  if (renderer.width() != options.width || renderer.height() != options.height ||
      renderer.requested_samples() != options.scene.msaa_samples ||
      renderer.shadow_map_size() != options.scene.shadow_map_size)
    renderer.set_size(options.width, options.height, options.scene.msaa_samples,
                      options.scene.shadow_map_size);
}

RenderResult render_clip(const CrowdAnimation& crowd, const RenderOptions& options, ViewpointId viewpoint,
                         const std::string& out_mp4) {
  validate_video_settings({options.width, options.height, crowd.meta.fps, options.crf, options.x264_preset});
  Renderer renderer;
  return render_clip(renderer, crowd, options, viewpoint, out_mp4);
}

RenderResult render_clip(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         ViewpointId viewpoint, const std::string& out_mp4) {
  const Viewpoint view(viewpoint, crowd, options.width, options.height, options.viewpoint_overrides);
  return render_clip(renderer, crowd, options, view, out_mp4);
}

RenderResult render_clip(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         const Viewpoint& view, const std::string& out_mp4) {
  const std::string& viewpoint = view.name();
  if (view.at(0).width != options.width || view.at(0).height != options.height)
    throw InputError("render: the viewpoint's image size differs from the render options'");
  const VideoSettings settings{options.width, options.height, crowd.meta.fps, options.crf,
                               options.x264_preset};
  validate_video_settings(settings);
  RenderResult result;
  result.width = options.width;
  result.height = options.height;
  result.fps = crowd.meta.fps;
  result.device = renderer.device();
  const auto setup_start = Clock::now();
  prepare_renderer(renderer, crowd, options);
  result.setup_s = ms_since(setup_start) / 1000.0;
  if (!options.frames_png_dir.empty()) std::filesystem::create_directories(options.frames_png_dir);
  const int n =
      options.max_frames >= 0 ? std::min(options.max_frames, crowd.frame_count()) : crowd.frame_count();
  if (n < 1) throw InputError("render: the crowd has no frames");

  const auto start = Clock::now();
  VideoEncoder encoder(out_mp4, settings);
  FrameQueue queue;
  std::exception_ptr worker_error;
  result.encode_ms.assign(static_cast<size_t>(n), 0.0);
  result.convert_ms.assign(static_cast<size_t>(n), 0.0);
  result.readback_ms.assign(static_cast<size_t>(n), 0.0);
  result.aa_ms.assign(static_cast<size_t>(n), 0.0);
  result.done_ms.assign(static_cast<size_t>(n), 0.0);
  std::thread worker([&] {
    try {
      for (;;) {
        QueuedFrame item;
        {
          std::unique_lock lock(queue.mutex);
          queue.changed.wait(lock, [&] { return !queue.items.empty() || queue.done; });
          if (queue.items.empty()) return;
          item = std::move(queue.items.front());
          queue.items.pop_front();
        }
        queue.changed.notify_all();
        const auto frame = static_cast<size_t>(item.index);
        if (item.needs_aa) {
          const auto aa_start = Clock::now();
          fxaa_rgba(item.rgba, options.width, options.height);
          result.aa_ms[frame] = ms_since(aa_start);
        }
        const EncodeTimes times = encoder.add_frame(item.rgba.data(), true);
        result.convert_ms[frame] = times.convert_ms;
        result.encode_ms[frame] = times.encode_ms;
        result.done_ms[frame] = ms_since(start);
        if (!options.frames_png_dir.empty()) {
          char name[32];
          std::snprintf(name, sizeof name, "frame_%05d.png", item.index);
          write_png((std::filesystem::path(options.frames_png_dir) / name).string(),
                    bottom_up_rgba_to_bgr(item.rgba, options.width, options.height));
        }
        std::lock_guard lock(queue.mutex);
        queue.free_buffers.push_back(std::move(item.rgba));
      }
    } catch (...) {
      worker_error = std::current_exception();
      std::lock_guard lock(queue.mutex);
      queue.failed = true;
      queue.items.clear();
      queue.changed.notify_all();
    }
  });
  auto push = [&](int frame, int slot) {
    std::vector<std::uint8_t> buffer;
    {
      std::unique_lock lock(queue.mutex);
      queue.changed.wait(lock, [&] { return queue.items.size() < FrameQueue::kCapacity || queue.failed; });
      if (queue.failed) return false;
      if (!queue.free_buffers.empty()) {
        buffer = std::move(queue.free_buffers.back());
        queue.free_buffers.pop_back();
      }
    }
    const auto read_start = Clock::now();
    const bool needs_aa = renderer.finish_read_rgba(slot, buffer);
    result.readback_ms[static_cast<size_t>(frame)] = ms_since(read_start);
    {
      std::lock_guard lock(queue.mutex);
      queue.items.push_back({frame, needs_aa, std::move(buffer)});
    }
    queue.changed.notify_all();
    return true;
  };

  bool ok = true;
  try {
    Progress progress("rendering " + viewpoint + " -> " + std::filesystem::path(out_mp4).filename().string(),
                      static_cast<size_t>(n));
    for (int f = 0; f < n && ok; ++f) {
      const auto t = Clock::now();
      renderer.draw(f, view.at(f), options.scene);
      result.passes.push_back(renderer.pass_times());
      if (options.scene.overlap) result.red_fraction.push_back(renderer.overlap_fraction());
      renderer.begin_read_rgba(f % 2);
      if (f > 0) ok = push(f - 1, (f - 1) % 2);
      result.render_ms.push_back(ms_since(t));
      progress.advance();
    }
    if (ok) ok = push(n - 1, (n - 1) % 2);
  } catch (...) {
    {
      std::lock_guard lock(queue.mutex);
      queue.done = true;
    }
    queue.changed.notify_all();
    worker.join();
    throw;
  }
  {
    std::lock_guard lock(queue.mutex);
    queue.done = true;
  }
  queue.changed.notify_all();
  worker.join();
  if (worker_error) std::rethrow_exception(worker_error);
  encoder.close();
  result.frames = encoder.frames_written();
  result.duration_s = result.frames / crowd.meta.fps;
  result.wall_s = ms_since(start) / 1000.0;
  spdlog::debug("rendered {} frames of {} in {:.2f} s ({})", result.frames, out_mp4, result.wall_s,
                result.device);
  return result;
}

BgrImage render_frame(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                      const Camera& camera, int frame, double* red_fraction) {
  prepare_renderer(renderer, crowd, options);
  renderer.draw(frame, camera, options.scene);
  if (red_fraction) *red_fraction = renderer.overlap_fraction();
  std::vector<std::uint8_t> rgba;
  renderer.read_rgba(rgba);
  const cv::Mat bgr = bottom_up_rgba_to_bgr(rgba, options.width, options.height);
  BgrImage image;
  image.width = options.width;
  image.height = options.height;
  image.bgr.assign(bgr.data, bgr.data + bgr.total() * bgr.elemSize());
  return image;
}

void write_contact_sheet(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         int frame, const std::string& out_png, const CrowdExtent* extent) {
  const int tile_w = options.width / 2, tile_h = options.height / 2;
  cv::Mat sheet(2 * tile_h, 2 * tile_w, CV_8UC3, cv::Scalar(0, 0, 0));
  const ViewpointId ids[4] = {ViewpointId::V1, ViewpointId::V2, ViewpointId::V3, ViewpointId::V4};
  for (int k = 0; k < 4; ++k) {
    const Viewpoint view =
        extent ? Viewpoint(ids[k], *extent, options.width, options.height, options.viewpoint_overrides)
               : Viewpoint(ids[k], crowd, options.width, options.height, options.viewpoint_overrides);
    BgrImage img = render_frame(renderer, crowd, options, view.at(frame), frame);
    const cv::Mat full(img.height, img.width, CV_8UC3, img.bgr.data());
    cv::Mat tile;
    cv::resize(full, tile, cv::Size(tile_w, tile_h), 0, 0, cv::INTER_AREA);
    const double scale = std::max(0.5, tile_h / 360.0);
    cv::putText(tile, view.name(), cv::Point(static_cast<int>(12 * scale), static_cast<int>(30 * scale)),
                cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(20, 20, 20),
                std::max(1, static_cast<int>(2 * scale)), cv::LINE_AA);
    tile.copyTo(sheet(cv::Rect((k % 2) * tile_w, (k / 2) * tile_h, tile_w, tile_h)));
  }
  write_png(out_png, sheet);
}

}  // namespace crowdlab::stimuli
