#pragma once
// The renderer's mesh source for one character: its own skinned surface when it carries one
// (CharacterAnimation::mesh, e.g. the MPFB2 body; skinned_body_mesh.hpp), otherwise the procedural
// mannequin built around its capsules (mannequin_mesh.hpp). Both give a MannequinMesh, so everything
// downstream (upload, GPU skinning, shadows, overlap mode) is shared.
// Levels of detail (build_character_lods): a procedural mannequin is polygonised on coarser grids (the
// grid spacing is the level's error); a skinned surface is simplified by meshoptimizer
// (simplify_character_mesh.hpp). Shadow casters (options.inset_m > 0) of a skinned surface are the coarse
// capsule mannequin, whose capsules were fitted to the surface (a tenth of the triangles; shadows are soft).
#include <cstdint>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/mannequin_mesh.hpp"
#include "stimuli/simplify_character_mesh.hpp"

namespace crowdlab::stimuli {

MannequinMesh build_character_mesh(const CharacterAnimation& character, const MannequinOptions& options);

/// The cache key of build_character_mesh(character, options).
std::uint64_t character_mesh_key(const CharacterAnimation& character, const MannequinOptions& options);

/// Every level of detail of the character's visible mesh, finest first, with each level's geometric error:
/// the mannequin on grids of options.voxel_m, 2.6, 3.5 and 5 cm (error = grid spacing), or the skinned
/// surface and its meshoptimizer simplifications.
std::vector<CharacterLod> build_character_lods(const CharacterAnimation& character,
                                               const MannequinOptions& options);

/// The cache key of build_character_lods(character, options).
std::uint64_t character_lod_set_key(const CharacterAnimation& character, const MannequinOptions& options);

}  // namespace crowdlab::stimuli
