#pragma once
// Renderer: the OpenGL scene renderer for crowd stimuli. It owns the headless EGL context (reused
// across clips), the GPU mesh cache (one mannequin mesh per distinct body shape) and the frame
// buffers. One Renderer per thread; all calls must come from the thread that created it.
//
// Per frame (draw(): prepare_frame, then one function per pass):
//   1. CPU (prepare_frame, stimuli/frame_plan.hpp, no OpenGL): forward kinematics -> skin matrices
//      (bone_world(frame) * bone_world(rest)^-1) for every character, uploaded to one SSBO; in overlap mode
//      also every character's candidate capsules of OTHER characters (those whose bounding boxes meet its
//      own), so each fragment tests only a few.
//   2. Shadow pass: characters and environment into a depth map from the key light (orthographic,
//      fitted to the crowd's clip-wide bounds).
//   3. Colour pass into a 4x multisampled FBO (colour + overlap mask + depth): characters (near to far,
//      back faces culled; the mannequin surface is closed), in overlap mode the parts of rendered meshes
//      that lie inside another character's (shaders.cpp), environment, ground. Environment boxes
//      that stand between the camera and any character's chest are cut away (not drawn, no shadow),
//      so corridor walls do not hide the crowd from side and tracking views.
//   4. Resolve (blit) to single-sample buffers; pixels are then read back, optionally through a pair
//      of pixel-buffer objects so that the read of frame f overlaps the rendering of frame f + 1 on GPUs.
//      At one sample per pixel the clean image is anti-aliased on the CPU after the read (fxaa_rgba.hpp).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/camera.hpp"
#include "stimuli/mannequin_mesh.hpp"
#include "stimuli/palette.hpp"

