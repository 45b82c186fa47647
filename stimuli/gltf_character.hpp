#pragma once
// Characters from files: a skinned glTF 2.0 character (.gltf / .glb; e.g. a Mixamo character exported
// or converted to glTF) rendered in place of the procedural mannequin and driven by crowdlab's 24-joint
// skeleton.
//
// Loading (load_gltf_character): the first node that has both a mesh and a skin. Every TRIANGLES
// primitive of its mesh contributes POSITION, NORMAL (area-weighted vertex normals when absent),
// JOINTS_0 (unsigned byte or short) and WEIGHTS_0 (float); the colour is COLOR_0 when present, else
// the material's baseColorFactor (textures are not read). The skin's joint names are mapped onto the
// SMPL joints with the animation layer's name maps (map_joint_names in framework/animation/retarget.hpp:
// Mixamo, CMU, Bandai-Namco or SMPL names; pelvis, hips, knees and ankles are required), and each skin
// joint is driven by its nearest mapped ancestor (Mixamo's fingers follow the SMPL wrist, etc.).
// The mesh is posed by its own skin in the file's rest node pose (joint matrices = node world transform
// times inverse bind matrix, glTF 2.0 §3.7.3), so armature rotations and scales (Z-up or centimetre
// rigs) are applied; that rest pose must be a T-pose or close to it (Mixamo's is).
// Errors (unreadable file, no skinned mesh, bad accessors, joint indices outside the skin, weights that
// do not sum to a positive value, unmappable skeletons) throw InputError naming the file and the glTF
// element ("meshes[0].primitives[1].attributes.JOINTS_0", "skins[0].joints[3]").
//
// Fitting to a body (fit_gltf_character): the mesh is scaled uniformly to the body's height
// (BodyParams::height_m over the mesh's vertical extent) and re-bound to the body's rest (T-)pose by
// moving each mapped file joint onto the body's joint: bone j gets the rigid map
//   T_j(x) = p_j + R_j (s x - s P_j),
// p_j the body's rest joint position, P_j the file's bind joint position, s the scale, and R_j the
// smallest rotation taking the file's bone direction (towards the next mapped joint down the chain)
// onto the body's (the animation layer's rest-pose alignment, seed of retarget.hpp step 2); bones
// without a mapped child keep their parent's R. Vertices are blended with their own skin weights
// (linear blend skinning), so limbs keep the file's shape while joints sit where the body's skeleton
// (and its retargeted motion) puts them. The result is an ordinary skinned mesh over the 24 SMPL
// joints (MannequinMesh with per-vertex colours), posed every frame by the renderer like a mannequin.
// The crowd's physics still uses the body's capsules; the file mesh is its look only.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

struct GltfCharacter {
  std::string source;                                ///< file, for messages and cache keys
  std::vector<Vec3> positions, normals;              ///< bind pose, the skin's mesh space (file units)
  std::vector<std::array<int, 4>> joints;            ///< skin joint indices per vertex
  std::vector<std::array<double, 4>> weights;        ///< per vertex, summing to 1
  std::vector<std::array<std::uint8_t, 4>> colours;  ///< sRGB (gamma 2 encoded), alpha 255
  std::vector<std::uint32_t> indices;                ///< triangles, counter-clockwise outside
  std::vector<std::string> joint_names;              ///< skin joints
  std::vector<int> joint_parent;                     ///< nearest ancestor among the skin joints, -1 at roots
  std::vector<Vec3> joint_bind_position;             ///< mesh space (from the inverse bind matrices)
  std::array<int, kJointCount> smpl_source{};        ///< skin joint mapped to each SMPL joint, -1 if none
  std::vector<int> smpl_of_joint;                    ///< SMPL joint driving each skin joint
};

/// Reads and validates a skinned character (see above). InputError names the file and the element.
GltfCharacter load_gltf_character(const std::filesystem::path& path);

/// The character re-bound to `shape`'s rest pose, as a skinned mesh over the SMPL joints whose
/// vertices carry the file's colours (alpha 255). Deterministic.
MannequinMesh fit_gltf_character(const GltfCharacter& character, const BodyShape& shape);

}  // namespace crowdlab::stimuli
