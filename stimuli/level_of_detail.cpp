#include "stimuli/level_of_detail.hpp"

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {

const LodLevel& select_lod(const std::vector<LodLevel>& levels, double max_error_m) {
  if (levels.empty()) throw RuntimeError("select_lod: a mesh set has no levels");
  size_t chosen = 0;
  for (size_t l = 1; l < levels.size(); ++l)
    if (levels[l].error_m <= max_error_m) chosen = l;
  return levels[chosen];
}

}  // namespace crowdlab::stimuli
