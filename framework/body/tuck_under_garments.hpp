#pragma once
// Skin and inner garments tucked behind the garments that cover them, so nothing under a garment shows
// through it (issue 28: triangles of thigh skin through a pair of shorts, a trouser waistband through a
// shirt's hem, a shoe's collar through a trouser leg).
//
// MakeHuman's `.mhclo` delete_verts remove the skin well inside a garment (body/mpfb2_outfit.hpp), but keep
// a band of skin under every hem and wherever the asset's author kept it; there the garment lies only a few
// millimetres above the skin. The renderer's levels of detail (stimuli/simplify_character_mesh.hpp)
// deviate by 0.8-9.8 mm from the full mesh, so a simplified skin under a tight garment breaks through it
// in triangles, and a garment edge whose skin lies 1-2 mm below it looks ragged.
//
// Rule, on the rest mesh (metres): a vertex of an inner layer is covered when its closest point on an
// outer layer's triangles lies within kTuckReachM, not on that layer's rim (a hem: boundary_vertices of
// the layer's triangles, so skin beside a hem is never moved), and in front of or behind it rather than
// beside it (|d| >= half the distance, with d the offset along the vertex's outward normal). A covered
// vertex with d < margin moves inward along its normal until d = margin. Layers, inner to outer: the
// lower garment under the upper garment, the shoes under the lower garment (a trouser leg over a shoe's
// collar), then the skin (SurfaceKind::kSkin) under every garment and the
// shoes. The normals are the area-weighted vertex normals of the inner layer's own triangles (the skin's
// and the garments' triangles are counter-clockwise from outside, as MakeHuman writes them).
// Under a lower garment the skin goes deeper (kSkirtMarginM, found within kSkirtReachM): a skirt hangs
// around both legs, weighted from both, and a thigh that swings forward in a stride or a dance broke
// through the front of it in triangles even 1 cm behind it. Trousers delete the legs' skin
// (delete_verts), so this moves only the thighs under a skirt and the bands under the trouser hems.
// The capsules are fitted before this (body/mpfb2_body.cpp): the collision bodies stay the skin's own.
#include <vector>

#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

constexpr double kTuckReachM = 0.03;    ///< how far from a garment a vertex can be covered by it
constexpr double kSkirtReachM = 0.06;   ///< the same for skin under a lower garment (a skirt's thighs)
constexpr double kSkirtMarginM = 0.03;  ///< depth behind a lower garment: a leg swings inside a skirt
constexpr double kTuckMarginM = 0.010;  ///< depth behind a garment; above the LOD errors up to level 3
/// Depth behind a hem (issue 28, session 12): what lies straight under a garment's rim, where the rule
/// above stops (its closest point is on the rim), is pushed this far in. It lay 0-2 mm under necklines and
/// broke through them in posed frames where the body bends (notches in the close-ups); a full margin there
/// would open a visible gap under the hem, so this is shallower.
constexpr double kHemMarginM = 0.004;

/// Moves covered vertices of `mesh` (labelled: mesh.surface) behind their garments as above; returns how
/// many moved. Positions only: triangles, weights, labels and normals are kept (the caller recomputes
/// the normals once the mesh is final).
int tuck_under_garments(SkinnedMesh& mesh, double margin_m = kTuckMarginM);

/// Per vertex: its offset d (metres, along its outward normal, returned in `normal`) behind the layers
/// `outer` when it is a vertex of `inner`'s triangles that they cover (the rule above), NaN otherwise.
/// What tuck_under_garments moves by; exposed for tests and diagnostics. `under_hems_only`: the offsets
/// of the vertices under a rim instead (kHemMarginM), NaN elsewhere.
std::vector<double> cover_depths(const SkinnedMesh& mesh, SurfaceKind inner,
                                 const std::vector<SurfaceKind>& outer, std::vector<Vec3>& normal,
                                 double reach_m = kTuckReachM, bool under_hems_only = false);

}  // namespace crowdlab
