#include "stimuli/frame_plan.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "framework/core/capsule_box.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/mesh_overlap.hpp"
#include "framework/metrics/surfaces_inside.hpp"

namespace crowdlab::stimuli {
namespace {

Mat4 to_matrix(const RigidTransform& t) {
  Mat4 m = Mat4::Identity();
  m.block<3, 3>(0, 0) = t.rotation.toRotationMatrix();
  m.block<3, 1>(0, 3) = t.translation;
  return m;
}

/// True when the segment [p, q] passes through the oriented box (slab test in the box frame).
bool segment_hits_box(const Vec3& p, const Vec3& q, const Box& box) {
  const Quat r = box.rotation.normalized();
  const Vec3 a = r.conjugate() * (p - box.center_m), b = r.conjugate() * (q - box.center_m);
  const Vec3 d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double h = box.half_extents_m[k];
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(a[k]) > h) return false;
      continue;
    }
    double ta = (-h - a[k]) / d[k], tb = (h - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

Mat4 ortho(double half, double near_m, double far_m) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 1.0 / half;
  m(1, 1) = 1.0 / half;
  m(2, 2) = -2.0 / (far_m - near_m);
  m(2, 3) = -(far_m + near_m) / (far_m - near_m);
  return m;
}

/// A horizontal direction rotated by `deg` about +Y, raised by `elevation_deg`.
Vec3 light_direction(const Vec3& horizontal_dir, double deg, double elevation_deg) {
  const double a = deg * std::numbers::pi / 180.0, e = elevation_deg * std::numbers::pi / 180.0;
  const Vec3 h = Eigen::AngleAxisd(a, Vec3::UnitY()) * horizontal_dir;
  return (std::cos(e) * h + std::sin(e) * Vec3::UnitY()).normalized();
}

const Vec3& root_at(const CharacterAnimation& c, int frame) {
  return c.frames[static_cast<std::size_t>(frame)].root_position_m;
}

/// Skin matrices of every character and, in overlap mode, each character's world capsules and box.
void pose_characters(const CrowdAnimation& crowd, int frame, const FrameScene& scene, bool overlap,
                     FramePlan& plan, std::vector<WorldCapsules>& world, std::vector<Aabb>& boxes) {
  const auto& chars = crowd.characters;
  const std::size_t n = chars.size();
  plan.skin_matrices.resize(n * kJointCount * 16);
  world.assign(overlap ? n : 0, {});
  boxes.assign(overlap ? n : 0, {});
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    const BoneTransforms bones =
        forward_kinematics(chars[i].shape, chars[i].frames[static_cast<std::size_t>(frame)]);
    for (std::size_t j = 0; j < bones.size(); ++j) {
      const Eigen::Matrix4f skin = (to_matrix(bones[j]) * scene.inverse_rest[i][j]).cast<float>();
      std::memcpy(&plan.skin_matrices[(i * kJointCount + j) * 16], skin.data(), 16 * sizeof(float));
    }
    if (!overlap) return;
    world[i] = world_capsules(chars[i].shape, bones);
    boxes[i] = capsules_box(world[i]);
  });
}

/// Overlap mode: each character's own capsules, then the capsules of others whose boxes meet its box.
/// A box test per pair: the crowds of a stimulus hold at most a few hundred characters.
void gather_overlap_candidates(const std::vector<WorldCapsules>& world, const std::vector<Aabb>& boxes,
                               FramePlan& plan) {
  const std::size_t n = world.size();
  auto push_capsule = [&](const Capsule& c) {
    plan.capsules.insert(plan.capsules.end(), {static_cast<float>(c.a.x()), static_cast<float>(c.a.y()),
                                               static_cast<float>(c.a.z()), static_cast<float>(c.radius_m),
                                               static_cast<float>(c.b.x()), static_cast<float>(c.b.y()),
                                               static_cast<float>(c.b.z()), 0.0f});
  };
  for (std::size_t a = 0; a < n; ++a) {
    plan.own_offset[a] = static_cast<int>(plan.capsules.size() / 8);
    for (const Capsule& c : world[a]) push_capsule(c);
    plan.cap_offset[a] = static_cast<int>(plan.capsules.size() / 8);
    if (plan.inside_offset[a] >= 0) continue;  // tested on its rendered surface instead
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b || !boxes[a].overlaps(boxes[b])) continue;
      for (const Capsule& c : world[b]) {
        if (!capsule_box(c).overlaps(boxes[a])) continue;
        push_capsule(c);
        ++plan.cap_count[a];
      }
    }
  }
}

