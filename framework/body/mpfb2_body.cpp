#include "framework/body/mpfb2_body.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {
namespace {

constexpr double kDecimetre = 0.1;  // OBJ units -> metres

constexpr std::array<const char*, kJointCount> kMixamoForJoint = {
    "Hips",        "LeftUpLeg",    "RightUpLeg",    "Spine",     "LeftLeg",         "RightLeg",
    "Spine1",      "LeftFoot",     "RightFoot",     "Spine2",    "LeftToeBase",     "RightToeBase",
    "Neck",        "LeftShoulder", "RightShoulder", "Head",      "LeftArm",         "RightArm",
    "LeftForeArm", "RightForeArm", "LeftHand",      "RightHand", "LeftHandMiddle1", "RightHandMiddle1"};

const std::string kPrefix = "mixamorig:";

/// SMPL joint that a Mixamo bone's skinning weights go to, or -1.
int joint_for_weights(const std::string& bone) {
  const std::string name = bone.rfind(kPrefix, 0) == 0 ? bone.substr(kPrefix.size()) : bone;
  for (const char* finger : {"Thumb", "Index", "Middle", "Ring", "Pinky"}) {
    if (name.find(std::string("Hand") + finger) != std::string::npos)
      return name.rfind("Left", 0) == 0 ? kLeftHand : kRightHand;
  }
  for (int j = 0; j < kJointCount; ++j)
    if (j != kLeftHand && j != kRightHand && name == kMixamoForJoint[static_cast<size_t>(j)]) return j;
  return -1;
}

const RigBone& bone(const Mpfb2Model& model, const std::string& name) {
  const auto it = model.bones().find(kPrefix + name);
  if (it == model.bones().end()) throw InputError("MPFB2 rig: bone '" + kPrefix + name + "' missing");
  return it->second;
}

/// Joint position (metres, Y-up) from a placement rule on the shaped vertices (decimetres).
Vec3 place(const JointPlacement& p, const std::vector<Vec3>& shaped_dm) {
  if (p.strategy == JointPlacement::Strategy::kDefault) return blender_to_y_up(p.default_position_blender);
  Vec3 sum = Vec3::Zero();
  for (int v : p.vertices) sum += shaped_dm[static_cast<size_t>(v)];
  return kDecimetre * sum / static_cast<double>(p.vertices.size());
}

/// Re-poses the A-pose mesh and joints into crowdlab's T-pose: shoulder, elbow, wrist and hand bones
/// of each arm point along +-X (the character's left/right), hip and knee bones straight down.
/// Rotations are the minimal ones (Eigen FromTwoVectors), applied parent-first; the mesh is skinned
/// with its own weights; the end points of the hand and foot bones follow their bones.
void to_t_pose(std::array<Vec3, kJointCount>& joint, SkinnedMesh& mesh, std::array<Vec3, 2>& finger_tip,
               std::array<Vec3, 2>& toe_tip) {
  BodyShape a_pose;
  a_pose.joint_offsets_m[kPelvis] = joint[kPelvis];
  for (int j = 1; j < kJointCount; ++j)
    a_pose.joint_offsets_m[static_cast<size_t>(j)] =
        joint[static_cast<size_t>(j)] - joint[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])];
  std::array<Quat, kJointCount> world;
  world.fill(Quat::Identity());
  Pose pose;
  pose.root_position_m = joint[kPelvis];
  auto aim = [&](int j, const Vec3& child, const Vec3& target) {
    const Quat parent = world[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])];
    const Vec3 current = parent * (child - joint[static_cast<size_t>(j)]);
    const Quat w = Quat::FromTwoVectors(current, target) * parent;
    world[static_cast<size_t>(j)] = w;
    pose.local_rotations[static_cast<size_t>(j)] = (parent.conjugate() * w).normalized();
  };
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? 1.0 : -1.0;
    const int sh = side == 0 ? kLeftShoulder : kRightShoulder, el = side == 0 ? kLeftElbow : kRightElbow;
    const int wr = side == 0 ? kLeftWrist : kRightWrist, ha = side == 0 ? kLeftHand : kRightHand;
    const int hip = side == 0 ? kLeftHip : kRightHip, knee = side == 0 ? kLeftKnee : kRightKnee;
    const int ankle = side == 0 ? kLeftAnkle : kRightAnkle;
    for (const auto& [j, child] :
         std::array<std::pair<int, Vec3>, 4>{{{sh, joint[static_cast<size_t>(el)]},
                                              {el, joint[static_cast<size_t>(wr)]},
                                              {wr, joint[static_cast<size_t>(ha)]},
                                              {ha, finger_tip[static_cast<size_t>(side)]}}})
      aim(j, child, Vec3(x, 0, 0));
    aim(hip, joint[static_cast<size_t>(knee)], -Vec3::UnitY());
    aim(knee, joint[static_cast<size_t>(ankle)], -Vec3::UnitY());
  }
  const BoneTransforms bones = forward_kinematics(a_pose, pose);
  mesh.rest_vertices_m = skin_vertices(mesh, bones);
  for (int side = 0; side < 2; ++side) {
    const int ha = side == 0 ? kLeftHand : kRightHand, foot = side == 0 ? kLeftFoot : kRightFoot;
    finger_tip[static_cast<size_t>(side)] = bones[static_cast<size_t>(ha)].apply(
        finger_tip[static_cast<size_t>(side)] - joint[static_cast<size_t>(ha)]);
    toe_tip[static_cast<size_t>(side)] = bones[static_cast<size_t>(foot)].apply(
        toe_tip[static_cast<size_t>(side)] - joint[static_cast<size_t>(foot)]);
  }
  for (int j = 0; j < kJointCount; ++j)
    joint[static_cast<size_t>(j)] = bones[static_cast<size_t>(j)].translation;
}

