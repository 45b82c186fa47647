#pragma once
// An MPFB2 body as a crowdlab character: M(beta, theta) of seed 000 Eq. 1 with MakeHuman's macro
// targets for beta, the Mixamo rig placed on the shaped mesh (so the skeleton follows the shape, as
// SMPL's joint regressor J(beta) does), mapped onto the 24 SMPL joints, with one capsule per bone
// (seed 000 §3.4) and linear-blend skinning weights for the renderer.
//
// Units: the OBJ is Y-up decimetres (x 0.1 -> metres); rig default_positions are Blender Z-up metres
// (see blender_to_y_up). The result is translated so the lowest body vertex is at y = 0 and the
// pelvis is above the origin; the mesh faces +Z with +X the character's left, crowdlab's convention.
//
// Mixamo -> SMPL joints (joint = the bone's head, i.e. where it rotates):
//   pelvis Hips | left/right_hip Left/RightUpLeg | spine1 Spine | spine2 Spine1 | spine3 Spine2
//   left/right_knee Left/RightLeg | left/right_ankle Left/RightFoot | left/right_foot Left/RightToeBase
//   neck Neck | head Head | left/right_collar Left/RightShoulder | left/right_shoulder Left/RightArm
//   left/right_elbow Left/RightForeArm | left/right_wrist Left/RightHand
//   left/right_hand Left/RightHandMiddle1 (SMPL's hand joint sits at the knuckles)
// Skinning weights: each Mixamo bone's weights go to the SMPL joint it maps to; all finger bones
// (Thumb/Index/Middle/Ring/Pinky 1-3) go to left/right_hand. Per vertex the 4 largest are kept and
// renormalised.
//
// Capsules (seed 000 §3.4): bone j's axis runs between two joints (its length comes from the
// joints): pelvis left_hip..right_hip (across the hips, as SMPL-capsule bodies do); spine1..spine2,
// spine2..spine3, spine3..neck, neck..head, head..top of head (Head tail); collar..shoulder,
// shoulder..elbow, elbow..wrist, wrist..hand, hand..middle fingertip (HandMiddle3 tail);
// hip..knee, knee..ankle, ankle..foot, foot..toe tip (ToeBase tail). The radius makes the capsule's
// volume equal the volume of the body part the bone carries, by the divergence theorem with the
// field radial to the bone's axis line (divergence 2: V = 1/2 ∮ F.n dA), each triangle shared among
// bones by its mean skinning weights (exact for a closed part around its own axis). Axes ending at the
// surface (top of head, fingertip, toe tip) are shortened by r so the cap ends there.
// Rest pose: MakeHuman's base mesh stands in an A-pose; crowdlab's rest is a T-pose, so the arm
// bones (shoulder, elbow, wrist, hand) are rotated to point along +-X and the hip and knee bones
// straight down, by the minimal rotations, and the mesh is skinned into that pose before anything
// else is measured.
#include <array>
#include <memory>

#include "framework/body/mpfb2_model.hpp"
#include "framework/body/mpfb2_outfit.hpp"
#include "framework/body/mpfb2_shape.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

struct Mpfb2Body {
  Mpfb2ShapeParams params;
  BodyShape shape;   ///< params.sex from gender (>= 0.5 male), params.height_m measured, girth 1
  SkinnedMesh mesh;  ///< the `body` group only
  /// Stature: lowest to highest body vertex as MakeHuman stands (A-pose, legs ~6 degrees apart); the
  /// T-posed rest mesh (straight legs) is up to ~1 % taller.
  double height_m = 0.0;
};

/// Builds the body for the given shape, in named steps: place the landmarks on the shaped mesh, take
/// the body group's vertices and stand them on the floor, bind the skin, re-pose into the T-pose and
/// stand it on the floor again, set the skeleton's rest offsets, fit the capsules. Throws InputError on
/// bad params or broken assets.
/// With an outfit (body/mpfb2_outfit.hpp) the mesh also carries eyes, eyebrows, hair, clothes and shoes
/// (SkinnedMesh::surface labels every vertex), placed before the re-pose so they follow it; the capsules
/// are fitted to the skin alone, and the body then stands on its soles. Without one (nullptr) the mesh is
/// the bare skin with no labels (renderers then paint clothing on it by position). Either way the fingers
/// rest slightly flexed (relax_fingers in mpfb2_body.cpp).
Mpfb2Body make_mpfb2_body(const Mpfb2Model& model, const Mpfb2ShapeParams& params,
                          const Mpfb2Outfit* outfit = nullptr);

/// Whether bone `joint`'s capsule axis ends at the body's surface (head, feet, hands: the whole
/// capsule carries the part) rather than at the next joint (the cylinder carries it).
bool mpfb2_bone_ends_at_surface(int joint);

/// Volume (m^3) of the body part each bone carries, the quantity its capsule's radius matches: the
/// divergence theorem over the rest mesh with the field radial to the line through axis_point[j]
/// along the unit axis_dir[j], each triangle shared among bones by its mean skinning weights.
std::array<double, kJointCount> body_part_volumes_m3(const SkinnedMesh& mesh,
                                                     const std::array<Vec3, kJointCount>& axis_point,
                                                     const std::array<Vec3, kJointCount>& axis_dir);

/// The Mixamo bone whose head is SMPL joint j (see the table above).
const char* mixamo_bone_for_joint(int joint);

}  // namespace crowdlab
