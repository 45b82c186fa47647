#pragma once
// prepare_frame: the CPU half of drawing one frame, a pure function of the crowd, the camera and the
// options (no OpenGL), so that it can be tested alone; Renderer::draw uploads its result and runs the
// shadow, colour and resolve passes from it (stimuli/renderer.cpp).
//
//   Inputs:  crowd, frame index, camera, SceneOptions (overlap, lod_pixels), and the renderer's per-crowd
//            FrameScene: each character's inverse rest transforms and level-of-detail set, the
//            environment boxes, the clip-wide bounds and the image height in pixels.
//   Output:  FramePlan (below): skin matrices, overlap candidates, lights, cut-away boxes, the level of
//            detail and the near-to-far order of the characters.
//
// Lighting: three-point lighting relative to the camera's horizontal viewing direction (key 35° right
// and 50° up, fill 60° left and 20° up, rim from behind 35° up), the key light's shadow map an orthographic
// view fitted to the clip-wide bounds (the same for every frame and both methods of a condition).
// Cut-away: an environment box that any segment from the eye to a character's chest (root + 0.35 m)
// passes through is not drawn (the near wall of a corridor seen from the side).
// Overlap mode on rendered surfaces: a character with a mesh is not tested against capsules; every vertex
// of the level drawn is skinned here (the GPU's linear blend with the same 8-bit weights) and flagged when
// it lies inside another character's posed full mesh (metrics/surfaces_inside.hpp, at most
// kMaxBodyDepth_m deep, as the mesh-level overlap counts). The renderer paints the flagged surface.
// Level of detail: the coarsest level whose geometric error spans at most lod_pixels pixels at the
// character's root distance (stimuli/level_of_detail.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/math_types.hpp"
#include "framework/core/pose.hpp"
#include "stimuli/camera.hpp"
#include "stimuli/level_of_detail.hpp"
#include "stimuli/renderer.hpp"

namespace crowdlab::stimuli {

/// Per crowd: what prepare_frame reads besides the frame's poses (filled by Renderer::load_crowd).
struct FrameScene {
  std::vector<std::array<Mat4, kJointCount>> inverse_rest;  ///< per character, bone_world(rest)^-1
  std::vector<const std::vector<LodLevel>*> lod_sets;       ///< per character, finest first
  std::vector<Box> boxes;                                   ///< environment boxes
  Vec3 bounds_lo = Vec3::Zero(), bounds_hi = Vec3::Zero();  ///< clip-wide bounds (shadow map fit)
  int height_px = 1;                                        ///< image height (LOD pixel size)
};

/// The lights of a frame: unit directions towards each light, and the key light's view-projection.
struct FrameLights {
  Vec3 key_dir = Vec3::UnitY(), fill_dir = Vec3::UnitY(), rim_dir = Vec3::UnitY();
  Mat4 light_view_proj = Mat4::Identity();
};

struct FramePlan {
  /// Per character and joint, bone_world(frame) * bone_world(rest)^-1 as 16 column-major floats.
  std::vector<float> skin_matrices;
  /// Overlap mode: capsules as 8 floats (a.xyz, radius, b.xyz, 0). Character i's own capsules start at
  /// own_offset[i]; its candidates (capsules of OTHER characters whose boxes meet its box) are the
  /// cap_count[i] capsules from cap_offset[i]. Empty otherwise, with zero offsets and counts.
  std::vector<float> capsules;
  std::vector<int> own_offset, cap_offset, cap_count;
  /// Overlap mode, characters that carry a rendered mesh (CharacterAnimation::mesh): per vertex of the
  /// level drawn, 1 when it lies inside another character's rendered surface (the mesh-level overlap's
  /// inside test, metrics/surfaces_inside.hpp), else 0. Character i's flags start at inside_offset[i]
  /// (-1: none; it keeps the capsule test, with no capsule candidates for the ones that have flags).
  std::vector<float> inside;
  std::vector<int> inside_offset;
  FrameLights lights;
  Mat4 view_proj = Mat4::Identity();
  std::vector<char> box_hidden;     ///< per environment box: 1 = cut away this frame
  std::vector<std::uint64_t> mesh;  ///< per character: the mesh-cache key of the level drawn
  std::vector<std::size_t> order;   ///< characters near to far from the eye (stable); empty without them
  std::vector<float> contacts;      ///< per drawn character: root x, z, 0, 0 (contact darkening)
};

/// Fills `plan` (its buffers are reused across frames). Throws InputError when `frame` is out of range.
void prepare_frame(const CrowdAnimation& crowd, int frame, const Camera& camera, const SceneOptions& options,
                   const FrameScene& scene, FramePlan& plan);

/// The inverse rest transforms of a body (FrameScene::inverse_rest).
std::array<Mat4, kJointCount> inverse_rest_transforms(const BodyShape& shape);

/// The lights of a camera over the clip-wide bounds [lo, hi] (see the header comment).
FrameLights frame_lights(const Camera& camera, const Vec3& lo, const Vec3& hi);

}  // namespace crowdlab::stimuli
