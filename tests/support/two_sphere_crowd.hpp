#pragma once
// Test crowd for the rendered-surface inside test (issue 27): two procedural bodies standing in the rest
// pose, each carrying a closed UV sphere of radius r skinned wholly to its pelvis and centred on it, as
// its rendered mesh. Their capsules (T-pose arm span about the stature, 1.75 m) do not meet when the
// pelvises are more than about 1.8 m apart; the spheres overlap when they are less than 2 r apart. A
// vertex of one sphere lies inside the other exactly when its distance to the other's centre is below r
// (up to the polygon's sagitta, r (1 - cos(pi / 48)), about 3 mm at r = 1.2 m), and the inside test counts
// it when it is at most kMaxBodyDepth_m (0.2 m) deep (metrics/mesh_overlap.hpp).
#include <cmath>
#include <memory>
#include <numbers>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab::test {

/// A closed UV sphere (24 rings, 48 segments, poles shared) around `centre`, skinned to the pelvis.
inline std::shared_ptr<SkinnedMesh> pelvis_sphere_mesh(const Vec3& centre, double radius) {
  constexpr int kRings = 24, kSegments = 48;
  auto m = std::make_shared<SkinnedMesh>();
  auto& v = m->rest_vertices_m;
  v.push_back(centre + Vec3(0, radius, 0));
  for (int i = 1; i < kRings; ++i) {
    const double th = std::numbers::pi * i / kRings;
    for (int j = 0; j < kSegments; ++j) {
      const double ph = 2.0 * std::numbers::pi * j / kSegments;
      v.push_back(centre +
                  radius * Vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)));
    }
  }
  v.push_back(centre - Vec3(0, radius, 0));
  const int south = static_cast<int>(v.size()) - 1;
  auto at = [](int ring, int seg) { return 1 + (ring - 1) * kSegments + (seg % kSegments); };
  for (int j = 0; j < kSegments; ++j) {  // counter-clockwise seen from outside
    m->triangles.emplace_back(0, at(1, j + 1), at(1, j));
    for (int i = 1; i + 1 < kRings; ++i) {
      m->triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j));
      m->triangles.emplace_back(at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
    }
    m->triangles.emplace_back(south, at(kRings - 1, j), at(kRings - 1, j + 1));
  }
  m->rest_normals = vertex_normals(m->rest_vertices_m, m->triangles);
  m->joints.assign(v.size(), {0, 0, 0, 0});
  m->weights.assign(v.size(), {1.0, 0.0, 0.0, 0.0});
  m->region.assign(v.size(), 0);
  return m;
}

/// Two such characters, pelvises `apart_m` apart along x, `frames` frames standing still.
inline CrowdAnimation two_sphere_crowd(double apart_m, double radius, int frames = 2) {
  CrowdAnimation crowd;
  crowd.meta.fps = 30;
  const BodyShape shape = make_procedural_body({});
  const Vec3 pelvis(0, shape.pelvis_height_m(), 0);
  auto mesh = pelvis_sphere_mesh(pelvis, radius);
  const BoneTransforms rest = forward_kinematics(shape, Pose::rest(shape));  // the skeleton it is bound to
  for (int j = 0; j < kJointCount; ++j)
    mesh->rest_joints_m[static_cast<size_t>(j)] = rest[static_cast<size_t>(j)].translation;
  for (int k = 0; k < 2; ++k) {
    CharacterAnimation c;
    c.name = "sphere" + std::to_string(k);
    c.shape = shape;
    c.mesh = mesh;
    Pose p = Pose::rest(shape);
    p.root_position_m = pelvis + Vec3(k * apart_m, 0, 0);
    c.frames.assign(static_cast<size_t>(frames), p);
    crowd.characters.push_back(std::move(c));
  }
  return crowd;
}

}  // namespace crowdlab::test
