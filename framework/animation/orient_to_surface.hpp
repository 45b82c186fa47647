#pragma once
// Standing animated bodies on a surface (scenario `manifold`, seed 002): each frame's pose, animated
// on the flat plane y = 0 along the developed 2D trajectory (framework/core/surface_trajectories.hpp),
// is carried rigidly onto the agent's 3D frame on the surface.
//
// Per character and frame f, with the developed position q = (x, z), heading h and the surface frame
// (feet p, up n, forward t):
//   B2 = [Y x F2 | Y | F2],  F2 = (sin h, 0, cos h)   (the character frame on the plane: left, up, forward)
//   B3 = [n x t  | n | t ]                            (the same frame on the surface)
//   M  = B3 B2^T   (a rotation: both bases are orthonormal and right-handed)
//   root' = p + M (root - (x, 0, z)),   root_rotation' = M root_rotation
// Every joint moves with the root, so the body keeps its gait and its feet stay on the tangent plane
// at p: upright on floors, horizontal on walls, upside down on ceilings.
#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab {

/// [in,out] crowd: characters in trajectory order, frame counts equal to the trajectories'.
/// Throws InputError when counts disagree or a surface frame is not orthonormal (|n|, |t| != 1 or
/// n . t != 0 within 1e-6).
void orient_to_surface(CrowdAnimation& crowd, const CrowdTrajectories& developed,
                       const SurfaceTrajectories& surface);

}  // namespace crowdlab
