#include "stimuli/skinned_body_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "framework/core/seed.hpp"

namespace crowdlab::stimuli {
namespace {

bool on_arm(int j) {
  switch (j) {
    case kLeftShoulder:
    case kRightShoulder:
    case kLeftElbow:
    case kRightElbow:
    case kLeftWrist:
    case kRightWrist:
    case kLeftHand:
    case kRightHand:
      return true;
    default:
      return false;
  }
}

SkinRegion region_of_surface(std::uint8_t surface) {
  switch (static_cast<SurfaceKind>(surface)) {
    case SurfaceKind::kEyeWhite:
      return SkinRegion::kEyeWhite;
    case SurfaceKind::kIris:
      return SkinRegion::kIris;
    case SurfaceKind::kBrow:
      return SkinRegion::kBrow;
    case SurfaceKind::kHair:
      return SkinRegion::kHair;
    case SurfaceKind::kUpperGarment:
      return SkinRegion::kShirt;
    case SurfaceKind::kLowerGarment:
      return SkinRegion::kTrousers;
    case SurfaceKind::kShoes:
      return SkinRegion::kShoes;
    default:
      return SkinRegion::kSkin;
  }
}

/// A labelled triangle's region: the label two of its vertices share, else its first vertex's.
SkinRegion labelled_triangle_region(const SkinnedMesh& mesh, const Eigen::Vector3i& t) {
  const auto label = [&](int k) { return mesh.surface[static_cast<size_t>(t[k])]; };
  const std::uint8_t s = label(1) == label(2) ? label(1) : label(0);
  return region_of_surface(s);
}

bool skin_or_lips(std::uint8_t surface) {
  return surface == static_cast<std::uint8_t>(SurfaceKind::kSkin) ||
         surface == static_cast<std::uint8_t>(SurfaceKind::kLips);
}

}  // namespace

std::vector<double> lip_weights(const SkinnedMesh& mesh) {
  std::vector<double> weight(mesh.surface.size(), 0.0);
  for (size_t v = 0; v < mesh.surface.size(); ++v)
    weight[v] = mesh.surface[v] == static_cast<std::uint8_t>(SurfaceKind::kLips) ? 1.0 : 0.0;
  if (mesh.surface.empty()) return weight;
  // The skin's edges, each vertex's neighbours once (a mean over neighbours).
  std::vector<std::vector<std::uint32_t>> neighbours(weight.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    if (!skin_or_lips(mesh.surface[static_cast<size_t>(t[0])]) ||
        !skin_or_lips(mesh.surface[static_cast<size_t>(t[1])]) ||
        !skin_or_lips(mesh.surface[static_cast<size_t>(t[2])]))
      continue;
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<size_t>(t[k]), b = static_cast<size_t>(t[(k + 1) % 3]);
      neighbours[a].push_back(static_cast<std::uint32_t>(b));
      neighbours[b].push_back(static_cast<std::uint32_t>(a));
    }
  }
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  for (int pass = 0; pass < kLipSmoothingPasses; ++pass) {
    std::vector<double> next = weight;
    for (size_t v = 0; v < weight.size(); ++v) {
      if (neighbours[v].empty()) continue;
      double sum = 0.0;
      for (const std::uint32_t u : neighbours[v]) sum += weight[u];
      next[v] = 0.5 * weight[v] + 0.5 * sum / static_cast<double>(neighbours[v].size());
    }
    weight = std::move(next);
  }
  return weight;
}

SkinRegion body_mesh_region(const Vec3& p, int joint, const std::array<Vec3, kJointCount>& rest_joints,
                            double head_top_y) {
  const auto J = [&](int j) -> const Vec3& { return rest_joints[static_cast<size_t>(j)]; };
  const bool left = p.x() > 0.0;
  if (on_arm(joint)) {
    const double x = std::abs(p.x());
    const double shoulder = std::abs(J(left ? kLeftShoulder : kRightShoulder).x());
    const double elbow = std::abs(J(left ? kLeftElbow : kRightElbow).x());
    const double wrist = std::abs(J(left ? kLeftWrist : kRightWrist).x());
    if (x < shoulder + 0.45 * (elbow - shoulder)) return SkinRegion::kShirt;
    if (x < wrist - 0.01) return SkinRegion::kSleeve;
    return SkinRegion::kSkin;
  }
  // Head and neck: above the head joint, or inside the neckline (a 7.5 cm half-width around the neck
  // joint from 1.5 cm below it, dipping 0.3 m per m toward the front: a crew neck).
  const Vec3& neck = J(kNeck);
  const bool in_neckline =
      std::abs(p.x() - neck.x()) < 0.075 && p.y() > neck.y() - 0.015 - 0.3 * std::max(p.z() - neck.z(), 0.0);
  if (p.y() > J(kHead).y() || in_neckline) {
    const Vec3 local = p - J(kHead);
    const double h = std::max(head_top_y - J(kHead).y(), 1e-3);  // skull base to crown
    // Hairline: rises toward the forehead (0.55 h at the crown's centre line, + 0.8 m per m forward),
    // down to the nape at the back, above the ears at the sides.
    const bool crown = local.y() > 0.55 * h + 0.8 * std::max(local.z(), 0.0);
    const bool back = local.z() < -0.02 && local.y() > 0.12 * h;
    const bool sides = std::abs(local.x()) > 0.055 && local.y() > 0.5 * h && local.z() < 0.02;
    return crown || back || sides ? SkinRegion::kHair : SkinRegion::kSkin;
  }
  // Waist: a horizontal cut for trunk and legs alike (the dominant joint does not matter here).
  const double waist = 0.5 * (J(kPelvis).y() + J(kSpine1).y());
  if (p.y() >= waist) return SkinRegion::kShirt;
  const double knee = J(left ? kLeftKnee : kRightKnee).y();
  const double ankle = J(left ? kLeftAnkle : kRightAnkle).y();
  if (p.y() < ankle + 0.035) return SkinRegion::kShoes;
  if (p.y() < knee + 0.06) return SkinRegion::kLowerLeg;
  return SkinRegion::kTrousers;
}

