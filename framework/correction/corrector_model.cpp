#include "framework/correction/corrector_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "framework/core/capsule_box.hpp"
#include "framework/core/capsule_box_distance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/correction/anticipate_contacts.hpp"

namespace crowdlab {

namespace {

struct JointGroup {
  std::string_view name;
  BoneMask joints;
};

/// The named groups of parse_joint_set, in the order joint_set_name writes them.
constexpr std::array<JointGroup, 7> kJointGroups = {{
    {"light", kLightJoints},
    {"elbows", kElbowJoints},
    {"head", kHeadJoints},
    {"shoulders", kShoulderJoints},
    {"spine", joint_set({kSpine1, kSpine2, kSpine3})},
    {"hips", joint_set({kLeftHip, kRightHip})},
    {"knees", joint_set({kLeftKnee, kRightKnee})},
}};

BoneMask joint_set_item(std::string_view item) {
  if (item == "none") return 0;
  for (const JointGroup& g : kJointGroups)
    if (item == g.name) return g.joints;
  if (const auto j = joint_from_name(item)) return BoneMask{1} << *j;
  throw InputError("joint set: unknown joint or group '" + std::string(item) +
                   "' (none, light, elbows, head, shoulders, spine, hips, knees or an SMPL joint name)");
}

}  // namespace

BoneMask parse_joint_set(std::string_view list) {
  BoneMask set = 0;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    set |= joint_set_item(list.substr(start, comma - start));
    start = comma + 1;
  }
  return set;
}

std::string joint_set_name(BoneMask set) {
  std::string out;
  auto add = [&out](std::string_view name) { out += (out.empty() ? "" : ",") + std::string(name); };
  for (const JointGroup& g : kJointGroups)
    if ((set & g.joints) == g.joints) {
      add(g.name);
      set &= ~g.joints;
    }
  for (int j = 0; j < kJointCount; ++j)
    if (set & (BoneMask{1} << j)) add(joint_name(j));
  return out.empty() ? "none" : out;
}

void validate_corrector_params(const CorrectorParams& p) {
  auto check = [](double v, const char* name, double lo) {
    if (!std::isfinite(v) || v < lo)
      throw InputError(std::string("corrector parameter ") + name +
                       " must be finite and >= " + std::to_string(lo) + ", got " + std::to_string(v));
  };
  check(p.stiffness, "stiffness", 0.0);
  check(p.damping, "damping", 0.0);
  check(p.stiff_joint_gain, "stiff_joint_gain", 0.0);
  check(p.root_translation_stiffness, "root_translation_stiffness", 0.0);
  check(p.foot_anchor_stiffness, "foot_anchor_stiffness", 0.0);
  check(p.swing_foot_stiffness, "swing_foot_stiffness", 0.0);
  check(p.foot_plant_speed_mps, "foot_plant_speed_mps", 0.0);
  check(p.foot_plant_height_m, "foot_plant_height_m", 0.0);
  check(p.foot_hold_tolerance_m, "foot_hold_tolerance_m", 0.0);
  check(p.foot_pop_budget_m, "foot_pop_budget_m", 0.0);
  check(p.joint_stiffness, "joint_stiffness", 0.0);
  check(p.contact_stiffness, "contact_stiffness", 0.0);
  check(p.intra_body_contact_stiffness, "intra_body_contact_stiffness", 0.0);
  check(p.contact_offset_m, "contact_offset_m", 0.0);
  check(p.ground_stiffness, "ground_stiffness", 0.0);
  check(p.environment_stiffness, "environment_stiffness", 0.0);
  check(p.environment_sample_spacing_m, "environment_sample_spacing_m", 1e-4);
  check(p.max_environment_points, "max_environment_points", 0.0);
  check(p.body_density_kg_m3, "body_density_kg_m3", 1.0);
  check(p.gravity_mps2, "gravity_mps2", 0.0);
  check(p.cg_tolerance, "cg_tolerance", 1e-14);
  check(p.max_bone_speed_mps, "max_bone_speed_mps", 1e-3);
  check(p.max_rotation_step_rad, "max_rotation_step_rad", 0.0);
  check(p.depenetration_tolerance_m, "depenetration_tolerance_m", 0.0);
  check(p.free_joint_margin_m, "free_joint_margin_m", 0.0);
  check(p.free_joint_hold_s, "free_joint_hold_s", 0.0);
  check(p.free_joint_return_radps, "free_joint_return_radps", 0.0);
  check(p.max_step_s, "max_step_s", 1e-4);
  check(p.follow_root_smoothing_s, "follow_root_smoothing_s", 0.0);
  if (p.depenetration_passes < 0) throw InputError("corrector parameter depenetration_passes must be >= 0");
  if (p.settle_steps < 0) throw InputError("corrector parameter settle_steps must be >= 0");
  if (p.active_set_passes < 0) throw InputError("corrector parameter active_set_passes must be >= 0");
  if (p.cg_max_iterations < 1) throw InputError("corrector parameter cg_max_iterations must be >= 1");
  validate_anticipation_params(p);
}

