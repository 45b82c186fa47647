#pragma once
// The procedural "mannequin" skin of one body shape: a smooth implicit surface around the capsules,
// polygonised once in the bind (rest) pose and bound to the skeleton with linear-blend-skinning weights.
//
// Surface: d(p) = min_j smin_k( s_j(p), s_parent(j)(p) ), s_j the signed distance to capsule j,
//   smin_k(a, b) = min(a, b) - h^2 k / 4, h = max(k - |a - b|, 0) / k   (polynomial smooth minimum,
//   Quilez, "Smooth minimum", iquilezles.org, 2013). Blending only along parent-child joints keeps
//   limbs that merely touch in the rest pose (the thighs, arm and torso) separate, so no webbing
//   stretches between them when they move apart. The trunk (pelvis, spine1-3, collars, neck) uses a
//   wider blend (10 cm, 5 cm) so its stacked horizontal capsules read as one torso, not ribs.
// Polygonisation: naive surface nets (Gibson 1998, "Constrained elastic surface nets"): one vertex per
//   grid cell that the surface crosses, at the mean of its edge crossings; one quad per crossed edge.
// Normals: the normalised central-difference gradient of d (smooth shading).
// Skinning: each vertex takes up to 4 bones among the bone nearest to it and that bone's parent and
//   children; weight w_j ~ exp(-(s_j - s_min) / sigma), sigma = 1.5 cm (a falloff that spans the
//   smooth-blend width), normalised to sum 1.
// Regions (for clothing palettes): skin, hair, shirt, sleeve, trousers, leg (shorts), shoes, by bone
//   and, on the head, by the position in the head's frame (hair on the crown and the back).
#include <array>
#include <cstdint>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "stimuli/mannequin_field.hpp"

namespace crowdlab::stimuli {

enum class SkinRegion : std::uint8_t {
  kSkin = 0,
  kHair,
  kShirt,
  kSleeve,
  kTrousers,
  kLowerLeg,
  kShoes,
  kEyeWhite,  ///< the regions below come from a dressed mesh's surface labels (SkinnedMesh::surface)
  kIris,
  kLips,
  kBrow,
  kCount
};
/// Size of the renderer's per-character colour table (>= kCount).
inline constexpr int kPaletteSlots = 12;

struct MannequinVertex {
  std::array<float, 3> position;        ///< bind pose, character frame (metres), rest pose standing at origin
  std::array<float, 3> normal;          ///< unit
  std::array<std::uint8_t, 4> bones;    ///< joint indices
  std::array<std::uint8_t, 4> weights;  ///< weights * 255, summing to 255
  std::uint8_t region;                  ///< SkinRegion
  std::array<std::uint8_t, 4> colour{};  ///< sRGB vertex colour (mesh files); alpha 255 replaces the
                                         ///< palette's region colour, alpha 0 (the mannequin) keeps it
  /// Lip weight * 255 of a skin vertex (dressed bodies, skinned_body_mesh.hpp): the shader paints the lip
  /// colour where the weight, interpolated across a triangle, passes 0.5, so the lips' outline is a
  /// smooth curve through the triangles instead of a sawtooth along their edges.
  std::uint8_t lips = 0;
};

struct MannequinMesh {
  std::vector<MannequinVertex> vertices;
  std::vector<std::uint32_t> indices;  ///< triangles, counter-clockwise seen from outside
  /// Open sheets (hair, eyebrows, garments) are seen from both sides: drawn without back-face culling.
  bool two_sided = false;
};

struct MannequinOptions {
  double voxel_m = 0.02;  ///< grid spacing of the polygonisation (metres): ~12k triangles per body
  double blend_m = 0.03;  ///< smooth-min width k at joints (metres)
  double inset_m = 0.0;   ///< polygonise the level set d = -inset_m (shrinks the body; for shadow casters)
};

/// Builds the mesh of `shape` in its rest pose (Pose::rest: pelvis at joint_offsets_m[0], facing +Z).
/// Deterministic: the same shape and options give the same mesh bit for bit, with either sampling of the
/// field (mannequin_field.hpp: kEveryPoint is the definition, kept as the reference kNarrowBand is tested
/// against).
MannequinMesh build_mannequin_mesh(const BodyShape& shape, const MannequinOptions& options = {},
                                   FieldSampling sampling = FieldSampling::kNarrowBand);

/// A stable 64-bit key of a shape's geometry (offsets, capsules) and the options, for mesh caches.
std::uint64_t mannequin_cache_key(const BodyShape& shape, const MannequinOptions& options = {});

}  // namespace crowdlab::stimuli
