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

}  // namespace

const char* mixamo_bone_for_joint(int joint) {
  if (joint < 0 || joint >= kJointCount) throw InputError("mixamo_bone_for_joint: bad joint index");
  return kMixamoForJoint[static_cast<size_t>(joint)];
}

Mpfb2Body make_mpfb2_body(const Mpfb2Model& model, const Mpfb2ShapeParams& params) {
  const std::vector<Vec3> shaped_dm = shaped_vertices_dm(model, params);

  // 1. Joints on the shaped mesh, plus the three surface end points of leaf bones.
  std::array<Vec3, kJointCount> joint{};
  for (int j = 0; j < kJointCount; ++j)
    joint[static_cast<size_t>(j)] =
        place(bone(model, kMixamoForJoint[static_cast<size_t>(j)]).head, shaped_dm);
  const Vec3 head_top = place(bone(model, "Head").tail, shaped_dm);
  std::array<Vec3, 2> finger_tip = {place(bone(model, "LeftHandMiddle3").tail, shaped_dm),
                                    place(bone(model, "RightHandMiddle3").tail, shaped_dm)};
  std::array<Vec3, 2> toe_tip = {place(bone(model, "LeftToeBase").tail, shaped_dm),
                                 place(bone(model, "RightToeBase").tail, shaped_dm)};

  // 2. Body-group vertices (metres) and the frame shift: feet on y = 0, pelvis above the origin.
  const std::vector<int>& ids = model.body_vertices();
  std::vector<int> to_local(model.base().vertices.size(), -1);
  std::vector<Vec3> verts(ids.size());
  double min_y = HUGE_VAL, max_y = -HUGE_VAL;
  for (size_t i = 0; i < ids.size(); ++i) {
    to_local[static_cast<size_t>(ids[i])] = static_cast<int>(i);
    verts[i] = kDecimetre * shaped_dm[static_cast<size_t>(ids[i])];
    min_y = std::min(min_y, verts[i].y());
    max_y = std::max(max_y, verts[i].y());
  }
  const Vec3 shift(-joint[kPelvis].x(), -min_y, -joint[kPelvis].z());
  for (Vec3& v : verts) v += shift;
  for (Vec3& p : joint) p += shift;
  Vec3 top = head_top + shift;
  for (Vec3& p : finger_tip) p += shift;
  for (Vec3& p : toe_tip) p += shift;

  // 3. Skinning weights, Mixamo bones -> SMPL joints, top 4 per vertex.
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
  Mpfb2Body body;
  body.params = params;
  SkinnedMesh& mesh = body.mesh;
  mesh.rest_vertices_m = verts;
  mesh.rest_joints_m = joint;
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

  const double stature_m = max_y - min_y;  // standing height in MakeHuman's own rest pose

  // 3b. MakeHuman's rest is an A-pose (arms ~45 degrees down and forward, legs apart); crowdlab's
  // rest is a T-pose (body_shape.hpp). Re-pose by skinning: arm bones to +-X, leg bones to -Y.
  to_t_pose(joint, mesh, finger_tip, toe_tip);
  verts = mesh.rest_vertices_m;
  min_y = HUGE_VAL;
  max_y = -HUGE_VAL;
  for (const Vec3& v : verts) {
    min_y = std::min(min_y, v.y());
    max_y = std::max(max_y, v.y());
  }
  const Vec3 refloor(-joint[kPelvis].x(), -min_y, -joint[kPelvis].z());
  for (Vec3& v : verts) v += refloor;
  for (Vec3& p : joint) p += refloor;
  top += refloor;
  for (Vec3& p : finger_tip) p += refloor;
  for (Vec3& p : toe_tip) p += refloor;
  max_y -= min_y;
  min_y = 0.0;
  mesh.rest_vertices_m = verts;
  mesh.rest_joints_m = joint;
  mesh.rest_normals = vertex_normals(mesh.rest_vertices_m, mesh.triangles);

  // 4. Skeleton: rest offsets (bone frames are aligned with the character frame in the rest pose).
  BodyShape& shape = body.shape;
  body.height_m = stature_m;
  shape.params = {params.gender >= 0.5 ? Sex::kMale : Sex::kFemale, body.height_m, 1.0};
  shape.joint_offsets_m[kPelvis] = Vec3(0.0, joint[kPelvis].y(), 0.0);
  for (int j = 1; j < kJointCount; ++j)
    shape.joint_offsets_m[static_cast<size_t>(j)] =
        joint[static_cast<size_t>(j)] - joint[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])];

  // 5. Capsules: axis between joints, radius from the volume of the part the bone carries.
  auto end_of = [&](int j, bool& surface) -> Vec3 {
    surface = false;
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
        surface = true;
        return top;
      case kLeftFoot:
        surface = true;
        return toe_tip[0];
      case kRightFoot:
        surface = true;
        return toe_tip[1];
      case kLeftHand:
        surface = true;
        return finger_tip[0];
      case kRightHand:
        surface = true;
        return finger_tip[1];
      default:
        break;
    }
    for (int c = 1; c < kJointCount; ++c)  // chain bones: their one child joint
      if (kJointParent[static_cast<size_t>(c)] == j) return joint[static_cast<size_t>(c)];
    return joint[static_cast<size_t>(j)];
  };
  std::array<Vec3, kJointCount> seg_a{}, seg_b{};
  std::array<bool, kJointCount> leaf{};
  for (int j = 0; j < kJointCount; ++j) {
    bool surface = false;
    seg_a[static_cast<size_t>(j)] = j == kPelvis ? joint[kLeftHip] : joint[static_cast<size_t>(j)];
    seg_b[static_cast<size_t>(j)] = end_of(j, surface);
    leaf[static_cast<size_t>(j)] = surface;
  }
  // Volume of the body part each bone carries, by the divergence theorem with the field radial to
  // the bone's axis line, F(x) = (x - a) - ((x - a).u) u, whose divergence is 2: V = 1/2 ∮ F.n dA.
  // F is affine, so a triangle contributes exactly F(centroid).n A. Triangles are shared among bones
  // by their mean skinning weights; for a closed part around its own axis this is its exact volume.
  std::array<double, kJointCount> part_volume{};
  std::array<Vec3, kJointCount> axis_dir{};
  for (size_t j = 0; j < kJointCount; ++j) {
    const Vec3 d = seg_b[j] - seg_a[j];
    axis_dir[j] = d.norm() > 1e-9 ? Vec3(d.normalized()) : Vec3::UnitY();
  }
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
      const Vec3 r = centroid - seg_a[j];
      const Vec3 radial = r - r.dot(axis_dir[j]) * axis_dir[j];
      part_volume[j] += w[j] * 0.5 * radial.dot(area_normal);
    }
  }
  for (int j = 0; j < kJointCount; ++j) {
    const auto jj = static_cast<size_t>(j);
    const Vec3 start = seg_a[jj];
    const double len = (seg_b[jj] - start).norm();
    const Vec3 dir = len > 0.0 ? Vec3((seg_b[jj] - start) / len) : Vec3::UnitY();
    const double target = part_volume[jj];
    if (!(target > 0.0))
      throw InputError("MPFB2 body: joint '" + std::string(joint_name(j)) + "' carries no mesh volume");
    // Joint-to-joint bones: the cylinder pi r^2 L carries the part (its caps overlap the neighbouring
    // bones' capsules, so counting them would count that volume twice). Bones ending at the surface:
    // the whole capsule pi r^2 (L - r) + 4/3 pi r^3. Both increase with r; solved by bisection.
    auto volume = [&](double r) {
      if (!leaf[jj]) return std::numbers::pi * r * r * len;  // caps lie inside the neighbours
      return std::numbers::pi * r * r * (std::max(0.0, len - r) + 4.0 / 3.0 * r);
    };
    double lo = 0.0, hi = 0.5;
    for (int iter = 0; iter < 60; ++iter) (volume(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
    const double r = 0.5 * (lo + hi);
    const Vec3 end = leaf[jj] ? Vec3(start + std::max(0.0, len - r) * dir) : seg_b[jj];
    const Vec3 origin = joint[jj];
    shape.capsules[jj] = Capsule{start - origin, end - origin, r};
  }
  compute_rest_contact_pairs(shape);
  validate_body_shape(shape, "MPFB2 body");
  return body;
}

}  // namespace crowdlab
