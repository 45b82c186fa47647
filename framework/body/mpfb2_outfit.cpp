#include "framework/body/mpfb2_outfit.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {
namespace {

constexpr double kWaistDm = 1.0;           // base-mesh height dividing tops from bottoms (see header)
constexpr double kIrisCos = 0.9135454576;  // cos(24 degrees)

const MhcloProxy* pick(const std::vector<std::shared_ptr<const MhcloProxy>>& list, Rng& rng) {
  if (list.empty()) return nullptr;
  return list[static_cast<size_t>(uniform_index(rng, list.size()))].get();
}

/// Connected pieces of a face list over `count` vertices: a piece index per vertex.
std::vector<int> pieces(const std::vector<std::vector<int>>& faces, size_t count) {
  std::vector<int> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a) {
    while (parent[static_cast<size_t>(a)] != a)
      a = parent[static_cast<size_t>(a)] = parent[static_cast<size_t>(parent[static_cast<size_t>(a)])];
    return a;
  };
  for (const auto& f : faces)
    for (size_t k = 1; k < f.size(); ++k) parent[static_cast<size_t>(find(f[k]))] = find(f[0]);
  std::vector<int> out(count);
  for (size_t v = 0; v < count; ++v) out[v] = find(static_cast<int>(v));
  return out;
}

/// Appends one fitted asset (or a base-mesh group: refs to single vertices) with per-vertex labels.
void append(OutfitGeometry& g, const std::vector<Vec3>& verts_dm,
            const std::vector<std::array<double, kJointCount>>& weights,
            const std::vector<std::uint8_t>& surface, const std::vector<std::vector<int>>& faces) {
  const auto first = static_cast<int>(g.vertices_dm.size());
  g.vertices_dm.insert(g.vertices_dm.end(), verts_dm.begin(), verts_dm.end());
  g.joint_weights.insert(g.joint_weights.end(), weights.begin(), weights.end());
  g.surface.insert(g.surface.end(), surface.begin(), surface.end());
  for (const auto& f : faces)
    for (size_t k = 1; k + 1 < f.size(); ++k)
      g.triangles.emplace_back(first + f[0], first + f[k], first + f[k + 1]);
}

/// The asset's interpolated joint weights (see the header).
std::vector<std::array<double, kJointCount>> proxy_weights(
    const MhcloProxy& p, const std::vector<std::array<double, kJointCount>>& base_weights) {
  std::vector<std::array<double, kJointCount>> out(p.refs.size());
  for (size_t v = 0; v < p.refs.size(); ++v) {
    out[v].fill(0.0);
    for (size_t k = 0; k < 3; ++k) {
      const auto& w = base_weights[static_cast<size_t>(p.refs[v][k])];
      for (size_t j = 0; j < kJointCount; ++j)
        out[v][j] += p.ref_weights[v][static_cast<Eigen::Index>(k)] * w[j];
    }
    for (double& w : out[v]) w = std::max(w, 0.0);
  }
  return out;
}

void add_proxy(OutfitGeometry& g, const MhcloProxy& p, SurfaceKind kind, const std::vector<Vec3>& base_dm,
               const std::vector<std::array<double, kJointCount>>& base_weights, bool split_garment) {
  const std::vector<Vec3> verts = fit_mhclo_proxy(p, base_dm);
  std::vector<std::uint8_t> surface(verts.size(), static_cast<std::uint8_t>(kind));
  if (split_garment) {
    // Label each connected piece by its mean height in the reference (unshaped) fit: above the waist, top.
    const std::vector<int> piece = pieces(p.faces, verts.size());
    std::vector<double> sum(verts.size(), 0.0), count(verts.size(), 0.0);
    for (size_t v = 0; v < verts.size(); ++v) {
      sum[static_cast<size_t>(piece[v])] += verts[v].y();
      count[static_cast<size_t>(piece[v])] += 1.0;
    }
    for (size_t v = 0; v < verts.size(); ++v) {
      const auto c = static_cast<size_t>(piece[v]);
      surface[v] = static_cast<std::uint8_t>(sum[c] / count[c] > kWaistDm ? SurfaceKind::kUpperGarment
                                                                          : SurfaceKind::kLowerGarment);
    }
  }
  append(g, verts, proxy_weights(p, base_weights), surface, p.faces);
  g.hidden_base_vertices.insert(g.hidden_base_vertices.end(), p.deleted_base_vertices.begin(),
                                p.deleted_base_vertices.end());
}