void capsule_mass_properties(const Capsule& capsule, double density, double& mass, Mat3& inertia) {
  const double r = capsule.radius_m, len = capsule.length_m();
  const double m_cyl = density * std::numbers::pi * r * r * len;
  const double m_caps = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;  // both hemispheres
  mass = m_cyl + m_caps;
  const double axial = m_cyl * r * r / 2.0 + m_caps * 2.0 * r * r / 5.0;
  const double perp = m_cyl * (r * r / 4.0 + len * len / 12.0) +
                      m_caps * (2.0 * r * r / 5.0 + len * len / 4.0 + 3.0 * len * r / 8.0);
  // Inertia in a frame whose z axis is the capsule axis, rotated into the capsule's frame.
  const Vec3 axis = len > 1e-12 ? Vec3((capsule.b - capsule.a) / len) : Vec3::UnitY();
  inertia = perp * Mat3::Identity() + (axial - perp) * axis * axis.transpose();
}

namespace {

/// Number of joints between bones i and j along the tree (1 = parent/child, 2 = e.g. spine3/shoulder).
int tree_distance(int i, int j) {
  int di = 0;
  for (int a = i; a >= 0; a = kJointParent[static_cast<size_t>(a)], ++di) {
    int dj = 0;
    for (int b = j; b >= 0; b = kJointParent[static_cast<size_t>(b)], ++dj)
      if (a == b) return di + dj;
  }
  return 1000;
}

/// Fraction of the summed capsule volume that the capsule union occupies (overlaps counted once),
/// by sampling a 2.5 cm grid over the body in its rest pose (cell volume error averages out over the
/// ~5000 cells of an adult body; only capsules whose box holds the cell centre are tested).
double union_fraction(const BodyShape& shape) {
  const WorldCapsules caps = world_capsules(shape, Pose::rest(shape));
  const Aabb body = capsules_box(caps);
  const Vec3 &lo = body.lo, &hi = body.hi;
  constexpr double kStep = 0.025;
  std::array<Aabb, kJointCount> boxes;
  for (size_t i = 0; i < kJointCount; ++i) boxes[i] = capsule_box(caps[i]);
  long inside_any = 0, inside_sum = 0;
  for (double x = lo.x() + kStep / 2; x < hi.x(); x += kStep)
    for (double y = lo.y() + kStep / 2; y < hi.y(); y += kStep)
      for (double z = lo.z() + kStep / 2; z < hi.z(); z += kStep) {
        const Vec3 p(x, y, z);
        int count = 0;
        for (size_t i = 0; i < kJointCount; ++i) {
          if (!boxes[i].contains(p)) continue;
          const Capsule& c = caps[i];
          if (segment_closest_points(c.a, c.b, p, p).distance_m < c.radius_m) ++count;
        }
        inside_any += count > 0 ? 1 : 0;
        inside_sum += count;
      }
  return inside_sum > 0 ? static_cast<double>(inside_any) / static_cast<double>(inside_sum) : 1.0;
}

bool is_ancestor_or_self(int ancestor, int bone) {
  for (int b = bone; b >= 0; b = kJointParent[static_cast<size_t>(b)])
    if (b == ancestor) return true;
  return false;
}

CorrectorBody make_body(BodyShape shape, const CorrectorParams& p) {
  CorrectorBody body;
  const BoneTransforms rest = forward_kinematics(shape, Pose::rest(shape));
  std::array<Vec3, kJointCount> com_world{};
  std::array<Mat3, kJointCount> inertia_world{};
  // Capsules overlap at the joints; scaling the density by the union fraction makes the total mass
  // density x union volume, so overlapping regions are not counted twice.
  const double density = p.body_density_kg_m3 * union_fraction(shape);
  for (size_t j = 0; j < kJointCount; ++j) {
    const Capsule& cap = shape.capsules[j];
    capsule_mass_properties(cap, density, body.mass_kg[j], body.inertia_local[j]);
    body.com_local_m[j] = 0.5 * (cap.a + cap.b);
    body.total_mass_kg += body.mass_kg[j];
    com_world[j] = rest[j].apply(body.com_local_m[j]);
    const Mat3 r = rest[j].rotation.toRotationMatrix();
    inertia_world[j] = r * body.inertia_local[j] * r.transpose();
  }
  // Effective inertia of joint j: composite inertia of its subtree about the joint, rest pose
  // (mean principal moment, trace / 3). For the root this is the whole body about the pelvis joint.
  for (int j = 0; j < kJointCount; ++j) {
    Mat3 composite = Mat3::Zero();
    const Vec3 joint = rest[static_cast<size_t>(j)].translation;
    for (int b = 0; b < kJointCount; ++b) {
      if (!is_ancestor_or_self(j, b)) continue;
      const Vec3 d = com_world[static_cast<size_t>(b)] - joint;
      composite +=
          inertia_world[static_cast<size_t>(b)] +
          body.mass_kg[static_cast<size_t>(b)] * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    }
    const double i_eff = composite.trace() / 3.0;
    const double gain = is_stiff_joint(j) ? p.stiff_joint_gain : 1.0;
    body.rot_stiffness[static_cast<size_t>(j)] = gain * p.stiffness * i_eff;
    // Stiffness-proportional (Rayleigh) damping: d multiplies the joint's own spring (see params).
    body.rot_damping[static_cast<size_t>(j)] = p.damping * body.rot_stiffness[static_cast<size_t>(j)];
    body.joint_stiffness[static_cast<size_t>(j)] = p.joint_stiffness * body.mass_kg[static_cast<size_t>(j)];
  }
  const double root_gain = p.stiff_joint_gain;
  body.root_translation_stiffness = root_gain * p.root_translation_stiffness * body.total_mass_kg;
  body.root_translation_damping = p.damping * body.root_translation_stiffness;
  body.foot_anchor_stiffness = root_gain * p.foot_anchor_stiffness * body.total_mass_kg;
  body.swing_foot_stiffness = root_gain * p.swing_foot_stiffness * body.total_mass_kg;
  // The feet anchors get the root's damper, not d x their own (10x stiffer) spring: Rayleigh damping
  // makes every deviation decay with time constant >= d/h (0.18 s at 30 fps), too slow for a walking
  // foot that plants ~0.1 s after its swing (the corrected foot then slid into place, measured as skate).
  body.foot_anchor_damping = body.root_translation_damping;
  for (int i = 0; i < kJointCount; ++i)
    for (int j = i + 1; j < kJointCount; ++j) {
      const bool excluded = std::find(shape.rest_contact_pairs.begin(), shape.rest_contact_pairs.end(),
                                      std::pair<int, int>(i, j)) != shape.rest_contact_pairs.end() ||
                            tree_distance(i, j) <= 2;
      if (!excluded) body.self_pairs.emplace_back(static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(j));
    }
  body.shape = std::move(shape);
  return body;
}

}  // namespace

