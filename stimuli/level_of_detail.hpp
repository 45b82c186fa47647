#pragma once
// Discrete level-of-detail selection by a screen-space error bound (Luebke et al., "Level of Detail for 3D
// Graphics", 2003, ch. 4): a character is drawn with the coarsest of its meshes whose geometric error
// spans at most SceneOptions::lod_pixels pixels at the character's distance.
//
// Why it matters here: llvmpipe shades every triangle in blocks of 4x4 pixels, so a dense body whose
// triangles cover 2-3 pixels each costs several times its pixel count, and the vertex stage runs on one
// thread. The error of a level is its mannequin grid spacing (procedural bodies) or meshoptimizer's
// deviation from the full mesh (skinned surfaces, simplify_character_mesh.hpp).
#include <cstdint>
#include <memory>
#include <vector>

#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

struct LodLevel {
  std::uint64_t key = 0;  ///< the renderer's mesh-cache key
  double error_m = 0.0;   ///< geometric error of this level (metres)
  int index_count = 0;    ///< 3 x triangles
  /// The level's vertices as uploaded (bind pose, bones, weights), kept on the CPU for characters that
  /// carry a rendered mesh: overlap mode tests each drawn vertex against the other characters' surfaces
  /// (frame_plan.hpp). Null otherwise.
  std::shared_ptr<const std::vector<MannequinVertex>> vertices;
};

/// The coarsest level of `levels` (finest first, errors increasing) whose error is at most
/// `max_error_m`; the finest level when none is. `levels` must not be empty.
const LodLevel& select_lod(const std::vector<LodLevel>& levels, double max_error_m);

}  // namespace crowdlab::stimuli