/// One eyeball from the base mesh's group, its front cap labelled iris.
void add_eye(OutfitGeometry& g, const Mpfb2Model& model, const std::string& group,
             const std::vector<Vec3>& base_dm,
             const std::vector<std::array<double, kJointCount>>& base_weights) {
  const ObjMesh& base = model.base();
  const int gi = base.group_index(group);
  if (gi < 0) throw InputError(model.dir().string() + ": base mesh has no group '" + group + "'");
  const std::vector<int> ids = base.group_vertices(gi);
  std::vector<int> local(base.vertices.size(), -1);
  std::vector<Vec3> verts;
  std::vector<std::array<double, kJointCount>> weights;
  Vec3 centre = Vec3::Zero();
  for (int v : ids) {
    local[static_cast<size_t>(v)] = static_cast<int>(verts.size());
    verts.push_back(base_dm[static_cast<size_t>(v)]);
    weights.push_back(base_weights[static_cast<size_t>(v)]);
    centre += verts.back();
  }
  centre /= static_cast<double>(verts.size());
  std::vector<std::uint8_t> surface(verts.size());
  for (size_t v = 0; v < verts.size(); ++v) {
    const Vec3 d = (verts[v] - centre).normalized();
    surface[v] = static_cast<std::uint8_t>(d.z() > kIrisCos ? SurfaceKind::kIris : SurfaceKind::kEyeWhite);
  }
  std::vector<std::vector<int>> faces;
  for (size_t f = 0; f < base.faces.size(); ++f) {
    if (base.face_group[f] != gi) continue;
    std::vector<int> face;
    for (int v : base.faces[f]) face.push_back(local[static_cast<size_t>(v)]);
    faces.push_back(std::move(face));
  }
  append(g, verts, weights, surface, faces);
}

}  // namespace

std::shared_ptr<const Mpfb2Wardrobe> Mpfb2Wardrobe::load(const std::filesystem::path& dir,
                                                         int base_vertex_count) {
  const std::filesystem::path list = dir / "wardrobe.txt";
  std::ifstream in(list);
  if (!in) throw InputError(list.string() + ": cannot open the wardrobe list");
  auto w = std::make_shared<Mpfb2Wardrobe>();
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ss(line);
    std::string category, path;
    if (!(ss >> category) || category[0] == '#') continue;
    const auto fail = [&](const std::string& msg) {
      throw InputError(SourceLocation{list.string(), line_no, 0, ""}, msg);
    };
    if (!(ss >> path)) fail("'" + category + "' needs a .mhclo path");
    std::vector<std::shared_ptr<const MhcloProxy>>* target = category == "outfit_female" ? &w->outfit_female
                                                             : category == "outfit_male" ? &w->outfit_male
                                                             : category == "hair_female" ? &w->hair_female
                                                             : category == "hair_male"   ? &w->hair_male
                                                             : category == "shoes"       ? &w->shoes
                                                             : category == "eyebrows"    ? &w->eyebrows
                                                                                         : nullptr;
    if (!target) fail("unknown category '" + category + "'");
    target->push_back(std::make_shared<const MhcloProxy>(read_mhclo(dir / path, base_vertex_count)));
  }
  return w;
}

Mpfb2Outfit sample_mpfb2_outfit(const Mpfb2Wardrobe& wardrobe, Sex sex, std::uint64_t seed) {
  Rng rng(seed);
  const bool female = sex == Sex::kFemale;
  Mpfb2Outfit o;
  o.outfit = pick(female ? wardrobe.outfit_female : wardrobe.outfit_male, rng);
  o.hair = pick(female ? wardrobe.hair_female : wardrobe.hair_male, rng);
  o.shoes = pick(wardrobe.shoes, rng);
  o.eyebrows = pick(wardrobe.eyebrows, rng);
  return o;
}

OutfitGeometry outfit_geometry(const Mpfb2Model& model, const Mpfb2Outfit& outfit,
                               const std::vector<Vec3>& base_dm,
                               const std::vector<std::array<double, kJointCount>>& base_weights) {
  OutfitGeometry g;
  add_eye(g, model, "helper-l-eye", base_dm, base_weights);
  add_eye(g, model, "helper-r-eye", base_dm, base_weights);
  if (outfit.eyebrows) add_proxy(g, *outfit.eyebrows, SurfaceKind::kBrow, base_dm, base_weights, false);
  if (outfit.hair) add_proxy(g, *outfit.hair, SurfaceKind::kHair, base_dm, base_weights, false);
  if (outfit.outfit) add_proxy(g, *outfit.outfit, SurfaceKind::kUpperGarment, base_dm, base_weights, true);
  if (outfit.shoes) add_proxy(g, *outfit.shoes, SurfaceKind::kShoes, base_dm, base_weights, false);
  std::sort(g.hidden_base_vertices.begin(), g.hidden_base_vertices.end());
  g.hidden_base_vertices.erase(std::unique(g.hidden_base_vertices.begin(), g.hidden_base_vertices.end()),
                               g.hidden_base_vertices.end());
  return g;
}

}  // namespace crowdlab
