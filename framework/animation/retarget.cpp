#include "framework/animation/retarget.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

using anim::shortest_arc;

std::string_view to_string(SkeletonConvention c) {
  switch (c) {
    case SkeletonConvention::kMixamo:
      return "mixamo";
    case SkeletonConvention::kCmu:
      return "cmu";
    case SkeletonConvention::kBandaiNamco:
      return "bandai-namco";
    case SkeletonConvention::kSmpl:
      return "smpl";
  }
  return "?";
}

namespace {

// Lower-case, without any "namespace:" prefix (mixamorig:Hips -> hips) or "mixamorig_" prefix.
std::string normalize(const std::string& name) {
  std::string s = name.substr(name.find(':') == std::string::npos ? 0 : name.find(':') + 1);
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (s.rfind("mixamorig_", 0) == 0) s = s.substr(10);
  return s;
}

using NameTable = std::array<std::vector<std::string>, kJointCount>;

// Candidate source names per SMPL joint (normalised), per convention. "{s}" is left/right handled by
// listing both sides explicitly.
NameTable table(SkeletonConvention c) {
  NameTable t;
  auto both = [&](int left, int right, std::vector<std::string> l, std::vector<std::string> r) {
    t[static_cast<size_t>(left)] = std::move(l);
    t[static_cast<size_t>(right)] = std::move(r);
  };
  switch (c) {
    case SkeletonConvention::kMixamo:
    case SkeletonConvention::kCmu: {
      const bool cmu = c == SkeletonConvention::kCmu;
      t[kPelvis] = {"hips"};
      t[kSpine1] = cmu ? std::vector<std::string>{"lowerback"} : std::vector<std::string>{"spine"};
      t[kSpine2] = cmu ? std::vector<std::string>{"spine"} : std::vector<std::string>{"spine1"};
      t[kSpine3] = cmu ? std::vector<std::string>{"spine1"} : std::vector<std::string>{"spine2"};
      t[kNeck] = {"neck"};
      t[kHead] = {"head"};
      both(kLeftHip, kRightHip, {"leftupleg"}, {"rightupleg"});
      both(kLeftKnee, kRightKnee, {"leftleg"}, {"rightleg"});
      both(kLeftAnkle, kRightAnkle, {"leftfoot"}, {"rightfoot"});
      both(kLeftFoot, kRightFoot, {"lefttoebase"}, {"righttoebase"});
      both(kLeftCollar, kRightCollar, {"leftshoulder"}, {"rightshoulder"});
      both(kLeftShoulder, kRightShoulder, {"leftarm"}, {"rightarm"});
      both(kLeftElbow, kRightElbow, {"leftforearm"}, {"rightforearm"});
      both(kLeftWrist, kRightWrist, {"lefthand"}, {"righthand"});
      both(kLeftHand, kRightHand,
           cmu ? std::vector<std::string>{"leftfingerbase"} : std::vector<std::string>{"lefthandmiddle1"},
           cmu ? std::vector<std::string>{"rightfingerbase"} : std::vector<std::string>{"righthandmiddle1"});
      break;
    }
    case SkeletonConvention::kBandaiNamco:
      t[kPelvis] = {"hips"};
      t[kSpine1] = {"spine"};
      t[kSpine3] = {"chest"};
      t[kNeck] = {"neck"};
      t[kHead] = {"head"};
      both(kLeftHip, kRightHip, {"upperleg_l"}, {"upperleg_r"});
      both(kLeftKnee, kRightKnee, {"lowerleg_l"}, {"lowerleg_r"});
      both(kLeftAnkle, kRightAnkle, {"foot_l"}, {"foot_r"});
      both(kLeftFoot, kRightFoot, {"toes_l"}, {"toes_r"});
      both(kLeftCollar, kRightCollar, {"shoulder_l"}, {"shoulder_r"});
      both(kLeftShoulder, kRightShoulder, {"upperarm_l"}, {"upperarm_r"});
      both(kLeftElbow, kRightElbow, {"lowerarm_l"}, {"lowerarm_r"});
      both(kLeftWrist, kRightWrist, {"hand_l"}, {"hand_r"});
      break;
    case SkeletonConvention::kSmpl:
      for (int j = 0; j < kJointCount; ++j) {
        std::string n(joint_name(j));
        std::string short_form = n;  // left_hip -> l_hip
        if (n.rfind("left_", 0) == 0) short_form = "l_" + n.substr(5);
        if (n.rfind("right_", 0) == 0) short_form = "r_" + n.substr(6);
        t[static_cast<size_t>(j)] = {n, short_form};
      }
      break;
  }
  return t;
}

// Next joints down the chain used for the primary bone direction (first mapped one wins).
std::vector<int> chain_after(int j) {
  switch (j) {
    case kPelvis:
      return {kSpine1, kSpine2, kSpine3, kNeck};
    case kSpine1:
      return {kSpine2, kSpine3, kNeck};
    case kSpine2:
      return {kSpine3, kNeck};
    case kSpine3:
      return {kNeck, kHead};
    case kNeck:
      return {kHead};
    case kLeftHip:
      return {kLeftKnee, kLeftAnkle};
    case kRightHip:
      return {kRightKnee, kRightAnkle};
    case kLeftKnee:
      return {kLeftAnkle};
    case kRightKnee:
      return {kRightAnkle};
    case kLeftAnkle:
      return {kLeftFoot};
    case kRightAnkle:
      return {kRightFoot};
    case kLeftCollar:
      return {kLeftShoulder, kLeftElbow};
    case kRightCollar:
      return {kRightShoulder, kRightElbow};
    case kLeftShoulder:
      return {kLeftElbow, kLeftWrist};
    case kRightShoulder:
      return {kRightElbow, kRightWrist};
    case kLeftElbow:
      return {kLeftWrist};
    case kRightElbow:
      return {kRightWrist};
    case kLeftWrist:
      return {kLeftHand};
    case kRightWrist:
      return {kRightHand};
    default:
      return {};
  }
}

double leg_chain_length(const std::vector<Vec3>& p, int hip, int knee, int ankle) {
  return (p[static_cast<size_t>(knee)] - p[static_cast<size_t>(hip)]).norm() +
         (p[static_cast<size_t>(ankle)] - p[static_cast<size_t>(knee)]).norm();
}

// Source feet rest at their own angle (ankle height over toe height differs between skeletons):
// measure each foot's pitch (ankle -> ball against the horizontal) over its 20 % lowest frames, i.e.
// while it stands, and turn the foot about its lateral axis by the difference to the target's rest
// pitch, so that stance feet are flat on the target body. The toes keep their world orientation.
void flatten_feet(std::vector<Pose>& frames, const BodyShape& target,
                  const std::array<Vec3, kJointCount>& tpose) {
  for (auto [ankle, ball, knee] : {std::array<int, 3>{kLeftAnkle, kLeftFoot, kLeftKnee},
                                   std::array<int, 3>{kRightAnkle, kRightFoot, kRightKnee}}) {
    const Vec3 rest_dir = tpose[static_cast<size_t>(ball)] - tpose[static_cast<size_t>(ankle)];
    const double rest_pitch = std::atan2(-rest_dir.y(), std::hypot(rest_dir.x(), rest_dir.z()));
    std::vector<std::pair<double, double>> height_pitch;
    for (const Pose& p : frames) {
      const auto jp = joint_positions(target, p);
      const Vec3 d = jp[static_cast<size_t>(ball)] - jp[static_cast<size_t>(ankle)];
      height_pitch.emplace_back(jp[static_cast<size_t>(ankle)].y(),
                                std::atan2(-d.y(), std::hypot(d.x(), d.z())));
    }
    std::sort(height_pitch.begin(), height_pitch.end());
    const size_t count = std::max<size_t>(1, height_pitch.size() / 5);
    std::vector<double> pitches;
    for (size_t i = 0; i < count; ++i) pitches.push_back(height_pitch[i].second);
    std::nth_element(pitches.begin(), pitches.begin() + static_cast<std::ptrdiff_t>(count / 2),
                     pitches.end());
    const double delta = pitches[count / 2] - rest_pitch;  // > 0: source foot points further down
    for (Pose& p : frames) {
      const BoneTransforms bones = forward_kinematics(target, p);
      const Quat w_ankle = bones[static_cast<size_t>(ankle)].rotation;
      const Vec3 d = w_ankle * target.joint_offsets_m[static_cast<size_t>(ball)];
      Vec3 axis = d.cross(Vec3::UnitY());
      if (axis.norm() < 1e-9) continue;
      const Quat corrected = (Quat(Eigen::AngleAxisd(delta, axis.normalized())) * w_ankle).normalized();
      const Quat w_shank = bones[static_cast<size_t>(knee)].rotation;
      p.local_rotations[static_cast<size_t>(ankle)] = (w_shank.conjugate() * corrected).normalized();
      p.local_rotations[static_cast<size_t>(ball)] =
          (corrected.conjugate() * bones[static_cast<size_t>(ball)].rotation).normalized();
    }
  }
}

}  // namespace