namespace crowdlab::stimuli {

struct GltfCharacter;
class GlProgram;

struct SceneOptions {
  bool overlap = false;  ///< paint red what lies inside other characters (rendered meshes; capsules without)
  Rgb background = {0.847f, 0.867f, 0.890f};  ///< sRGB clear colour (#d8dde3)
  double fog_density = 0.0;                   ///< EXP2 fog density (1/m); 0 = off
  int msaa_samples = 1;  ///< 1: the fast path (cached ground); 4: the quality reference (docs/stimuli.md)
  int shadow_map_size = 2048;
  Rgb ground = {0.64f, 0.62f, 0.58f};       ///< sRGB base colour of the ground
  Rgb environment = {0.78f, 0.76f, 0.72f};  ///< sRGB colour of boxes and meshes
  double lod_pixels = 6.0;  ///< screen-space error bound of the level of detail (pixels; see renderer.cpp)
  bool characters =
      true;  ///< false: the scene without its characters (the fixed per-frame cost, for benchmarks)
  bool time_passes = false;  ///< finish each pass before the next to time it (benchmarks; slower)
  /// The clean image (docs/stimuli.md): FXAA on the single-sample path, soft shadow edges (four bilinear
  /// shadow taps) and contact darkening under every character. false: the raw draw (benchmarks compare).
  bool clean_image = true;
};

/// Wall time of each stage of the last draw(), milliseconds. The GPU passes (shadow, colour, resolve) are
/// only separated when SceneOptions::time_passes is set: otherwise the rasteriser works on them later, in
/// whichever call waits for the pixels, and they read 0 here.
struct PassTimes {
  double prepare_ms = 0.0;  ///< CPU: forward kinematics, skin matrices, overlap candidates, LOD choice
  double shadow_ms = 0.0;   ///< shadow-map pass
  double colour_ms = 0.0;   ///< colour pass (characters, environment, ground)
  double resolve_ms = 0.0;  ///< MSAA resolve
};

/// Parses "#rrggbb" (or "rrggbb"); throws InputError otherwise.
Rgb parse_hex_colour(const std::string& text, const std::string& context);

class Renderer {
 public:
  explicit Renderer(MannequinOptions mesh_options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// GL_RENDERER / GL_VERSION of the context.
  const std::string& device() const;

  /// (Re)allocates the frame buffers for width x height pixels (> 0) and `samples` MSAA samples.
  void set_size(int width, int height, int samples = 4, int shadow_map_size = 2048);

  /// Characters from files (stimuli/gltf_character.hpp): character i of later crowds is drawn with
  /// the skinned glTF character files[i % files.size()], fitted to its body; empty = the mannequin.
  /// Files are read once per renderer (InputError naming the file and element on bad input).
  void set_character_files(const std::vector<std::string>& files);

  /// Prepares a crowd: builds (in parallel, cached across crowds) and uploads the mannequin meshes of
  /// all body shapes, the environment geometry and the clip-wide bounds used by the shadow map.
  /// Validates the crowd (InputError on bad input). The crowd must outlive later draw() calls.
  void load_crowd(const CrowdAnimation& crowd);

  /// Renders frame `frame` of the loaded crowd from `camera` into the resolved buffers.
  void draw(int frame, const Camera& camera, const SceneOptions& options);
  /// The stage times of the last draw().
  const PassTimes& pass_times() const { return pass_times_; }

  /// Reads the finished frame as width*height RGBA, bottom row first (synchronous; the clean image's
  /// anti-aliasing applied).
  void read_rgba(std::vector<std::uint8_t>& rgba);
  /// Asynchronous read: starts copying the resolved colour buffer into PBO `slot` (0 or 1)...
  void begin_read_rgba(int slot);
  /// ...and waits for PBO `slot`'s pixels and copies them out (width*height RGBA, bottom row first).
  /// Returns true when the frame is a clean image still to be anti-aliased: the caller then applies
  /// fxaa_rgba() (stimuli/fxaa_rgba.hpp), on any thread, so that it can run beside the next draw.
  [[nodiscard]] bool finish_read_rgba(int slot, std::vector<std::uint8_t>& rgba);

  /// Fraction of the image's pixels whose visible surface lies inside another character (overlap
  /// mode; the resolved mask >= 0.5, i.e. at least half the MSAA samples), of the last draw().
  double overlap_fraction();

  /// The crowd of the last load_crowd() (nullptr before).
  const CrowdAnimation* loaded_crowd() const { return crowd_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int requested_samples() const { return requested_samples_; }  ///< as passed to set_size()
  int shadow_map_size() const { return shadow_map_size_; }
  /// Number of distinct meshes in the cache and triangles drawn per character pass in the last draw.
  std::size_t cached_meshes() const;
  std::size_t triangles_per_frame() const { return triangles_; }

 private:
  struct Gl;
  // The passes of draw(), in order, over the FramePlan that prepare_frame() filled (stimuli/frame_plan.hpp).
  void upload_frame(Gl& g);
  void set_frame_uniforms(Gl& g, const Camera& camera, const SceneOptions& options);
  void shadow_pass(Gl& g, const SceneOptions& options);
  void colour_pass(Gl& g, const Camera& camera, const SceneOptions& options);
  void draw_characters(Gl& g, const SceneOptions& options);
  void draw_inside_surfaces(Gl& g);
  void resolve_pass(Gl& g, const SceneOptions& options);
  void draw_contacts(Gl& g, const SceneOptions& options);
  static GlProgram& character_program(Gl& g, const SceneOptions& options);
  /// Visible boxes (with the set dressing and colours when `environment`, the environment's colour, is
  /// given; the environment's own boxes only for the shadow pass, environment == nullptr), then meshes.
  void draw_environment(Gl& g, unsigned program, int model_location, int colour_location,
                        int emission_location, const Rgb* environment);
  void draw_ground(Gl& g, const Rgb& colour);
  void begin_shadow_pass(Gl& g);
  bool uses_ground_cache(const SceneOptions& options) const;
  std::uint64_t ground_cache_key(const Camera& camera, const SceneOptions& options) const;
  void draw_ground_cache(const SceneOptions& options);
  void copy_ground_cache();
  void draw_ground_shadows(const Rgb& ground, const Vec3& key_dir);
  std::unique_ptr<Gl> gl_;
  MannequinOptions mesh_options_;
  const CrowdAnimation* crowd_ = nullptr;
  int width_ = 0, height_ = 0, requested_samples_ = 0, shadow_map_size_ = 0;
  std::size_t triangles_ = 0;
  bool overlap_drawn_ = false;
  PassTimes pass_times_;
  std::uint64_t crowd_generation_ = 0;  ///< counts load_crowd() calls (invalidates the ground cache)
  std::map<std::string, std::shared_ptr<const GltfCharacter>> file_cache_;
  std::vector<std::shared_ptr<const GltfCharacter>> file_characters_;
};

}  // namespace crowdlab::stimuli
