#pragma once
// The renderer's mesh source for one character: its own skinned surface when it carries one
// (CharacterAnimation::mesh, e.g. the MPFB2 body; skinned_body_mesh.hpp), otherwise the procedural
// mannequin built around its capsules (mannequin_mesh.hpp). Both give a MannequinMesh, so everything
// downstream (upload, GPU skinning, shadows, overlap mode) is shared.
// For a skinned surface the mannequin's voxel size does not apply (the mesh is what it is: one level of
// detail), except for shadow casters (options.inset_m > 0): those are the coarse capsule mannequin,
// whose capsules were fitted to the surface (a tenth of the triangles; shadows are soft).
#include <cstdint>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

MannequinMesh build_character_mesh(const CharacterAnimation& character, const MannequinOptions& options);

/// The cache key of build_character_mesh(character, options).
std::uint64_t character_mesh_key(const CharacterAnimation& character, const MannequinOptions& options);

}  // namespace crowdlab::stimuli