JointMap map_joint_names(const BvhMotion& motion) {
  std::vector<std::string> names;
  for (const BvhJoint& j : motion.joints) names.push_back(normalize(j.name));
  JointMap best;
  int best_count = -1;
  for (SkeletonConvention c : {SkeletonConvention::kMixamo, SkeletonConvention::kCmu,
                               SkeletonConvention::kBandaiNamco, SkeletonConvention::kSmpl}) {
    const NameTable t = table(c);
    JointMap m;
    m.convention = c;
    m.source.fill(-1);
    int count = 0;
    for (int j = 0; j < kJointCount; ++j)
      for (const std::string& cand : t[static_cast<size_t>(j)]) {
        const auto it = std::find(names.begin(), names.end(), cand);
        if (it != names.end()) {
          m.source[static_cast<size_t>(j)] = static_cast<int>(it - names.begin());
          ++count;
          break;
        }
      }
    // CMU and Mixamo share most names; "lowerback" decides.
    if (c == SkeletonConvention::kCmu && std::find(names.begin(), names.end(), "lowerback") == names.end())
      count -= 2;
    if (count > best_count) best = m, best_count = count;
  }
  for (int j : {kPelvis, kLeftHip, kRightHip, kLeftKnee, kRightKnee, kLeftAnkle, kRightAnkle})
    if (best.source[static_cast<size_t>(j)] < 0)
      throw InputError(SourceLocation{motion.source, 0, 0, ""},
                       "cannot retarget: no source joint for SMPL '" + std::string(joint_name(j)) +
                           "' (skeleton looks like " + std::string(to_string(best.convention)) +
                           "; supported names: Mixamo, CMU, Bandai-Namco, SMPL)");
  return best;
}