/// The level character i draws this frame (its key is plan.mesh[i]).
const LodLevel& drawn_level(const FrameScene& scene, const FramePlan& plan, std::size_t i) {
  for (const LodLevel& l : *scene.lod_sets[i])
    if (l.key == plan.mesh[i]) return l;
  return scene.lod_sets[i]->front();
}

/// Vertex v skinned by the frame's skin matrices of character i (the vertex shader's linear blend).
Vec3 skin_drawn_vertex(const MannequinVertex& v, const FramePlan& plan, std::size_t i) {
  const Eigen::Vector4f p(v.position[0], v.position[1], v.position[2], 1.0f);
  Eigen::Vector4f out = Eigen::Vector4f::Zero();
  for (int k = 0; k < 4; ++k) {
    if (v.weights[k] == 0) continue;
    const Eigen::Map<const Eigen::Matrix4f> m(&plan.skin_matrices[(i * kJointCount + v.bones[k]) * 16]);
    out += (static_cast<float>(v.weights[k]) / 255.0f) * (m * p);
  }
  return out.head<3>().cast<double>();
}

/// Overlap mode: the inside flags of every drawn vertex of the characters that carry a rendered mesh
/// (FramePlan::inside). Offsets are laid out first and filled in parallel: thread-count independent.
void flag_inside_vertices(const CrowdAnimation& crowd, int frame, const FrameScene& scene, FramePlan& plan) {
  const std::size_t n = crowd.characters.size();
  plan.inside.clear();
  plan.inside_offset.assign(n, -1);
  std::vector<const LodLevel*> level(n, nullptr);
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const LodLevel& l = drawn_level(scene, plan, i);
    if (!crowd.characters[i].mesh || !l.vertices) continue;
    level[i] = &l;
    plan.inside_offset[i] = static_cast<int>(total);
    total += l.vertices->size();
  }
  if (total == 0) return;
  plan.inside.assign(total, 0.0f);
  const FrameSurfaces surfaces(crowd, frame);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    if (!level[i]) return;
    const std::vector<MannequinVertex>& vs = *level[i]->vertices;
    float* flags = &plan.inside[static_cast<std::size_t>(plan.inside_offset[i])];
    for (std::size_t v = 0; v < vs.size(); ++v)
      flags[v] =
          surfaces.inside_depth(skin_drawn_vertex(vs[v], plan, i), static_cast<int>(i), kMaxBodyDepth_m) > 0.0
              ? 1.0f
              : 0.0f;
  });
}

void cut_away_boxes(const CrowdAnimation& crowd, int frame, const Camera& camera, const FrameScene& scene,
                    FramePlan& plan) {
  plan.box_hidden.assign(scene.boxes.size(), 0);
  for (std::size_t b = 0; b < scene.boxes.size(); ++b)
    for (const CharacterAnimation& c : crowd.characters) {
      // The chest and the feet: a stage edge or a barrier below the chest still hides the feet.
      const Vec3 root = root_at(c, frame);
      if (segment_hits_box(camera.eye, root + Vec3(0, 0.35, 0), scene.boxes[b]) ||
          segment_hits_box(camera.eye, Vec3(root.x(), 0.1, root.z()), scene.boxes[b])) {
        plan.box_hidden[b] = 1;
        break;
      }
    }
}

void choose_levels_of_detail(const CrowdAnimation& crowd, int frame, const Camera& camera,
                             const SceneOptions& options, const FrameScene& scene, FramePlan& plan) {
  const double pixel_angle =  // metres per pixel per metre of distance
      2.0 * std::tan(0.5 * camera.fov_y_deg * std::numbers::pi / 180.0) / scene.height_px;
  plan.mesh.resize(crowd.characters.size());
  for (std::size_t i = 0; i < crowd.characters.size(); ++i) {
    const double distance = (root_at(crowd.characters[i], frame) - camera.eye).norm();
    plan.mesh[i] = select_lod(*scene.lod_sets[i], options.lod_pixels * distance * pixel_angle).key;
  }
}

