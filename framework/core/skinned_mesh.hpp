#pragma once
// A skinned body surface (e.g. the shaped MPFB2 mesh): rest-pose geometry in the character frame
// (metres, Y-up, facing +Z, feet on y = 0, pelvis above the origin: the frame of Pose::rest()), up to
// 4 SMPL joints per vertex with weights, and a region label per vertex. A CharacterAnimation may carry
// one (CharacterAnimation::mesh); renderers then draw it instead of a surface built from the capsules,
// and crowd files store it as the character's glTF skin mesh (docs/crowd-files.md).
//
// Linear blend skinning (seed 000 Eq. 1, W(...)): with bone transforms B_j from forward_kinematics()
// and rest joint positions p_j (rest bone frames are translations only, see body_shape.hpp),
//   v' = sum_k w_k (R_jk (v - p_jk) + t_jk)
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

/// What a vertex's surface is (SkinnedMesh::surface), so a renderer can shade skin, eyes, hair and each
/// garment apart; fitted garments and hair are separate sheets laid over the skin (body/mpfb2_outfit.hpp).
enum class SurfaceKind : std::uint8_t {
  kSkin = 0,
  kLips,
  kEyeWhite,
  kIris,
  kBrow,
  kHair,
  kUpperGarment,
  kLowerGarment,
  kShoes,
  kCount
};

struct SkinnedMesh {
  std::vector<Vec3> rest_vertices_m;           ///< (V)
  std::vector<Vec3> rest_normals;              ///< (V) unit, area-weighted vertex normals
  std::vector<Eigen::Vector3i> triangles;      ///< (T) counter-clockwise from outside
  std::vector<std::array<int, 4>> joints;      ///< (V) SMPL joint indices (unused slots: 0 with weight 0)
  std::vector<std::array<double, 4>> weights;  ///< (V) sum to 1, descending
  std::vector<int> region;                     ///< (V) the dominant SMPL joint (body-part label)
  /// (V) SurfaceKind per vertex, or empty: a bare body whose renderer assigns clothing by position.
  std::vector<std::uint8_t> surface;
  std::array<Vec3, kJointCount> rest_joints_m{};  ///< rest joint positions, same frame
};

/// Checks sizes, finite positions/weights, joint indices in [0, 24), weights >= 0 summing to 1 (within
/// 1e-4) and triangle indices in range. Throws InputError "<context>: body mesh: <problem>".
/// (validate_crowd() also checks that rest_joints_m matches the character's skeleton.)
void validate_skinned_mesh(const SkinnedMesh& mesh, const std::string& context);

/// Posed vertex positions (world, metres) for bone transforms from forward_kinematics().
std::vector<Vec3> skin_vertices(const SkinnedMesh& mesh, const BoneTransforms& bones);

/// Area-weighted vertex normals of a triangle mesh (unit; zero where a vertex has no area).
std::vector<Vec3> vertex_normals(const std::vector<Vec3>& vertices,
                                 const std::vector<Eigen::Vector3i>& triangles);

/// Enclosed volume by the divergence theorem (m^3 for metres); exact for a closed, consistently
/// oriented mesh, an estimate where the mesh has holes.
double mesh_volume(const std::vector<Vec3>& vertices, const std::vector<Eigen::Vector3i>& triangles);

}  // namespace crowdlab
