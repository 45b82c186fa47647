#pragma once
// align_two_axes: the rotation R with R * a0 = a1 (primary directions, exact) and R * b0 as close as
// possible to b1 (secondary directions, projected orthogonal to the primary). Inputs need not be
// unit; when a secondary vector is parallel to its primary, world +Y (then +Z) stands in for it.
// Used to build bone rotations from a bone direction plus a bend-plane normal (leg_ik.hpp).
#include "framework/core/math_types.hpp"

namespace crowdlab {

Quat align_two_axes(const Vec3& a0, const Vec3& b0, const Vec3& a1, const Vec3& b1);

}  // namespace crowdlab
