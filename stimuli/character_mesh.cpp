#include "stimuli/character_mesh.hpp"

#include "stimuli/skinned_body_mesh.hpp"

namespace crowdlab::stimuli {

namespace {
/// Shadow casters (inset > 0) of a skinned surface are the coarse capsule mannequin: its capsules were
/// fitted to that surface, shadows are soft and seen from afar, and it has a tenth of the triangles.
bool use_surface(const CharacterAnimation& character, const MannequinOptions& options) {
  return character.mesh && options.inset_m <= 0.0;
}
}  // namespace

MannequinMesh build_character_mesh(const CharacterAnimation& character, const MannequinOptions& options) {
  return use_surface(character, options) ? skinned_body_mesh(*character.mesh)
                                         : build_mannequin_mesh(character.shape, options);
}

std::uint64_t character_mesh_key(const CharacterAnimation& character, const MannequinOptions& options) {
  return use_surface(character, options) ? skinned_body_mesh_key(*character.mesh)
                                         : mannequin_cache_key(character.shape, options);
}

}  // namespace crowdlab::stimuli