int substeps_per_frame(double fps, double max_step_s) {
  // A frame time within 1 % of max_step_s takes one step (29.97 fps at 1/30 s).
  constexpr double kSlack = 1.01;
  const double ratio = 1.0 / (fps * max_step_s);
  return ratio <= kSlack ? 1 : static_cast<int>(std::ceil(ratio / kSlack));
}

CorrectorModel make_corrector_model(std::vector<BodyShape> shapes, const CorrectorParams& params,
                                    const Environment& env, double fps) {
  validate_corrector_params(params);
  if (!(fps > 0.0) || !std::isfinite(fps))
    throw InputError("corrector fps must be > 0, got " + std::to_string(fps));
  if (shapes.empty()) throw InputError("corrector: the crowd has no characters");
  CorrectorModel model;
  model.params = params;
  model.fps = fps;
  model.substeps = substeps_per_frame(fps, params.max_step_s);
  model.h = 1.0 / (fps * model.substeps);
  model.ground_plane = env.ground_plane;
  model.bodies.reserve(shapes.size());
  for (size_t c = 0; c < shapes.size(); ++c) {
    validate_body_shape(shapes[c], "corrector: character " + std::to_string(c));
    model.bodies.push_back(make_body(std::move(shapes[c]), params));
  }
  // Boxes (walls, barriers, the stage) are contacted exactly (capsule_box_distance, issue 27); only
  // triangle meshes are point-sampled as seed 000 §3.4 does.
  Environment meshes = env;
  meshes.boxes.clear();
  model.environment =
      EnvironmentPointTree(meshes, params.environment_sample_spacing_m, params.max_environment_points);
  model.environment_boxes = env.boxes;
  for (const Box& b : env.boxes) model.environment_box_bounds.push_back(box_bounds(b));
  return model;
}

}  // namespace crowdlab