RetargetedClip retarget_bvh(const BvhMotion& motion, const BodyShape& target,
                            const RetargetOptions& options) {
  if (motion.frame_count < 1)
    throw InputError(SourceLocation{motion.source, 0, 0, ""}, "BVH has no frames to retarget");
  RetargetedClip out;
  out.fps = motion.fps();
  out.map = map_joint_names(motion);
  const auto& src = out.map.source;
  auto S = [&](int j) { return static_cast<size_t>(src[static_cast<size_t>(j)]); };
  auto mapped = [&](int j) { return src[static_cast<size_t>(j)] >= 0; };

  // Axis convention: Y-up, or Z-up converted by a -90 deg turn about X.
  Quat axes = Quat::Identity();
  {
    const std::vector<RigidTransform> w0 = motion.world_transforms(0);
    const int top = mapped(kHead) ? kHead : (mapped(kNeck) ? kNeck : kSpine1);
    if (mapped(top)) {
      const Vec3 up = w0[S(top)].translation - w0[S(kPelvis)].translation;
      if (std::abs(up.z()) > std::abs(up.y()) && std::abs(up.z()) > std::abs(up.x()) && up.z() > 0)
        axes = Quat(Eigen::AngleAxisd(-anim::kPi / 2, Vec3::UnitX()));
      else if (!(up.y() > 0))
        throw InputError(
            SourceLocation{motion.source, 0, 0, ""},
            "cannot retarget: the first frame's head is not above the hips (unsupported up axis)");
    }
  }

  const std::vector<Vec3> zero = motion.zero_pose_positions();
  const std::array<Vec3, kJointCount> tpose = joint_positions(target, Pose::rest(target));

  // Rest-offset rotations A_j (source zero pose -> target T-pose, in our world axes).
  std::array<Quat, kJointCount> align;
  align.fill(Quat::Identity());
  for (int j = 0; j < kJointCount; ++j) {
    const int parent = kJointParent[static_cast<size_t>(j)];
    align[static_cast<size_t>(j)] = parent >= 0 ? align[static_cast<size_t>(parent)] : Quat::Identity();
    if (!mapped(j)) continue;
    int child = -1;
    for (int c : chain_after(j))
      if (mapped(c) && (zero[S(c)] - zero[S(j)]).norm() > 1e-6) {
        child = c;
        break;
      }
    if (child < 0) continue;
    const Vec3 a0 = axes * (zero[S(child)] - zero[S(j)]);
    const Vec3 a1 = tpose[static_cast<size_t>(child)] - tpose[static_cast<size_t>(j)];
    int l = -1, r = -1;
    if (j == kPelvis) l = kLeftHip, r = kRightHip;
    if (j == kSpine3)
      l = mapped(kLeftCollar) ? kLeftCollar : kLeftShoulder,
      r = mapped(kRightCollar) ? kRightCollar : kRightShoulder;
    if (l >= 0 && mapped(l) && mapped(r)) {
      const Vec3 b0 = axes * (zero[S(l)] - zero[S(r)]);
      const Vec3 b1 = tpose[static_cast<size_t>(l)] - tpose[static_cast<size_t>(r)];
      align[static_cast<size_t>(j)] = align_two_axes(a0, b0, a1, b1);
    } else {
      // One child: the bone's direction fixes all but its twist, which is inherited from the parent's
      // alignment (the minimal turn after it), so a head or hand keeps facing the way its chest or arm
      // faces even when the source's zero pose turns the body (the twist moves no joint, but it turns
      // a skinned head or hand).
      const Quat inherited = align[static_cast<size_t>(j)];
      align[static_cast<size_t>(j)] = (shortest_arc(inherited * a0, a1) * inherited).normalized();
    }
  }

  const double src_leg =
      0.5 * (leg_chain_length(zero, static_cast<int>(S(kLeftHip)), static_cast<int>(S(kLeftKnee)),
                              static_cast<int>(S(kLeftAnkle))) +
             leg_chain_length(zero, static_cast<int>(S(kRightHip)), static_cast<int>(S(kRightKnee)),
                              static_cast<int>(S(kRightAnkle))));
  const double tgt_leg = target.joint_offsets_m[kLeftKnee].norm() + target.joint_offsets_m[kLeftAnkle].norm();
  if (!(src_leg > 1e-9))
    throw InputError(SourceLocation{motion.source, 0, 0, ""},
                     "cannot retarget: source legs have zero length");
  out.scale = tgt_leg / src_leg;

  out.frames.resize(static_cast<size_t>(motion.frame_count));
  for (int f = 0; f < motion.frame_count; ++f) {
    const std::vector<RigidTransform> w = motion.world_transforms(f);
    std::array<Quat, kJointCount> world;
    for (int j = 0; j < kJointCount; ++j) {
      const int parent = kJointParent[static_cast<size_t>(j)];
      if (mapped(j))
        world[static_cast<size_t>(j)] =
            (axes * w[S(j)].rotation * axes.conjugate() * align[static_cast<size_t>(j)].conjugate())
                .normalized();
      else
        world[static_cast<size_t>(j)] = parent >= 0 ? world[static_cast<size_t>(parent)] : Quat::Identity();
    }
    Pose& p = out.frames[static_cast<size_t>(f)];
    p.root_position_m = axes * w[S(kPelvis)].translation * out.scale;
    p.local_rotations[0] = world[0];
    for (int j = 1; j < kJointCount; ++j)
      p.local_rotations[static_cast<size_t>(j)] =
          (world[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])].conjugate() *
           world[static_cast<size_t>(j)])
              .normalized();
  }

  if (options.flatten_feet) flatten_feet(out.frames, target, tpose);

  // Ground: per frame, the lowest contact point's height above its rest height (ankle or ball, either
  // foot); its 10th percentile is moved to 0.
  std::vector<double> lows;
  for (const Pose& p : out.frames) {
    const auto jp = joint_positions(target, p);
    double low = 1e9;
    for (int j : {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot})
      low = std::min(low, jp[static_cast<size_t>(j)].y() - tpose[static_cast<size_t>(j)].y());
    lows.push_back(low);
  }
  std::nth_element(lows.begin(), lows.begin() + static_cast<std::ptrdiff_t>(lows.size() / 10), lows.end());
  const double shift = -lows[lows.size() / 10];
  for (Pose& p : out.frames) p.root_position_m.y() += shift;
  return out;
}

void normalize_clip_start(std::vector<Pose>& frames) {
  if (frames.empty()) return;
  const double h0 = frames.front().heading_rad();
  const Vec3 origin(frames.front().root_position_m.x(), 0, frames.front().root_position_m.z());
  const Quat turn = anim::yaw(-h0);
  for (Pose& p : frames) {
    p.root_position_m = turn * (p.root_position_m - origin);
    p.local_rotations[0] = (turn * p.local_rotations[0]).normalized();
  }
}

}  // namespace crowdlab
