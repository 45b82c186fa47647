#pragma once
// Levels of detail of a dense skinned character mesh (e.g. the 26.8k-triangle MPFB2 body), made with
// meshoptimizer's edge-collapse simplifier (Debian libmeshoptimizer-dev; Kapoulkine, "meshoptimizer",
// meshopt_simplify: quadric error metrics after Garland & Heckbert, SIGGRAPH 1997).
//
// Each level keeps a subset of the full mesh's vertices, so skinning weights, regions and normals stay
// exactly those of the full mesh (no attribute interpolation). Border edges are locked
// (meshopt_SimplifyLockBorder): the clothing regions of skinned_body_mesh() duplicate the vertices on
// garment edges, which makes every garment edge a topological border; locking them keeps the two sides
// of each edge together, so simplified meshes never tear at a sleeve or waist line.
// The unused vertices are then dropped and the rest reordered for the post-transform cache
// (meshopt_optimizeVertexCache, meshopt_optimizeVertexFetch), which a CPU rasteriser's vertex stage likes
// as much as a GPU's.
#include <vector>

#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

struct CharacterLod {
  MannequinMesh mesh;
  double error_m = 0.0;  ///< meshoptimizer's geometric deviation from the full mesh (metres)
};

/// Levels of `full`, finest first: level 0 is `full` itself (error 0); level k targets
/// full-triangle-count / ratio^k triangles, for k = 1..levels-1. A level that the simplifier cannot make
/// smaller than the previous one (locked borders) ends the list early. Deterministic.
std::vector<CharacterLod> simplify_character_mesh(const MannequinMesh& full, int levels = 5,
                                                  double ratio = 2.5);

}  // namespace crowdlab::stimuli
