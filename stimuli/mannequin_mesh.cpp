#include "stimuli/mannequin_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "framework/core/capsule_box.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"
#include "stimuli/mannequin_field.hpp"

namespace crowdlab::stimuli {
namespace {

constexpr double kSkinSigmaM = 0.015;  // skinning-weight falloff (see header)

SkinRegion region_of(int bone, const Vec3& p_rest, const BodyShape& shape, const BoneTransforms& rest) {
  const double H = shape.params.height_m;
  switch (bone) {
    case kHead: {
      const Vec3 local = p_rest - rest[kHead].translation;  // bone frames are aligned in the rest pose
      const bool crown = local.y() > 0.066 * H;
      const bool back = local.z() < -0.005 * H && local.y() > 0.02 * H;
      const bool sides = std::abs(local.x()) > 0.035 * H && local.y() > 0.05 * H;
      return (crown || back || sides) ? SkinRegion::kHair : SkinRegion::kSkin;
    }
    case kNeck:
    case kLeftWrist:
    case kRightWrist:
    case kLeftHand:
    case kRightHand:
      return SkinRegion::kSkin;
    case kSpine1:
    case kSpine2:
    case kSpine3:
    case kLeftCollar:
    case kRightCollar:
    case kLeftShoulder:
    case kRightShoulder:
      return SkinRegion::kShirt;
    case kLeftElbow:
    case kRightElbow:
      return SkinRegion::kSleeve;
    case kPelvis:
    case kLeftHip:
    case kRightHip:
      return SkinRegion::kTrousers;
    case kLeftKnee:
    case kRightKnee:
      return SkinRegion::kLowerLeg;
    default:
      return SkinRegion::kShoes;  // ankles, feet
  }
}

/// Up to four skinning influences of a vertex among the nearest bone and its skeletal neighbours.
void skin_weights(const std::array<double, kJointCount>& s, MannequinVertex& v) {
  const int nearest = static_cast<int>(std::min_element(s.begin(), s.end()) - s.begin());
  std::array<std::pair<double, int>, kJointCount> cand;
  int n = 0;
  for (int j = 0; j < kJointCount; ++j) {
    const bool neighbour = j == nearest || j == kJointParent[static_cast<size_t>(nearest)] ||
                           kJointParent[static_cast<size_t>(j)] == nearest;
    if (neighbour)
      cand[static_cast<size_t>(n++)] = {
          std::exp(-(s[static_cast<size_t>(j)] - s[static_cast<size_t>(nearest)]) / kSkinSigmaM), j};
  }
  std::sort(cand.begin(), cand.begin() + n, [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  const int m = std::min(n, 4);
  double total = 0.0;
  for (int i = 0; i < m; ++i) total += cand[static_cast<size_t>(i)].first;
  int assigned = 0;
  for (int i = 0; i < 4; ++i) {
    const bool used = i < m;
    v.bones[static_cast<size_t>(i)] =
        static_cast<std::uint8_t>(used ? cand[static_cast<size_t>(i)].second : nearest);
    const int w =
        used && i > 0 ? static_cast<int>(std::lround(255.0 * cand[static_cast<size_t>(i)].first / total)) : 0;
    v.weights[static_cast<size_t>(i)] = static_cast<std::uint8_t>(w);
    assigned += w;
  }
  v.weights[0] = static_cast<std::uint8_t>(255 - assigned);  // the largest weight absorbs rounding
}

}  // namespace

std::uint64_t mannequin_cache_key(const BodyShape& shape, const MannequinOptions& options) {
  std::vector<double> data;
  for (const Vec3& o : shape.joint_offsets_m) data.insert(data.end(), {o.x(), o.y(), o.z()});
  for (const Capsule& c : shape.capsules)
    data.insert(data.end(), {c.a.x(), c.a.y(), c.a.z(), c.b.x(), c.b.y(), c.b.z(), c.radius_m});
  data.insert(data.end(), {options.voxel_m, options.blend_m, options.inset_m, shape.params.height_m});
  return stable_hash_words(data);
}

MannequinMesh build_mannequin_mesh(const BodyShape& shape, const MannequinOptions& options,
                                   FieldSampling sampling) {
  if (!(options.voxel_m > 0.002) || !(options.blend_m > 0.0))
    throw InputError("mannequin mesh: voxel_m must be > 2 mm and blend_m > 0");
  validate_body_shape(shape, "mannequin mesh");
  const Pose rest = Pose::rest(shape);
  const BoneTransforms bones = forward_kinematics(shape, rest);
  const WorldCapsules caps = world_capsules(shape, bones);
  const MannequinField field(caps, options.blend_m);

  // Grid over the capsules' bounding box plus a margin of two cells.
  const Aabb body = capsules_box(caps);
  const double h = options.voxel_m;
  FieldGrid grid;
  grid.spacing_m = h;
  grid.lo = body.lo - Vec3::Constant(2 * h);
  const Vec3 hi = body.hi + Vec3::Constant(2 * h);
  grid.nx = static_cast<int>(std::ceil((hi.x() - grid.lo.x()) / h)) + 1;
  grid.ny = static_cast<int>(std::ceil((hi.y() - grid.lo.y()) / h)) + 1;
  grid.nz = static_cast<int>(std::ceil((hi.z() - grid.lo.z()) / h)) + 1;
  const int nx = grid.nx, ny = grid.ny, nz = grid.nz;
  auto point = [&](int i, int j, int k) { return grid.point(i, j, k); };
  auto idx = [&](int i, int j, int k) { return grid.index(i, j, k); };
  const std::vector<float> value = sample_field(field, grid, options.inset_m, sampling);

  // One vertex per crossed cell.
  MannequinMesh mesh;
  std::vector<std::int32_t> cell_vertex(value.size(), -1);
  static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  static constexpr int kEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                       {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::array<double, kJointCount> s;
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        float v[8];
        int inside = 0;
        for (int c = 0; c < 8; ++c) {
          v[c] = value[idx(i + kCorner[c][0], j + kCorner[c][1], k + kCorner[c][2])];
          inside += v[c] < 0.0f;
        }
        if (inside == 0 || inside == 8) continue;
        Vec3 sum = Vec3::Zero();
        int crossings = 0;
        for (const auto& e : kEdge) {
          const float a = v[e[0]], b = v[e[1]];
          if ((a < 0.0f) == (b < 0.0f)) continue;
          const double t = a / (a - b);
          const Vec3 pa = point(i + kCorner[e[0]][0], j + kCorner[e[0]][1], k + kCorner[e[0]][2]);
          const Vec3 pb = point(i + kCorner[e[1]][0], j + kCorner[e[1]][1], k + kCorner[e[1]][2]);
          sum += pa + t * (pb - pa);
          ++crossings;
        }
        const Vec3 p = sum / crossings;
        MannequinVertex mv{};
        field.distances(p, s);
        const Vec3 n = sampling == FieldSampling::kEveryPoint ? field.gradient(p, 0.5 * h)
                                                              : field.gradient(p, 0.5 * h, s);
        for (int a = 0; a < 3; ++a) {
          mv.position[static_cast<size_t>(a)] = static_cast<float>(p[a]);
          mv.normal[static_cast<size_t>(a)] = static_cast<float>(n[a]);
        }
        skin_weights(s, mv);
        mv.region = static_cast<std::uint8_t>(region_of(mv.bones[0], p, shape, bones));
        cell_vertex[idx(i, j, k)] = static_cast<std::int32_t>(mesh.vertices.size());
        mesh.vertices.push_back(mv);
      }

  // One quad per crossed grid edge, wound so that its normal points from inside to outside.
  auto emit = [&](size_t c0, size_t c1, size_t c2, size_t c3, bool start_inside) {
    const std::int32_t q[4] = {cell_vertex[c0], cell_vertex[c1], cell_vertex[c2], cell_vertex[c3]};
    if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[3] < 0) return;
    const auto u = [&](int n) { return static_cast<std::uint32_t>(q[n]); };
    if (start_inside)
      mesh.indices.insert(mesh.indices.end(), {u(0), u(1), u(2), u(0), u(2), u(3)});
    else
      mesh.indices.insert(mesh.indices.end(), {u(0), u(2), u(1), u(0), u(3), u(2)});
  };
  for (int k = 1; k + 1 < nz; ++k)
    for (int j = 1; j + 1 < ny; ++j)
      for (int i = 1; i + 1 < nx; ++i) {
        const bool in0 = value[idx(i, j, k)] < 0.0f;
        if (in0 != (value[idx(i + 1, j, k)] < 0.0f))  // x edge: cells around it in the (y, z) plane
          emit(idx(i, j - 1, k - 1), idx(i, j, k - 1), idx(i, j, k), idx(i, j - 1, k), in0);
        if (in0 != (value[idx(i, j + 1, k)] < 0.0f))  // y edge: (z, x) plane
          emit(idx(i - 1, j, k - 1), idx(i - 1, j, k), idx(i, j, k), idx(i, j, k - 1), in0);
        if (in0 != (value[idx(i, j, k + 1)] < 0.0f))  // z edge: (x, y) plane
          emit(idx(i - 1, j - 1, k), idx(i, j - 1, k), idx(i, j, k), idx(i - 1, j, k), in0);
      }
  if (mesh.indices.empty()) throw RuntimeError("mannequin mesh: the implicit surface produced no triangles");
  return mesh;
}

}  // namespace crowdlab::stimuli
