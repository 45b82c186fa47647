#pragma once
// A minimal Wavefront OBJ reader for the MPFB2 base mesh: vertex positions and polygon faces tagged
// with their `g` group. Texture/normal indices are ignored. Units are whatever the file uses (MPFB2:
// decimetres, Y-up).
#include <filesystem>
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

struct ObjMesh {
  std::vector<Vec3> vertices;           ///< all `v` lines, in file order (0-based indices)
  std::vector<std::string> groups;      ///< group names, in order of first appearance
  std::vector<std::vector<int>> faces;  ///< each face's 0-based vertex indices (3 or more)
  std::vector<int> face_group;          ///< group index of each face

  /// Index of a group by name, or -1.
  int group_index(const std::string& name) const;
  /// The distinct vertex indices used by the faces of a group, sorted.
  std::vector<int> group_vertices(int group) const;
};

/// Throws InputError "file:line: message" on malformed lines or out-of-range indices.
ObjMesh read_obj(const std::filesystem::path& path);

}  // namespace crowdlab
