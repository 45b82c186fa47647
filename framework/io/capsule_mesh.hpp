#pragma once
// A low-poly triangle mesh of a capsule (cylinder + two hemispheres), for showing capsule bodies in
// glTF viewers and Blender.
#include <cstdint>
#include <vector>

#include "framework/core/capsule.hpp"

namespace crowdlab {

struct TriangleSoup {
  std::vector<Vec3> positions;         ///< metres, in the capsule's frame
  std::vector<Vec3> normals;           ///< unit outward normals, one per position
  std::vector<std::uint32_t> indices;  ///< 3 per triangle, counter-clockwise seen from outside
};

/// Appends a capsule tessellated with `segments` vertices around the axis (>= 3) and `rings` latitude
/// rings per hemisphere (>= 1): 2 + segments * (2 * rings) vertices (one equator ring fewer for a
/// sphere, a == b), no degenerate triangles. Every vertex lies exactly on the capsule surface.
void append_capsule_mesh(const Capsule& capsule, int segments, int rings, TriangleSoup& out);

}  // namespace crowdlab
