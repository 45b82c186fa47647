#pragma once
// Developing a surface walk into the plane: the 2D CrowdTrajectories that the gait is computed from
// for a crowd on a surface (see framework/core/surface_trajectories.hpp).
//
// Per agent, frame 0 starts at the origin heading 0 (+Z). Heading changes by the signed angle by which
// the facing direction turns about the body's up axis between frames,
//   dh_f = atan2(up_f . (fwd_{f-1}' x fwd_f), fwd_{f-1}' . fwd_f),  fwd_{f-1}' = fwd_{f-1} projected
//   onto the plane orthogonal to up_f (a discrete parallel transport, so crossing a crease or a fold
//   is not a turn),
// with the sign of the 2D convention (positive turns +Z toward +X, i.e. about +Y = up). Position
// advances by the 3D step length |feet_{f} - feet_{f-1}| along the mean of the two headings. Step
// lengths and turning rates, hence speeds and curvature, are those of the surface walk.
#include "framework/core/surface_trajectories.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab {

/// radius_m and group are copied into every agent. Throws InputError on ragged or non-finite input.
CrowdTrajectories develop_surface_trajectories(const SurfaceTrajectories& surface, double fps,
                                               double radius_m);

}  // namespace crowdlab