/// The skeleton's landmarks (metres, Y-up): the 24 joints plus the surface end points of the leaf
/// bones (top of the head, middle fingertips, toe tips; index 0 left, 1 right).
struct BodyLandmarks {
  std::array<Vec3, kJointCount> joint{};
  Vec3 head_top = Vec3::Zero();
  std::array<Vec3, 2> finger_tip{}, toe_tip{};

  void translate(const Vec3& d) {
    for (Vec3& p : joint) p += d;
    head_top += d;
    for (Vec3& p : finger_tip) p += d;
    for (Vec3& p : toe_tip) p += d;
  }
};

/// Step 1: the joints and leaf end points placed on the shaped mesh (decimetres).
BodyLandmarks place_landmarks(const Mpfb2Model& model, const std::vector<Vec3>& shaped_dm) {
  BodyLandmarks lm;
  for (int j = 0; j < kJointCount; ++j)
    lm.joint[static_cast<size_t>(j)] =
        place(bone(model, kMixamoForJoint[static_cast<size_t>(j)]).head, shaped_dm);
  lm.head_top = place(bone(model, "Head").tail, shaped_dm);
  lm.finger_tip = {place(bone(model, "LeftHandMiddle3").tail, shaped_dm),
                   place(bone(model, "RightHandMiddle3").tail, shaped_dm)};
  lm.toe_tip = {place(bone(model, "LeftToeBase").tail, shaped_dm),
                place(bone(model, "RightToeBase").tail, shaped_dm)};
  return lm;
}

/// Lowest and highest y of a vertex set (metres).
struct VerticalRange {
  double min_y = HUGE_VAL, max_y = -HUGE_VAL;
};

VerticalRange vertical_range(const std::vector<Vec3>& verts) {
  VerticalRange r;
  for (const Vec3& v : verts) {
    r.min_y = std::min(r.min_y, v.y());
    r.max_y = std::max(r.max_y, v.y());
  }
  return r;
}

/// Stands the body on the floor: the lowest vertex (at min_y) to y = 0 and the pelvis above the origin.
void stand_on_floor(std::vector<Vec3>& verts, BodyLandmarks& lm, double min_y) {
  const Vec3 shift(-lm.joint[kPelvis].x(), -min_y, -lm.joint[kPelvis].z());
  for (Vec3& v : verts) v += shift;
  lm.translate(shift);
}

