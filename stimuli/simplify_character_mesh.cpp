#include "stimuli/simplify_character_mesh.hpp"

#include <meshoptimizer.h>

#include <cmath>
#include <cstddef>

namespace crowdlab::stimuli {
namespace {

/// Keeps only the vertices `indices` use, in first-use order after a vertex-cache reordering.
MannequinMesh compact(const std::vector<MannequinVertex>& vertices, std::vector<std::uint32_t> indices) {
  meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), vertices.size());
  MannequinMesh out;
  out.vertices.resize(vertices.size());
  const size_t used = meshopt_optimizeVertexFetch(out.vertices.data(), indices.data(), indices.size(),
                                                  vertices.data(), vertices.size(), sizeof(MannequinVertex));
  out.vertices.resize(used);
  out.indices = std::move(indices);
  return out;
}

}  // namespace

std::vector<CharacterLod> simplify_character_mesh(const MannequinMesh& full, int levels, double ratio) {
  std::vector<CharacterLod> out;
  out.push_back({full, 0.0});
  if (full.indices.empty() || full.vertices.empty()) return out;
  const float* positions = full.vertices.front().position.data();
  const size_t stride = sizeof(MannequinVertex);
  // meshopt reports errors relative to the mesh's extent; this scale converts them to metres.
  const double scale_m = meshopt_simplifyScale(positions, full.vertices.size(), stride);
  size_t previous = full.indices.size();
  for (int level = 1; level < levels; ++level) {
    const size_t target = 3 * static_cast<size_t>(std::floor(static_cast<double>(full.indices.size() / 3) /
                                                             std::pow(ratio, level)));
    std::vector<std::uint32_t> indices(full.indices.size());
    float error = 0.0f;
    // target_error 1 (the whole extent): the triangle budget, not the error, decides where to stop.
    const size_t count =
        meshopt_simplify(indices.data(), full.indices.data(), full.indices.size(), positions,
                         full.vertices.size(), stride, target, 1.0f, meshopt_SimplifyLockBorder, &error);
    if (count == 0 || count >= previous) break;
    indices.resize(count);
    previous = count;
    out.push_back({compact(full.vertices, std::move(indices)), static_cast<double>(error) * scale_m});
    out.back().mesh.two_sided = full.two_sided;
  }
  return out;
}

}  // namespace crowdlab::stimuli
