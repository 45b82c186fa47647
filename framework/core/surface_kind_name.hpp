#pragma once
// Names of the surface kinds of a skinned mesh (core/skinned_mesh.hpp), as the metrics JSON writes them.
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

/// "skin", "lips", "eye_white", "iris", "brow", "hair", "upper_garment", "lower_garment", "shoes".
const char* surface_kind_name(SurfaceKind kind);

}  // namespace crowdlab