/// Step 2: the body group's vertices in metres; to_local maps a base-mesh vertex index to its index
/// here (-1 for vertices outside the body group).
std::vector<Vec3> body_vertices_m(const Mpfb2Model& model, const std::vector<Vec3>& shaped_dm,
                                  std::vector<int>& to_local) {
  const std::vector<int>& ids = model.body_vertices();
  to_local.assign(model.base().vertices.size(), -1);
  std::vector<Vec3> verts(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    to_local[static_cast<size_t>(ids[i])] = static_cast<int>(i);
    verts[i] = kDecimetre * shaped_dm[static_cast<size_t>(ids[i])];
  }
  return verts;
}

/// Step 3: skinning weights, Mixamo bones -> SMPL joints, the 4 largest per vertex renormalised (a
/// vertex without weight is bound rigidly to its nearest joint); the triangles of the body group.
void bind_skin(const Mpfb2Model& model, const std::vector<int>& to_local,
               const std::array<Vec3, kJointCount>& joint, SkinnedMesh& mesh) {
  const std::vector<Vec3>& verts = mesh.rest_vertices_m;
  std::vector<std::array<double, kJointCount>> acc(verts.size());
  for (auto& a : acc) a.fill(0.0);
  for (const auto& [bone_name, list] : model.weights()) {
    const int j = joint_for_weights(bone_name);
    if (j < 0) continue;
    for (const auto& [v, w] : list) {
      const int local = to_local[static_cast<size_t>(v)];
      if (local >= 0 && w > 0.0) acc[static_cast<size_t>(local)][static_cast<size_t>(j)] += w;
    }
  }
  mesh.joints.resize(verts.size());
  mesh.weights.resize(verts.size());
  mesh.region.resize(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) {
    std::array<int, kJointCount> order{};
    for (int j = 0; j < kJointCount; ++j) order[static_cast<size_t>(j)] = j;
    const auto& a = acc[i];
    std::stable_sort(order.begin(), order.end(),
                     [&](int x, int y) { return a[static_cast<size_t>(x)] > a[static_cast<size_t>(y)]; });
    double total = 0.0;
    for (size_t k = 0; k < 4; ++k) total += a[static_cast<size_t>(order[k])];
    if (total <= 0.0) {
      // No weight: bind rigidly to the nearest joint.
      int nearest = 0;
      for (int j = 1; j < kJointCount; ++j)
        if ((verts[i] - joint[static_cast<size_t>(j)]).norm() <
            (verts[i] - joint[static_cast<size_t>(nearest)]).norm())
          nearest = j;
      mesh.joints[i] = {nearest, 0, 0, 0};
      mesh.weights[i] = {1.0, 0.0, 0.0, 0.0};
    } else {
      for (size_t k = 0; k < 4; ++k) {
        const double w = a[static_cast<size_t>(order[k])] / total;
        mesh.joints[i][k] = w > 0.0 ? order[k] : 0;
        mesh.weights[i][k] = w;
      }
    }
    mesh.region[i] = mesh.joints[i][0];
  }
  for (const auto& t : model.body_triangles())
    mesh.triangles.emplace_back(to_local[static_cast<size_t>(t[0])], to_local[static_cast<size_t>(t[1])],
                                to_local[static_cast<size_t>(t[2])]);
}

/// Step 5: the skeleton's rest offsets (bone frames are aligned with the character frame at rest).
void set_rest_offsets(const std::array<Vec3, kJointCount>& joint, BodyShape& shape) {
  shape.joint_offsets_m[kPelvis] = Vec3(0.0, joint[kPelvis].y(), 0.0);
  for (int j = 1; j < kJointCount; ++j)
    shape.joint_offsets_m[static_cast<size_t>(j)] =
        joint[static_cast<size_t>(j)] - joint[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])];
}

/// The axis segment of each bone's capsule, before leaf axes are shortened by their radius.
struct CapsuleAxes {
  std::array<Vec3, kJointCount> a{}, b{};
};

