#pragma once
// The MPFB2 / MakeHuman asset folder (CC0), loaded once and shared read-only (immutable model):
//   3dobjs/base.obj                   base mesh, Y-up, decimetres; group `body` is the skin, the other
//                                     groups are helper geometry (joint cubes, eyelashes, tights...)
//   targets/macrodetails/**.target.gz per-vertex offsets "index dx dy dz" (decimetres), loaded lazily
//   targets/macrodetails/macro.json   the macro variables' parts (which targets each range blends)
//   rigs/standard/rig.mixamo.json     bones: parent, head/tail placement (MEAN of vertex indices, CUBE
//                                     = mean of a joint-cube group's vertices, or default_position in
//                                     Blender's Z-up metres)
//   rigs/standard/weights.mixamo.json skinning weights per bone: [[vertex index, weight], ...]
// Where: a `body_model: {type: mpfb2, path: ...}` spec entry, else $CROWDLAB_MPFB2, else the subset
// shipped in framework/body/assets/mpfb2 (core/mpfb2_asset_dir.hpp).
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "framework/body/obj_mesh.hpp"

namespace crowdlab {

/// How a rig joint is placed (rig.mixamo.json "strategy").
struct JointPlacement {
  enum class Strategy { kMean, kCube, kDefault };
  Strategy strategy = Strategy::kDefault;
  std::vector<int> vertices;  ///< base-mesh vertex indices (kMean) or the cube group's (kCube)
  Vec3 default_position_blender = Vec3::Zero();  ///< Blender Z-up metres
};

struct RigBone {
  std::string name;
  std::string parent;  ///< empty for the root
  JointPlacement head;
  JointPlacement tail;
};

/// One shape target: sparse offsets (decimetres) of base-mesh vertices.
struct ShapeTarget {
  std::vector<int> indices;
  std::vector<Vec3> offsets_dm;
};

/// One part of a macro variable's range (macro.json): between `lowest` and `highest` the variable
/// blends target `low` (weight 1 at the part's lower end) into `high` (weight 1 at its upper end).
struct MacroPart {
  double lowest = 0.0;
  double highest = 1.0;
  std::string low;
  std::string high;
};

class Mpfb2Model {
 public:
  /// Loads the base mesh, rig, weights and macro.json. Throws InputError naming the missing/bad file.
  static std::shared_ptr<const Mpfb2Model> load(const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }
  const ObjMesh& base() const { return base_; }
  const std::vector<int>& body_vertices() const { return body_vertices_; }  ///< sorted, into base()
  const std::vector<Eigen::Vector3i>& body_triangles() const { return body_triangles_; }  ///< base indices
  /// Per base-mesh vertex: the body vertex whose shape displacement it takes (itself for body vertices;
  /// the nearest body vertex of the unshaped mesh for helper geometry: tights, hair and skirt helpers,
  /// eyeballs). The shipped targets hold body vertices only, so helpers follow the skin they lie on.
  const std::vector<int>& shape_anchor() const { return shape_anchor_; }
  const std::map<std::string, RigBone>& bones() const { return bones_; }
  const std::map<std::string, std::vector<std::pair<int, double>>>& weights() const { return weights_; }
  const std::map<std::string, std::vector<MacroPart>>& macro_parts() const { return macro_parts_; }

  /// A target by its path relative to targets/macrodetails without ".target.gz" (e.g.
  /// "height/male-young-averagemuscle-averageweight-maxheight"), parsed on first use and cached
  /// (thread-safe). Throws InputError when the file is missing or malformed.
  const ShapeTarget& target(const std::string& name) const;

 private:
  std::filesystem::path dir_;
  ObjMesh base_;
  std::vector<int> body_vertices_;
  std::vector<Eigen::Vector3i> body_triangles_;
  std::vector<int> shape_anchor_;
  std::map<std::string, RigBone> bones_;
  std::map<std::string, std::vector<std::pair<int, double>>> weights_;
  std::map<std::string, std::vector<MacroPart>> macro_parts_;
  mutable std::mutex cache_mutex_;
  mutable std::map<std::string, std::unique_ptr<ShapeTarget>> cache_;
};

/// Bytes per vertex a target's decompressed text may hold (its lines are about 25 bytes).
inline constexpr int kMaxTargetLineBytes = 128;

/// Reads a gzipped target file ("index dx dy dz" per line; '#' comments). vertex_count bounds indices,
/// the number of entries (one per vertex at most) and the decompressed size (vertex_count x
/// kMaxTargetLineBytes + 1 MiB): past either the file is refused while inflating (InputError).
ShapeTarget read_target_gz(const std::filesystem::path& path, int vertex_count);

/// Blender Z-up (x, y, z) -> crowdlab / OBJ Y-up (x, z, -y); same units.
inline Vec3 blender_to_y_up(const Vec3& b) {
  return {b.x(), b.z(), -b.y()};
}

}  // namespace crowdlab
