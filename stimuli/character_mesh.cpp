#include "stimuli/character_mesh.hpp"

#include "stimuli/skinned_body_mesh.hpp"

namespace crowdlab::stimuli {

MannequinMesh build_character_mesh(const CharacterAnimation& character, const MannequinOptions& options) {
  return character.mesh ? skinned_body_mesh(*character.mesh, options.inset_m)
                        : build_mannequin_mesh(character.shape, options);
}

std::uint64_t character_mesh_key(const CharacterAnimation& character, const MannequinOptions& options) {
  return character.mesh ? skinned_body_mesh_key(*character.mesh, options.inset_m)
                        : mannequin_cache_key(character.shape, options);
}

}  // namespace crowdlab::stimuli
