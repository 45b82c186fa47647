#include "framework/body/mpfb2_body.hpp"

#include "framework/body/tuck_under_garments.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {
namespace {

constexpr double kDecimetre = 0.1;  // OBJ units -> metres
// Lips relative to the eyes on the base mesh (see mouth_surface).
constexpr double kBaseEyeDistanceM = 0.0616, kLipDropM = 0.061, kLipHalfWidthM = 0.024,
                 kLipHalfHeightM = 0.008;
constexpr double kLipThicknessM = 0.012, kLipAheadOfEyesM = 0.025;

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

/// Step 2b: a relaxed hand. MakeHuman's base mesh holds its fingers straight and spread; a hand at rest
/// is flexed a little at every finger joint, more toward the little finger (the hand's resting "cascade").
/// Each finger (index..pinky) bends about the knuckle line (index to pinky knuckle) by kFingerCurlDeg per
/// joint (MCP, PIP, DIP), toward the palm (the side facing the body's midline in the A-pose), most at the
/// knuckle (MCP) and least at the tip, since a finger bent mostly at its middle joints reads as a claw
/// (issue 28), and the skin follows by linear blend skinning with the rig's finger weights. First each
/// finger closes its spread (adduction_rad): relaxed fingers lie side by side. Session 11 closed 75 % of
/// the rig bones' spread, which left the fingers of a raised hand, seen from the palm or the back, visibly
/// apart (neighbouring fingers 2.4-3.7 mm farther apart at their last segment than at their first).
/// The thumb flexes across the palm by kThumbCurlDeg per joint.
/// Landmarks (the middle fingertip that aims the hand in to_t_pose) are not moved.
constexpr std::array<std::array<double, 3>, 4> kFingerCurlDeg = {{{24, 16, 8},     // index
                                                                  {28, 18, 9},     // middle
                                                                  {32, 20, 10},    // ring
                                                                  {36, 22, 10}}};  // pinky

/// How much closer the fingertips lie to the middle finger's line than their knuckles do, once the
/// fingers are parallel: the fingers of a resting hand converge slightly, tips touching (a knuckle 2 cm
/// beside the middle finger's brings its tip to 1.7 cm).
constexpr double kFingertipConvergence = 0.15;
/// The little finger leans this much more toward the ring finger: it flexes most (kFingerCurlDeg) about
/// the rig's knuckle line, which is tilted against the skin's, and that fanned its skin out from the ring
/// finger's by 1.4 mm at the tip with kFingertipConvergence alone (test "relaxed fingers lie side by side").
constexpr double kLittleFingerExtraLeanDeg = 3.0;
constexpr std::array<double, 3> kThumbCurlDeg = {10, 15, 20};  // Thumb1 (CMC), Thumb2 (MCP), Thumb3 (IP)

/// The extra turn (radians, about `palm_normal`) that leans a finger parallel to the middle finger toward
/// it, so that its tip is kFingertipConvergence closer to the middle finger's line than its knuckle:
/// `knuckle_offset` is the knuckle's offset from the middle finger's, `length` the finger's length.
double adduction_rad(const Vec3& knuckle_offset, double length, const Vec3& middle_dir, const Vec3& axis,
                     const Vec3& palm_normal) {
  const double lateral = knuckle_offset.dot(axis);  // signed, along the knuckle line
  if (std::abs(lateral) < 1e-9 || length <= 0.0) return 0.0;
  const double lean = std::atan2(kFingertipConvergence * std::abs(lateral), length);
  // The sign that brings the tip toward the middle finger's line.
  const Vec3 turned = Eigen::AngleAxisd(lean, palm_normal) * middle_dir.normalized();
  return turned.dot(axis) * lateral < 0.0 ? lean : -lean;
}

/// kLittleFingerExtraLeanDeg, signed toward the middle finger's line (as adduction_rad).
double pinky_extra_lean_rad(const Vec3& knuckle_offset, const Vec3& middle_dir, const Vec3& axis,
                            const Vec3& palm_normal) {
  const double lean = kLittleFingerExtraLeanDeg * std::numbers::pi / 180.0;
  const Vec3 turned = Eigen::AngleAxisd(lean, palm_normal) * middle_dir.normalized();
  return turned.dot(axis) * knuckle_offset.dot(axis) < 0.0 ? lean : -lean;
}

void relax_fingers(const Mpfb2Model& model, const std::vector<Vec3>& shaped_dm, const std::vector<int>& ids,
                   std::vector<Vec3>& verts) {
  // Per base vertex: total rig weight, and per finger bone its affine transform.
  std::vector<double> total(model.base().vertices.size(), 0.0);
  for (const auto& [name, list] : model.weights())
    for (const auto& [v, w] : list) total[static_cast<size_t>(v)] += std::max(w, 0.0);
  std::map<std::string, Eigen::Affine3d> transform;
  std::vector<int> to_local(model.base().vertices.size(), -1);
  for (size_t i = 0; i < ids.size(); ++i) to_local[static_cast<size_t>(ids[i])] = static_cast<int>(i);
  // The centroid of the skin a rig bone dominates (weight > 0.5).
  const auto skin_of = [&](const std::string& bone_name) {
    Vec3 sum = Vec3::Zero();
    double n = 0.0;
    const auto it = model.weights().find(bone(model, bone_name).name);
    if (it != model.weights().end())
      for (const auto& [v, w] : it->second)
        if (const int l = to_local[static_cast<size_t>(v)]; w > 0.5 && l >= 0) {
          sum += verts[static_cast<size_t>(l)];
          n += 1.0;
        }
    return Vec3(n > 0.0 ? Vec3(sum / n) : Vec3::Zero());
  };
  static const std::array<const char*, 4> kFingers = {"Index", "Middle", "Ring", "Pinky"};
  for (const char* side : {"Left", "Right"}) {
    const std::string hand = std::string(side) + "Hand";
    const Vec3 index1 = place(bone(model, hand + "Index1").head, shaped_dm);
    const Vec3 pinky1 = place(bone(model, hand + "Pinky1").head, shaped_dm);
    const Vec3 wrist = place(bone(model, hand).head, shaped_dm);
    const Vec3 axis = (pinky1 - index1).normalized();
    const Vec3 medial(-wrist.x(), 0.0, 0.0);  // toward the midline
    const auto finger_dir = [&](const char* finger) {
      return Vec3(place(bone(model, hand + finger + "3").tail, shaped_dm) -
                  place(bone(model, hand + finger + "1").head, shaped_dm));
    };
    const Vec3 middle_dir = finger_dir("Middle");
    const Vec3 palm_normal = axis.cross(middle_dir).normalized();
    const Vec3 middle1 = place(bone(model, hand + "Middle1").head, shaped_dm);
    // The fingers' directions as the skin shows them (first to last segment's skin): the rig's bones
    // follow the mesh's fingers only roughly, and closing the bones' spread left the little finger's skin
    // fanned out from the ring finger's.
    const auto skin_dir = [&](const char* finger) {
      return Vec3(skin_of(hand + finger + "3") - skin_of(hand + finger + "1"));
    };
    const Vec3 middle_skin = skin_dir("Middle");
    for (size_t f = 0; f < kFingers.size(); ++f) {
      // Spread: the base mesh's fingers fan out; a resting hand holds them together, parallel to the middle
      // finger and then leaning toward it (adduction_rad), turned at the knuckle about the palm's normal.
      const Vec3 dir = finger_dir(kFingers[f]), skin = skin_dir(kFingers[f]);
      const double spread =
          std::atan2(skin.cross(middle_skin).dot(palm_normal), skin.dot(middle_skin)) +
          adduction_rad(place(bone(model, hand + kFingers[f] + "1").head, shaped_dm) - middle1, dir.norm(),
                        middle_dir, axis, palm_normal) +
          (f == 3 ? pinky_extra_lean_rad(place(bone(model, hand + "Pinky1").head, shaped_dm) - middle1,
                                         middle_dir, axis, palm_normal)
                  : 0.0);
      Eigen::Affine3d chain = Eigen::Affine3d::Identity();
      for (int k = 1; k <= 3; ++k) {
        const RigBone& b = bone(model, hand + kFingers[f] + std::to_string(k));
        const Vec3 head = place(b.head, shaped_dm), tail = place(b.tail, shaped_dm);
        const double angle = kFingerCurlDeg[f][static_cast<size_t>(k - 1)] * std::numbers::pi / 180.0;
        // The sign that moves this bone's tail toward the palm.
        const Vec3 moved = Eigen::AngleAxisd(angle, axis) * (tail - head);
        const double sign = (moved - (tail - head)).dot(medial) >= 0.0 ? 1.0 : -1.0;
        Eigen::Affine3d bend =
            Eigen::Translation3d(head) * Eigen::AngleAxisd(sign * angle, axis) * Eigen::Translation3d(-head);
        if (k == 1)
          bend = bend * Eigen::Translation3d(head) * Eigen::AngleAxisd(spread, palm_normal) *
                 Eigen::Translation3d(-head);
        chain = chain * bend;
        transform[b.name] = chain;
      }
    }
    // The thumb: MakeHuman's lies nearly straight beside the palm. At rest it is flexed a little at each
    // joint (kThumbCurlDeg: the carpometacarpal joint, then MCP and IP), across the palm: each thumb bone
    // turns about the axis normal to it and to the palm's normal, toward the palm normal's lateral side
    // (its tip then lies 4.1 cm from the index knuckle instead of 7.1 cm on the default body; the other
    // side moves it 9.8 cm away, out of the hand).
    const Vec3 palm_side = palm_normal.dot(medial) >= 0.0 ? Vec3(-palm_normal) : palm_normal;
    Eigen::Affine3d chain = Eigen::Affine3d::Identity();
    for (int k = 1; k <= 3; ++k) {
      const RigBone& b = bone(model, hand + "Thumb" + std::to_string(k));
      const Vec3 head = place(b.head, shaped_dm), tail = place(b.tail, shaped_dm);
      const Vec3 bend_axis = (tail - head).cross(palm_side).normalized();  // turns the tail across the palm
      const double angle = kThumbCurlDeg[static_cast<size_t>(k - 1)] * std::numbers::pi / 180.0;
      chain = chain * (Eigen::Translation3d(head) * Eigen::AngleAxisd(angle, bend_axis) *
                       Eigen::Translation3d(-head));
      transform[b.name] = chain;
    }
  }
  std::vector<Vec3> moved(verts.size(), Vec3::Zero());
  std::vector<double> moved_weight(verts.size(), 0.0);
  for (const auto& [name, xf] : transform) {
    const auto it = model.weights().find(name);
    if (it == model.weights().end()) continue;
    for (const auto& [v, w] : it->second) {
      const int local = to_local[static_cast<size_t>(v)];
      if (local < 0 || w <= 0.0 || total[static_cast<size_t>(v)] <= 0.0) continue;
      const double share = w / total[static_cast<size_t>(v)];
      moved[static_cast<size_t>(local)] += share * (xf * verts[static_cast<size_t>(local)]);
      moved_weight[static_cast<size_t>(local)] += share;
    }
  }
  for (size_t i = 0; i < verts.size(); ++i)
    if (moved_weight[i] > 0.0) verts[i] = moved[i] + (1.0 - moved_weight[i]) * verts[i];
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

/// The SMPL joint weights of every base-mesh vertex (Mixamo bones mapped to joints, summed; unnormalised).
std::vector<std::array<double, kJointCount>> base_joint_weights(const Mpfb2Model& model) {
  std::vector<std::array<double, kJointCount>> acc(model.base().vertices.size());
  for (auto& a : acc) a.fill(0.0);
  for (const auto& [bone_name, list] : model.weights()) {
    const int j = joint_for_weights(bone_name);
    if (j < 0) continue;
    for (const auto& [v, w] : list)
      if (w > 0.0) acc[static_cast<size_t>(v)][static_cast<size_t>(j)] += w;
  }
  return acc;
}

/// Vertex i's 4 largest joint weights of `a`, renormalised (a vertex without weight is bound rigidly to
/// its nearest joint).
void set_skin_weights(const std::array<double, kJointCount>& a, const std::array<Vec3, kJointCount>& joint,
                      SkinnedMesh& mesh, size_t i) {
  const Vec3& p = mesh.rest_vertices_m[i];
  std::array<int, kJointCount> order{};
  for (int j = 0; j < kJointCount; ++j) order[static_cast<size_t>(j)] = j;
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return a[static_cast<size_t>(x)] > a[static_cast<size_t>(y)]; });
  double total = 0.0;
  for (size_t k = 0; k < 4; ++k) total += a[static_cast<size_t>(order[k])];
  if (total <= 0.0) {
    int nearest = 0;
    for (int j = 1; j < kJointCount; ++j)
      if ((p - joint[static_cast<size_t>(j)]).norm() < (p - joint[static_cast<size_t>(nearest)]).norm())
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

/// Step 3: skinning weights, Mixamo bones -> SMPL joints, the 4 largest per vertex renormalised; the
/// triangles of the body group.
void bind_skin(const Mpfb2Model& model, const std::vector<int>& to_local,
               const std::vector<std::array<double, kJointCount>>& base_weights,
               const std::array<Vec3, kJointCount>& joint, SkinnedMesh& mesh) {
  const std::vector<int>& ids = model.body_vertices();
  mesh.joints.resize(ids.size());
  mesh.weights.resize(ids.size());
  mesh.region.resize(ids.size());
  for (size_t i = 0; i < ids.size(); ++i)
    set_skin_weights(base_weights[static_cast<size_t>(ids[i])], joint, mesh, i);
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

/// Every base-mesh vertex shaped: body vertices as the targets move them, helper geometry by its
/// anchor's displacement (Mpfb2Model::shape_anchor).
std::vector<Vec3> anchored_vertices_dm(const Mpfb2Model& model, const std::vector<Vec3>& shaped_dm) {
  const std::vector<Vec3>& base = model.base().vertices;
  std::vector<Vec3> out(base.size());
  for (size_t v = 0; v < base.size(); ++v) {
    const auto a = static_cast<size_t>(model.shape_anchor()[v]);
    out[v] = base[v] + (shaped_dm[a] - base[a]);
  }
  return out;
}

/// Surface labels of the body's vertices: skin, and lips, found from the eyes (the base mesh's eyeball
/// groups, anchored like all helper geometry; the eyes are where any face's proportions start). On
/// MakeHuman's base mesh the face's profile has the nose tip 3.5 cm below the eyes' midpoint, the lips'
/// bulge 5.3 to 7.0 cm below it (3.6 cm in front), the chin below that, and the eyes are 6.16 cm apart; on a
/// shaped body these lengths scale with its eye distance s. Lips: within an ellipse 2.4 s wide and 0.8 s
/// high either side of the point 6.1 s below the eyes' midpoint (an adult mouth is about 5 cm wide), at
/// most 1.2 s behind the ellipse's foremost vertex and at least 2.5 s in front of the eyes.
std::vector<std::uint8_t> mouth_surface(const Mpfb2Model& model, const std::vector<Vec3>& shaped_dm,
                                        const Vec3& shift, const std::vector<Vec3>& verts_m) {
  std::vector<std::uint8_t> out(verts_m.size(), static_cast<std::uint8_t>(SurfaceKind::kSkin));
  const std::vector<Vec3>& base = model.base().vertices;
  const auto centre_m = [&](const char* group, bool& found) {
    const int g = model.base().group_index(group);
    found = g >= 0;
    Vec3 c = Vec3::Zero();
    if (!found) return c;
    const std::vector<int> ids = model.base().group_vertices(g);
    for (int v : ids) {
      const auto a = static_cast<size_t>(model.shape_anchor()[static_cast<size_t>(v)]);
      c += base[static_cast<size_t>(v)] + (shaped_dm[a] - base[a]);
    }
    return Vec3(kDecimetre * c / static_cast<double>(ids.size()) + shift);
  };
  bool left_found = false, right_found = false;
  const Vec3 left = centre_m("helper-l-eye", left_found), right = centre_m("helper-r-eye", right_found);
  if (!left_found || !right_found) return out;
  const double s = std::abs(left.x() - right.x()) / kBaseEyeDistanceM;
  const Vec3 lips = 0.5 * (left + right) - Vec3(0.0, kLipDropM * s, 0.0);
  std::vector<double> depth(verts_m.size(), -HUGE_VAL);
  double front = -HUGE_VAL;
  for (size_t i = 0; i < verts_m.size(); ++i) {
    const Vec3 d = verts_m[i] - lips;
    const double ex = d.x() / (kLipHalfWidthM * s), ey = d.y() / (kLipHalfHeightM * s);
    if (ex * ex + ey * ey < 1.0 && d.z() > kLipAheadOfEyesM * s) {
      depth[i] = d.z();
      front = std::max(front, d.z());
    }
  }
  for (size_t i = 0; i < verts_m.size(); ++i)
    if (depth[i] > front - kLipThicknessM * s) out[i] = static_cast<std::uint8_t>(SurfaceKind::kLips);
  return out;
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

Mpfb2Body make_mpfb2_body(const Mpfb2Model& model, const Mpfb2ShapeParams& params,
                          const Mpfb2Outfit* outfit) {
  const std::vector<Vec3> shaped_dm = shaped_vertices_dm(model, params);
  BodyLandmarks lm = place_landmarks(model, shaped_dm);

  Mpfb2Body body;
  body.params = params;
  SkinnedMesh& mesh = body.mesh;
  std::vector<int> to_local;
  mesh.rest_vertices_m = body_vertices_m(model, shaped_dm, to_local);
  relax_fingers(model, shaped_dm, model.body_vertices(), mesh.rest_vertices_m);
  const VerticalRange as_made = vertical_range(mesh.rest_vertices_m);
  const Vec3 first_shift(-lm.joint[kPelvis].x(), -as_made.min_y, -lm.joint[kPelvis].z());
  stand_on_floor(mesh.rest_vertices_m, lm, as_made.min_y);
  const std::vector<std::array<double, kJointCount>> base_weights = base_joint_weights(model);
  bind_skin(model, to_local, base_weights, lm.joint, mesh);
  const size_t body_vertex_count = mesh.rest_vertices_m.size();
  if (outfit) mesh.surface = mouth_surface(model, shaped_dm, first_shift, mesh.rest_vertices_m);
  // Standing height in MakeHuman's own rest pose.
  body.height_m = as_made.max_y - as_made.min_y;

  // Eyes, eyebrows, hair, clothes and shoes (body/mpfb2_outfit.hpp), skinned like the skin they lie on.
  std::vector<Eigen::Vector3i> outfit_triangles;
  std::vector<int> hidden;
  if (outfit) {
    OutfitGeometry g = outfit_geometry(model, *outfit, anchored_vertices_dm(model, shaped_dm), base_weights);
    for (size_t v = 0; v < g.vertices_dm.size(); ++v) {
      mesh.rest_vertices_m.push_back(kDecimetre * g.vertices_dm[v] + first_shift);
      mesh.joints.emplace_back();
      mesh.weights.emplace_back();
      mesh.region.push_back(0);
      set_skin_weights(g.joint_weights[v], lm.joint, mesh, mesh.rest_vertices_m.size() - 1);
    }
    mesh.surface.insert(mesh.surface.end(), g.surface.begin(), g.surface.end());
    for (const Eigen::Vector3i& t : g.triangles)
      outfit_triangles.push_back(t + Eigen::Vector3i::Constant(static_cast<int>(body_vertex_count)));
    hidden = std::move(g.hidden_base_vertices);
  }

  // Step 4: MakeHuman's rest is an A-pose (arms ~45 degrees down and forward, legs apart); crowdlab's
  // rest is a T-pose (body_shape.hpp). Re-pose by skinning (arm bones to +-X, leg bones to -Y) and
  // stand the T-posed body on the floor again (on its shoes' soles when it wears shoes).
  mesh.rest_joints_m = lm.joint;
  to_t_pose(lm.joint, mesh, lm.finger_tip, lm.toe_tip);
  stand_on_floor(mesh.rest_vertices_m, lm, vertical_range(mesh.rest_vertices_m).min_y);
  mesh.rest_joints_m = lm.joint;

  BodyShape& shape = body.shape;
  shape.params = {params.gender >= 0.5 ? Sex::kMale : Sex::kFemale, body.height_m, 1.0};
  set_rest_offsets(lm.joint, shape);
  // Capsules from the skin alone (the body group's closed surface), then the skin an outfit covers goes and
  // the outfit's sheets join.
  mesh.rest_normals = vertex_normals(mesh.rest_vertices_m, mesh.triangles);
  fit_capsules(mesh, lm, shape);
  if (outfit) {
    std::vector<bool> gone(body_vertex_count, false);
    for (int v : hidden)
      if (const int local = to_local[static_cast<size_t>(v)]; local >= 0)
        gone[static_cast<size_t>(local)] = true;
    std::erase_if(mesh.triangles, [&](const Eigen::Vector3i& t) {
      return gone[static_cast<size_t>(t[0])] || gone[static_cast<size_t>(t[1])] ||
             gone[static_cast<size_t>(t[2])];
    });
    mesh.triangles.insert(mesh.triangles.end(), outfit_triangles.begin(), outfit_triangles.end());
    tuck_under_garments(mesh);
    mesh.rest_normals = vertex_normals(mesh.rest_vertices_m, mesh.triangles);
    for (size_t i = body_vertex_count; i < mesh.rest_normals.size(); ++i)
      if (mesh.rest_normals[i].norm() < 0.5) mesh.rest_normals[i] = Vec3::UnitY();
  }
  compute_rest_contact_pairs(shape);
  validate_body_shape(shape, "MPFB2 body");
  return body;
}

}  // namespace crowdlab