/// Where bone j's axis ends (see the header): the next joint, or a surface landmark for leaf bones.
Vec3 axis_end(int j, const BodyLandmarks& lm) {
  const auto& joint = lm.joint;
  switch (j) {
    case kPelvis:
      return joint[kRightHip];
    case kSpine1:
      return joint[kSpine2];
    case kSpine2:
      return joint[kSpine3];
    case kSpine3:
      return joint[kNeck];
    case kNeck:
      return joint[kHead];
    case kHead:
      return lm.head_top;
    case kLeftFoot:
      return lm.toe_tip[0];
    case kRightFoot:
      return lm.toe_tip[1];
    case kLeftHand:
      return lm.finger_tip[0];
    case kRightHand:
      return lm.finger_tip[1];
    default:
      break;
  }
  for (int c = 1; c < kJointCount; ++c)  // chain bones: their one child joint
    if (kJointParent[static_cast<size_t>(c)] == j) return joint[static_cast<size_t>(c)];
  return joint[static_cast<size_t>(j)];
}

CapsuleAxes capsule_axes(const BodyLandmarks& lm) {
  CapsuleAxes axes;
  for (int j = 0; j < kJointCount; ++j) {
    axes.a[static_cast<size_t>(j)] = j == kPelvis ? lm.joint[kLeftHip] : lm.joint[static_cast<size_t>(j)];
    axes.b[static_cast<size_t>(j)] = axis_end(j, lm);
  }
  return axes;
}