MannequinMesh skinned_body_mesh(const SkinnedMesh& mesh, double inset_m) {
  validate_skinned_mesh(mesh, "render");
  double top = -HUGE_VAL;
  for (const Vec3& v : mesh.rest_vertices_m) top = std::max(top, v.y());
  const std::vector<double> lips = lip_weights(mesh);
  // Per-vertex geometry and skinning.
  std::vector<MannequinVertex> base;
  base.reserve(mesh.rest_vertices_m.size());  // (reserve + push_back: GCC 12 warns on resize)
  for (size_t i = 0; i < mesh.rest_vertices_m.size(); ++i) {
    MannequinVertex mv{};
    const Vec3 n =
        mesh.rest_normals[i].norm() > 0.5 ? Vec3(mesh.rest_normals[i].normalized()) : Vec3::UnitY();
    const Vec3 p = mesh.rest_vertices_m[i] - inset_m * n;
    for (size_t a = 0; a < 3; ++a) {
      mv.position[a] = static_cast<float>(p[static_cast<Eigen::Index>(a)]);
      mv.normal[a] = static_cast<float>(n[static_cast<Eigen::Index>(a)]);
    }
    // Influences in descending weight; 8-bit weights, the largest absorbing the rounding.
    std::array<size_t, 4> order = {0, 1, 2, 3};
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return mesh.weights[i][a] > mesh.weights[i][b]; });
    int assigned = 0;
    for (size_t k = 0; k < 4; ++k) {
      const size_t s = order[k];
      mv.bones[k] = static_cast<std::uint8_t>(mesh.joints[i][s]);
      const int w = k > 0 ? static_cast<int>(std::lround(255.0 * mesh.weights[i][s])) : 0;
      mv.weights[k] = static_cast<std::uint8_t>(w);
      assigned += w;
    }
    mv.weights[0] = static_cast<std::uint8_t>(255 - assigned);
    if (!lips.empty())
      mv.lips = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(lips[i], 0.0, 1.0)));
    base.push_back(mv);
  }
  // Regions per triangle (at its centroid, by the dominant joint of its first vertex), so a garment
  // edge follows mesh edges instead of zig-zagging with the shader's flat (provoking-vertex) region;
  // vertices on an edge between two regions are duplicated, one copy per region.
  constexpr size_t kRegions = static_cast<size_t>(SkinRegion::kCount);
  std::vector<std::array<std::int32_t, kRegions>> copy(base.size());
  for (auto& c : copy) c.fill(-1);
  MannequinMesh out;
  out.two_sided = !mesh.surface.empty();  // a dressed body: hair, brows and garments are open sheets
  out.vertices.reserve(base.size() + base.size() / 8);
  out.indices.reserve(3 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Vec3 centroid =
        (mesh.rest_vertices_m[static_cast<size_t>(t[0])] + mesh.rest_vertices_m[static_cast<size_t>(t[1])] +
         mesh.rest_vertices_m[static_cast<size_t>(t[2])]) /
        3.0;
    const auto region = static_cast<size_t>(
        mesh.surface.empty()
            ? body_mesh_region(centroid, base[static_cast<size_t>(t[0])].bones[0], mesh.rest_joints_m, top)
            : labelled_triangle_region(mesh, t));
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<size_t>(t[k]);
      if (copy[v][region] < 0) {
        copy[v][region] = static_cast<std::int32_t>(out.vertices.size());
        MannequinVertex mv = base[v];
        mv.region = static_cast<std::uint8_t>(region);
        out.vertices.push_back(mv);
      }
      out.indices.push_back(static_cast<std::uint32_t>(copy[v][region]));
    }
  }
  return out;
}

std::uint64_t skinned_body_mesh_key(const SkinnedMesh& mesh, double inset_m) {
  std::vector<double> data;
  data.reserve(3 * mesh.rest_vertices_m.size() + 8 * mesh.weights.size() + 3 * mesh.triangles.size() + 2);
  for (const Vec3& v : mesh.rest_vertices_m) data.insert(data.end(), {v.x(), v.y(), v.z()});
  for (size_t i = 0; i < mesh.weights.size(); ++i)
    for (size_t k = 0; k < 4; ++k) data.insert(data.end(), {mesh.weights[i][k], double(mesh.joints[i][k])});
  for (const Eigen::Vector3i& t : mesh.triangles)
    data.insert(data.end(), {double(t[0]), double(t[1]), double(t[2])});
  for (const std::uint8_t label : mesh.surface) data.push_back(double(label));  // none on a bare body
  data.insert(data.end(), {inset_m, -1.0});  // -1: never equal to a mannequin key's data layout
  return stable_hash_words(data);
}

}  // namespace crowdlab::stimuli