void sort_near_to_far(const CrowdAnimation& crowd, int frame, const Camera& camera, FramePlan& plan) {
  const auto& chars = crowd.characters;
  plan.order.resize(chars.size());
  for (std::size_t i = 0; i < chars.size(); ++i) plan.order[i] = i;
  std::stable_sort(plan.order.begin(), plan.order.end(), [&](std::size_t a, std::size_t b) {
    return (root_at(chars[a], frame) - camera.eye).squaredNorm() <
           (root_at(chars[b], frame) - camera.eye).squaredNorm();
  });
}

}  // namespace

std::array<Mat4, kJointCount> inverse_rest_transforms(const BodyShape& shape) {
  const BoneTransforms rest = forward_kinematics(shape, Pose::rest(shape));
  std::array<Mat4, kJointCount> out;
  for (std::size_t j = 0; j < rest.size(); ++j) out[j] = to_matrix(rest[j]).inverse();
  return out;
}

FrameLights frame_lights(const Camera& camera, const Vec3& lo, const Vec3& hi) {
  Vec3 view_h(camera.target.x() - camera.eye.x(), 0.0, camera.target.z() - camera.eye.z());
  view_h = view_h.norm() > 1e-6 ? Vec3(view_h.normalized()) : Vec3(-Vec3::UnitZ());
  FrameLights lights;
  lights.key_dir = light_direction(-view_h, 35.0, 50.0);
  lights.fill_dir = light_direction(-view_h, -60.0, 20.0);
  lights.rim_dir = light_direction(view_h, 20.0, 35.0);
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm() + 0.5;
  Camera light_cam;
  light_cam.eye = centre + lights.key_dir * (radius + 1.0);
  light_cam.target = centre;
  lights.light_view_proj = ortho(radius, 0.5, 2.0 * radius + 2.0) * light_cam.view();
  return lights;
}

void prepare_frame(const CrowdAnimation& crowd, int frame, const Camera& camera, const SceneOptions& options,
                   const FrameScene& scene, FramePlan& plan) {
  if (frame < 0 || frame >= crowd.frame_count())
    throw InputError("frame " + std::to_string(frame) + " out of range [0, " +
                     std::to_string(crowd.frame_count()) + ")");
  const std::size_t n = crowd.characters.size();
  if (scene.inverse_rest.size() != n || scene.lod_sets.size() != n)
    throw RuntimeError("prepare_frame: the scene was prepared for another crowd");
  std::vector<WorldCapsules> world;
  std::vector<Aabb> boxes;
  pose_characters(crowd, frame, scene, options.overlap, plan, world, boxes);
  plan.capsules.clear();
  plan.own_offset.assign(n, 0);
  plan.cap_offset.assign(n, 0);
  plan.cap_count.assign(n, 0);
  plan.inside.clear();
  plan.inside_offset.assign(n, -1);
  choose_levels_of_detail(crowd, frame, camera, options, scene, plan);
  if (options.overlap) {
    flag_inside_vertices(crowd, frame, scene, plan);
    gather_overlap_candidates(world, boxes, plan);
  }
  plan.lights = frame_lights(camera, scene.bounds_lo, scene.bounds_hi);
  plan.view_proj = camera.projection() * camera.view();
  cut_away_boxes(crowd, frame, camera, scene, plan);
  sort_near_to_far(crowd, frame, camera, plan);
  if (!options.characters) plan.order.clear();
  plan.contacts.clear();
  for (const std::size_t i : plan.order) {
    const Vec3& r = root_at(crowd.characters[i], frame);
    plan.contacts.insert(plan.contacts.end(),
                         {static_cast<float>(r.x()), static_cast<float>(r.z()), 0.0f, 0.0f});
  }
}

}  // namespace crowdlab::stimuli
