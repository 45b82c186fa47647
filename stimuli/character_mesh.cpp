#include "stimuli/character_mesh.hpp"

#include "stimuli/skinned_body_mesh.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "framework/core/seed.hpp"

namespace crowdlab::stimuli {

namespace {
// Coarser mannequin grids after options.voxel_m (about 12k, 7k, 4k and 2k triangles per body at 2, 2.6,
// 3.5 and 5 cm); the grid spacing bounds the polygonisation's deviation from the implicit surface.
constexpr std::array<double, 3> kMannequinLodVoxelM = {0.026, 0.035, 0.05};

/// An inset mesh (inset > 0: a shadow caster kept inside the visible skin) is always the capsule mannequin;
/// otherwise a character with a skinned surface is drawn with that surface.
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

std::vector<CharacterLod> build_character_lods(const CharacterAnimation& character,
                                               const MannequinOptions& options) {
  if (use_surface(character, options)) return simplify_character_mesh(skinned_body_mesh(*character.mesh));
  std::vector<CharacterLod> levels;
  levels.push_back({build_mannequin_mesh(character.shape, options), options.voxel_m});
  for (const double voxel_m : kMannequinLodVoxelM) {
    MannequinOptions coarse = options;
    coarse.voxel_m = std::max(options.voxel_m, voxel_m);
    levels.push_back({build_mannequin_mesh(character.shape, coarse), coarse.voxel_m});
  }
  return levels;
}

std::uint64_t character_lod_set_key(const CharacterAnimation& character, const MannequinOptions& options) {
  return stable_hash("lods:" + std::to_string(character_mesh_key(character, options)));
}

}  // namespace crowdlab::stimuli
