#pragma once
// A character's own skinned surface (CharacterAnimation::mesh, e.g. the shaped MPFB2 body) as a
// renderer mesh: the same vertex layout and skinning path as the procedural mannequin
// (mannequin_mesh.hpp), so the GPU skinning, shadows and overlap mode work unchanged.
//
// Normals: the mesh's smooth (area-weighted) rest normals. Weights: quantised to 8 bits, the largest
// absorbing the rounding so that they sum to 255.
// Clothing regions (SkinRegion), by the vertex's rest (T-pose) position relative to the rest joints and
// its dominant joint, so that garment edges are straight cuts across limbs rather than the jagged
// borders of skinning-weight regions:
//   arm (dominant joint on the shoulder..hand chain): shirt up to 45 % of the upper arm (every palette
//     has at least short sleeves), sleeve to the wrist (shirt colour for long-sleeved palettes, skin
//     otherwise), skin beyond (hands);
//   head and neck (above the head joint, or inside a crew neckline: 7.5 cm either side of the neck
//     joint, from 1.5 cm below it, dipping toward the front): hair on the crown, back and upper sides
//     of the head (MakeHuman's base mesh is bald), skin elsewhere;
//   trunk and legs: shirt above the waist (a horizontal cut halfway between the pelvis and spine1
//     joints, about the iliac crest), trousers below;
//   legs: trousers down to 6 cm above the knee joint (shorts or skirt length for short-legged palettes),
//     lower leg (trouser colour or skin) to 3.5 cm above the ankle joint, shoes below.
// Regions are assigned per triangle (at its centroid), and vertices on a border are duplicated, one
// copy per region, so garment edges follow mesh edges (no zig-zag from flat per-vertex regions).
// A dressed body (SkinnedMesh::surface) takes its regions from its labels, except the lips: their label
// marks a set of vertices whose border, drawn along mesh edges, was a sawtooth around the mouth (issue 28,
// session 11's close-ups). They are skin with a lip weight per vertex (lip_weights), which the shader
// thresholds at 0.5 after interpolation: an outline through the triangles, smoothed like the label set.
// The proportions are everyday-clothing conventions chosen by eye on rendered frames (no published
// standard applies).
#include <cstdint>
#include <vector>

#include "framework/core/skinned_mesh.hpp"
#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

/// Converts `mesh` (vertices on region borders duplicated, see above); `inset_m` > 0 moves every vertex
/// inward along its normal (shadow casters, as MannequinOptions::inset_m). Throws InputError when the mesh is
/// invalid.
MannequinMesh skinned_body_mesh(const SkinnedMesh& mesh, double inset_m = 0.0);

/// Passes of neighbour averaging that turn the lips label into a weight (lip_weights).
inline constexpr int kLipSmoothingPasses = 3;

/// Per vertex of `mesh`, its lip weight in [0, 1]: 1 on the vertices labelled lips, 0 on the others, then
/// kLipSmoothingPasses passes that replace each skin or lips vertex's weight by the mean of its own and
/// its skin neighbours' mean (a diffusion of the label over the skin's edges; garments, eyes and hair do
/// not take part). Its 0.5 level set is the label set's outline with the vertex-sized steps smoothed out.
/// Empty when the mesh has no labels.
std::vector<double> lip_weights(const SkinnedMesh& mesh);

/// A stable 64-bit key of the mesh's geometry and skinning and of `inset_m`, for mesh caches.
std::uint64_t skinned_body_mesh_key(const SkinnedMesh& mesh, double inset_m = 0.0);

/// The clothing region of rest-pose point `p` whose dominant joint is `joint` (see the header).
SkinRegion body_mesh_region(const Vec3& p, int joint, const std::array<Vec3, kJointCount>& rest_joints,
                            double head_top_y);

}  // namespace crowdlab::stimuli
