#include "framework/core/surface_kind_name.hpp"

#include <iterator>

namespace crowdlab {

const char* surface_kind_name(SurfaceKind kind) {
  static constexpr const char* kNames[] = {"skin", "lips",          "eye_white",     "iris", "brow",
                                           "hair", "upper_garment", "lower_garment", "shoes"};
  static_assert(std::size(kNames) == static_cast<size_t>(SurfaceKind::kCount));
  const auto k = static_cast<size_t>(kind);
  return k < std::size(kNames) ? kNames[k] : "unknown";
}

}  // namespace crowdlab
