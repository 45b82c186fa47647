#pragma once
// CorrectorModel: the immutable half of the collision-correction solver (MuJoCo-style mjModel),
// built once from the characters' body shapes and the parameters; CorrectorState holds what changes.
//
// Formulation (seed 000 §3.2): maximal coordinates, the paper's choice. Every bone of every character
// is a rigid body with 6 DoF (centre-of-mass position + orientation); joints are stiff soft
// constraints. Bone b of character c has global index g = c * 24 + b (kJointCount = 24).
// Mass and inertia come from the bone's capsule at body density (capsule of bone j, in bone frame).
#include <array>
#include <utility>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"
#include "framework/correction/environment_point_tree.hpp"

namespace crowdlab {

using Vec4 = Eigen::Vector4d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Per-bone constants of one character, arrays of 24 indexed by bone (= joint) index.
struct CorrectorBody {
  BodyShape shape;
  std::array<double, kJointCount> mass_kg{};          ///< capsule volume x density x union fraction (kg)
  std::array<Mat3, kJointCount> inertia_local{};      ///< inertia about the COM, bone frame (kg m^2)
  std::array<Vec3, kJointCount> com_local_m{};        ///< COM in bone frame (m) = capsule midpoint
  std::array<double, kJointCount> rot_stiffness{};    ///< k of Eq. 4 for joint j (J), scaled per header
  std::array<double, kJointCount> rot_damping{};      ///< d of Eq. 4 for joint j (J s^2) = d x rot_stiffness
  std::array<double, kJointCount> joint_stiffness{};  ///< soft joint spring child j <-> parent (N/m)
  double root_translation_stiffness = 0.0;            ///< N/m
  double root_translation_damping = 0.0;              ///< N s^2/m (d of Eq. 4 on the root position)
  double foot_anchor_stiffness = 0.0;                 ///< N/m, planted ankle and ball joints to anchors
  double swing_foot_stiffness = 0.0;                  ///< N/m, swinging ankle and ball joints to targets
  double foot_anchor_damping = 0.0;                   ///< N s^2/m
  double total_mass_kg = 0.0;
  /// Capsule pairs tested for self-collision: all i < j not in shape.rest_contact_pairs (seed 000
  /// §3.4) and more than two joints apart along the tree. The second rule is ours: around the shoulder
  /// and hip girdles, capsules two joints apart (spine3/upper arm, pelvis/thigh...) overlap in ordinary
  /// poses such as hanging arms, where the real body is continuous, not self-colliding.
  std::vector<std::pair<std::uint8_t, std::uint8_t>> self_pairs;
};

struct CorrectorModel {
  CorrectorParams params;
  double fps = 30.0;                   ///< frames per second of the targets
  int substeps = 1;                    ///< steps per frame (substeps_per_frame)
  double h = 1.0 / 30.0;               ///< time step (s) = 1 / (fps x substeps)
  std::vector<CorrectorBody> bodies;   ///< one per character
  EnvironmentPointTree environment;    ///< sample points of the environment's triangle meshes
  std::vector<Box> environment_boxes;  ///< the environment's boxes, contacted exactly (stage_narrow_phase)
  std::vector<Aabb> environment_box_bounds;  ///< their world bounds
  bool ground_plane = true;

  int characters() const { return static_cast<int>(bodies.size()); }
  int bones() const { return characters() * kJointCount; }
};

/// Steps per frame at `fps` so that no step is longer than max_step_s (CorrectorParams::max_step_s):
/// 1 up to a frame time 1 % longer than max_step_s, else ceil(frame time / (1.01 max_step_s)).
int substeps_per_frame(double fps, double max_step_s);

/// Builds the model. Throws InputError for an empty crowd, an invalid shape (validate_body_shape),
/// invalid params or fps <= 0.
CorrectorModel make_corrector_model(std::vector<BodyShape> shapes, const CorrectorParams& params,
                                    const Environment& env, double fps);

/// Mass (kg) and inertia about the COM (kg m^2, in the capsule's frame) of a solid capsule of
/// uniform density: a cylinder plus two hemispherical caps (standard result, e.g. the derivation in
/// Eberly, "Game Physics", 2nd ed., §2.5, with the parallel-axis shift of each cap's centroid 3r/8).
void capsule_mass_properties(const Capsule& capsule, double density, double& mass, Mat3& inertia);

}  // namespace crowdlab
