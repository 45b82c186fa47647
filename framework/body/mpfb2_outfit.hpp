#pragma once
// What an MPFB2 body wears: eyes, eyebrows, hair, a two-piece outfit and shoes, as separate skinned
// sheets over the skin (MakeHuman's CC0 proxy assets, body/mhclo_proxy.hpp; the subset crowdlab ships is in
// framework/body/assets/makehuman, made by scripts/make_makehuman_subset.py).
//
// Wardrobe folder: `wardrobe.txt` lists one asset per line, "<category> <path to .mhclo>" ('#' comments);
// categories: outfit_female, outfit_male, hair_female, hair_male, shoes, eyebrows. An outfit is a top and a
// bottom: its OBJ's connected pieces are labelled upper or lower garment by whether their mean height lies
// above the base mesh's waist (y = 1 dm in MakeHuman's base-mesh frame, the top of the trousers' pieces).
//
// Fitting (per body): every asset vertex is placed on the shaped base mesh by its .mhclo line and skinned
// with the same weights, interpolated: w_j = sum_k w_k W_j(ref_k) over its three reference vertices (W the
// base mesh's per-vertex SMPL joint weights), clamped at 0, the 4 largest kept and renormalised.
// Eyes: the base mesh's own eyeball groups (helper-l-eye, helper-r-eye); a vertex is iris when its direction
// from the eyeball's centre lies within 24 degrees of straight ahead (+Z; a human iris spans about 12 mm
// of a 24 mm eyeball, i.e. a half-angle near 30 degrees, drawn a little smaller so the sclera reads).
// Base-mesh vertices an outfit or shoes cover (their delete_verts) are removed from the skin after the
// capsules are fitted, so the collision bodies stay the body's own; what they keep under the hems is tucked
// behind the garment (body/tuck_under_garments.hpp), so no skin pokes through a garment.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "framework/body/mhclo_proxy.hpp"
#include "framework/body/mpfb2_model.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

struct Mpfb2Wardrobe {
  std::vector<std::shared_ptr<const MhcloProxy>> outfit_female, outfit_male, hair_female, hair_male, shoes,
      eyebrows;
  /// Reads wardrobe.txt and every asset it lists (InputError naming the file and line).
  static std::shared_ptr<const Mpfb2Wardrobe> load(const std::filesystem::path& dir, int base_vertex_count);
};

/// One body's choice (nullptr: none of that kind). Eyes are always drawn.
struct Mpfb2Outfit {
  const MhcloProxy* outfit = nullptr;
  const MhcloProxy* hair = nullptr;
  const MhcloProxy* shoes = nullptr;
  const MhcloProxy* eyebrows = nullptr;
};

/// Draws an outfit, hair, shoes and eyebrows uniformly from the sex's lists, from its own stream `seed`.
Mpfb2Outfit sample_mpfb2_outfit(const Mpfb2Wardrobe& wardrobe, Sex sex, std::uint64_t seed);

/// The outfit's geometry before posing: vertices in decimetres (the base mesh's frame), per-vertex SMPL
/// joint weights (kJointCount each, unnormalised), surface labels, triangles (0-based into these
/// vertices) and the base-mesh vertices it hides.
struct OutfitGeometry {
  std::vector<Vec3> vertices_dm;
  std::vector<std::array<double, kJointCount>> joint_weights;
  std::vector<std::uint8_t> surface;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> hidden_base_vertices;  ///< sorted
};

/// The eyes and the outfit's assets fitted to `base_dm` (every base-mesh vertex, shaped; helpers
/// following their anchors, Mpfb2Model::shape_anchor), skinned from base_weights (per base vertex).
OutfitGeometry outfit_geometry(const Mpfb2Model& model, const Mpfb2Outfit& outfit,
                               const std::vector<Vec3>& base_dm,
                               const std::vector<std::array<double, kJointCount>>& base_weights);

}  // namespace crowdlab