/// The radius (m) whose modelled volume is target_m3: the cylinder pi r^2 L for a joint-to-joint bone
/// (its caps lie inside the neighbouring bones' capsules, so counting them would count that volume
/// twice), the whole capsule pi r^2 (L - r) + 4/3 pi r^3 for a bone ending at the surface. Both grow
/// with r; solved by bisection on [0, 0.5 m] to machine precision.
double capsule_radius_for_volume(double length_m, bool ends_at_surface, double target_m3) {
  auto volume = [&](double r) {
    if (!ends_at_surface) return std::numbers::pi * r * r * length_m;
    return std::numbers::pi * r * r * (std::max(0.0, length_m - r) + 4.0 / 3.0 * r);
  };
  double lo = 0.0, hi = 0.5;
  for (int iter = 0; iter < 60; ++iter) (volume(0.5 * (lo + hi)) < target_m3 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

/// Step 6: one capsule per bone, its radius matching the volume of the part the bone carries.
void fit_capsules(const SkinnedMesh& mesh, const BodyLandmarks& lm, BodyShape& shape) {
  const CapsuleAxes axes = capsule_axes(lm);
  std::array<Vec3, kJointCount> axis_dir{};
  for (size_t j = 0; j < kJointCount; ++j) {
    const Vec3 d = axes.b[j] - axes.a[j];
    axis_dir[j] = d.norm() > 1e-9 ? Vec3(d.normalized()) : Vec3::UnitY();
  }
  const std::array<double, kJointCount> part_volume = body_part_volumes_m3(mesh, axes.a, axis_dir);
  for (int j = 0; j < kJointCount; ++j) {
    const auto jj = static_cast<size_t>(j);
    const Vec3 start = axes.a[jj];
    const double len = (axes.b[jj] - start).norm();
    const Vec3 dir = len > 0.0 ? Vec3((axes.b[jj] - start) / len) : Vec3::UnitY();
    if (!(part_volume[jj] > 0.0))
      throw InputError("MPFB2 body: joint '" + std::string(joint_name(j)) + "' carries no mesh volume");
    const bool leaf = mpfb2_bone_ends_at_surface(j);
    const double r = capsule_radius_for_volume(len, leaf, part_volume[jj]);
    // Axes ending at the surface are shortened by r so the cap ends there.
    const Vec3 end = leaf ? Vec3(start + std::max(0.0, len - r) * dir) : axes.b[jj];
    const Vec3 origin = lm.joint[jj];
    shape.capsules[jj] = Capsule{start - origin, end - origin, r};
  }
}

}  // namespace

const char* mixamo_bone_for_joint(int joint) {
  if (joint < 0 || joint >= kJointCount) throw InputError("mixamo_bone_for_joint: bad joint index");
  return kMixamoForJoint[static_cast<size_t>(joint)];
}

bool mpfb2_bone_ends_at_surface(int joint) {
  return joint == kHead || joint == kLeftFoot || joint == kRightFoot || joint == kLeftHand ||
         joint == kRightHand;
}

std::array<double, kJointCount> body_part_volumes_m3(const SkinnedMesh& mesh,
                                                     const std::array<Vec3, kJointCount>& axis_point,
                                                     const std::array<Vec3, kJointCount>& axis_dir) {
  // F(x) = (x - a) - ((x - a).u) u is affine, so a triangle contributes exactly F(centroid).n A.
  const std::vector<Vec3>& verts = mesh.rest_vertices_m;
  std::array<double, kJointCount> part_volume{};
  for (const auto& t : mesh.triangles) {
    const Vec3& v0 = verts[static_cast<size_t>(t[0])];
    const Vec3& v1 = verts[static_cast<size_t>(t[1])];
    const Vec3& v2 = verts[static_cast<size_t>(t[2])];
    const Vec3 centroid = (v0 + v1 + v2) / 3.0;
    const Vec3 area_normal = 0.5 * (v1 - v0).cross(v2 - v0);
    std::array<double, kJointCount> w{};
    for (int k = 0; k < 3; ++k) {
      const auto vi = static_cast<size_t>(t[k]);
      for (size_t q = 0; q < 4; ++q) w[static_cast<size_t>(mesh.joints[vi][q])] += mesh.weights[vi][q] / 3.0;
    }
    for (size_t j = 0; j < kJointCount; ++j) {
      if (w[j] <= 0.0) continue;
      const Vec3 r = centroid - axis_point[j];
      const Vec3 radial = r - r.dot(axis_dir[j]) * axis_dir[j];
      part_volume[j] += w[j] * 0.5 * radial.dot(area_normal);
    }
  }
  return part_volume;
}

Mpfb2Body make_mpfb2_body(const Mpfb2Model& model, const Mpfb2ShapeParams& params) {
  const std::vector<Vec3> shaped_dm = shaped_vertices_dm(model, params);
  BodyLandmarks lm = place_landmarks(model, shaped_dm);

  Mpfb2Body body;
  body.params = params;
  SkinnedMesh& mesh = body.mesh;
  std::vector<int> to_local;
  mesh.rest_vertices_m = body_vertices_m(model, shaped_dm, to_local);
  const VerticalRange as_made = vertical_range(mesh.rest_vertices_m);
  stand_on_floor(mesh.rest_vertices_m, lm, as_made.min_y);
  bind_skin(model, to_local, lm.joint, mesh);
  // Standing height in MakeHuman's own rest pose.
  body.height_m = as_made.max_y - as_made.min_y;

  // Step 4: MakeHuman's rest is an A-pose (arms ~45 degrees down and forward, legs apart); crowdlab's
  // rest is a T-pose (body_shape.hpp). Re-pose by skinning (arm bones to +-X, leg bones to -Y) and
  // stand the T-posed body on the floor again.
  mesh.rest_joints_m = lm.joint;
  to_t_pose(lm.joint, mesh, lm.finger_tip, lm.toe_tip);
  stand_on_floor(mesh.rest_vertices_m, lm, vertical_range(mesh.rest_vertices_m).min_y);
  mesh.rest_joints_m = lm.joint;
  mesh.rest_normals = vertex_normals(mesh.rest_vertices_m, mesh.triangles);

  BodyShape& shape = body.shape;
  shape.params = {params.gender >= 0.5 ? Sex::kMale : Sex::kFemale, body.height_m, 1.0};
  set_rest_offsets(lm.joint, shape);
  fit_capsules(mesh, lm, shape);
  compute_rest_contact_pairs(shape);
  validate_body_shape(shape, "MPFB2 body");
  return body;
}

}  // namespace crowdlab
