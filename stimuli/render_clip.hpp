#pragma once
// render_clip: one crowd animation -> one H.264/MP4 stimulus from one viewpoint.
//
// Rendering and encoding run as a two-stage pipeline: the calling thread renders frame f + 1 while a
// worker thread converts and encodes frame f (a bounded queue of two frames). Exactly
// crowd.frame_count() frames are written with pts 0..N-1, so an animation that loops (frame N would
// equal frame 0) gives a seamlessly looping clip.
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/viewpoint.hpp"

namespace crowdlab::stimuli {

struct RenderOptions {
  int width = 1920, height = 1080;  ///< even (yuv420p); InputError otherwise
  int crf = 18;
  std::string x264_preset = "veryfast";
  SceneOptions scene;  ///< overlap mode, background, fog, MSAA, shadow map size
  ViewpointOverrides viewpoint_overrides;
  std::vector<std::string> character_files;  ///< skinned glTF characters (Renderer::set_character_files)
  std::string frames_png_dir;                ///< when set, also writes DIR/frame_00000.png ...
  int max_frames = -1;                       ///< render only the first N frames (< 0: all)
};

struct RenderResult {
  int frames = 0;
  double duration_s = 0.0;  ///< frames / fps
  double fps = 0.0;
  int width = 0, height = 0;
  std::vector<double> red_fraction;  ///< overlap mode: fraction of red pixels per frame (else empty)
  std::vector<double> render_ms;     ///< per frame: CPU skinning + GL draw + resolve + readback
  std::vector<PassTimes> passes;     ///< per frame: the renderer's stages (renderer.hpp)
  std::vector<double> readback_ms;   ///< per frame: waiting for and copying the pixels (PBO)
  std::vector<double> aa_ms;         ///< per frame: the clean image's anti-aliasing (worker thread; 0 if off)
  std::vector<double> convert_ms;    ///< per frame: RGBA -> yuv420p (worker thread)
  std::vector<double> encode_ms;     ///< per frame: H.264 encode and mux (worker thread)
  std::vector<double> done_ms;       ///< per frame: time its encoding finished, from the clip's start
  double wall_s = 0.0;               ///< whole clip, excluding mesh building
  double setup_s = 0.0;              ///< mesh building and upload (load_crowd)
  std::string device;                ///< GL renderer / version
};

/// Loads `crowd` into `renderer` (meshes come from its cache) and sizes its frame buffers for `options`.
void prepare_renderer(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options);

/// Renders with a Renderer created for this call (an EGL context per call; prefer the overload
/// below for many clips).
RenderResult render_clip(const CrowdAnimation& crowd, const RenderOptions& options, ViewpointId viewpoint,
                         const std::string& out_mp4);
/// Renders with an existing Renderer (its context and mesh cache are reused across clips), framed
/// from the crowd's own motion (Viewpoint(viewpoint, crowd, ...)).
RenderResult render_clip(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         ViewpointId viewpoint, const std::string& out_mp4);
/// Renders from a given viewpoint, e.g. one framed from data several crowds share (crowd_extent.hpp);
/// its image size must be options.width x options.height.
RenderResult render_clip(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         const Viewpoint& view, const std::string& out_mp4);

/// Renders frame `frame` from each of V1..V4 and tiles them 2x2 (each tile width/2 x height/2, labelled)
/// into a PNG at `out_png` (OpenCV). Framed by `extent` when given, else by the crowd's own motion.
void write_contact_sheet(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                         int frame, const std::string& out_png, const CrowdExtent* extent = nullptr);

/// Renders one frame to an 8-bit BGR image, top row first (for tests and quick looks); sets
/// *red_fraction when non-null (overlap mode). Loads the crowd into the renderer on every call
/// (meshes come from the cache); for many frames of one crowd use Renderer directly.
struct BgrImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bgr;
};
BgrImage render_frame(Renderer& renderer, const CrowdAnimation& crowd, const RenderOptions& options,
                      const Camera& camera, int frame, double* red_fraction = nullptr);

}  // namespace crowdlab::stimuli
