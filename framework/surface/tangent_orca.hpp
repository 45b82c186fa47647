#pragma once
// ORCA (van den Berg, Guy, Lin, Manocha 2011, "Reciprocal n-Body Collision Avoidance") applied in one
// agent's tangent plane, fed by seed 002's Offset tuples: the surface analogue of the 2D crowd model
// (framework/crowd/orca_model.hpp), reusing its half-plane linear programs (orca_linear_program.hpp).
//
// Frame: a right-handed orthonormal tangent basis (e1, e2) of agent a with e1 x e2 = up_a. Every
// quantity below is 2D in that basis (m, m/s).
// One Offset tuple (direction u in the tangent plane, clearance c) of obstacle sphere k becomes a
// disc obstacle at relative position p = u * (c + 2r) (seed 002: "angle found by projecting
// v_obstacle onto the plane tangent to a", distance its Euclidean length) with combined radius 2r.
// The obstacle's velocity is its 3D velocity projected onto a's tangent plane. The half-plane is the
// paper's Sec. 4 construction with reciprocity 1/2:
//   w = v - p / tau (v = v_a - v_o). Outside the cut-off disc and inside the cone: project onto a leg;
//   otherwise onto the cut-off circle (radius R / tau). Already overlapping (|p| < R): the horizon is
//   the step dt. Half-plane {v' : (v' - (v_a + u / 2)) . n >= 0} with u the smallest change leaving
//   the velocity obstacle and n its outward normal.
#include "framework/core/math_types.hpp"
#include "framework/crowd/orca_linear_program.hpp"

namespace crowdlab {

/// A right-handed orthonormal basis (e1, e2) of the plane orthogonal to the unit vector `up`
/// (e1 x e2 = up). Deterministic function of `up` only.
void tangent_basis(const Vec3& up, Vec3& e1, Vec3& e2);

/// ORCA half-plane for one disc obstacle (see header). rel_pos = p_o - p_a, rel_vel = v_a - v_o,
/// velocity = v_a, combined_radius_m > 0, horizon_s > 0, dt_s > 0.
orca::Line orca_half_plane(const Vec2& rel_pos, const Vec2& rel_vel, const Vec2& velocity,
                           double combined_radius_m, double horizon_s, double dt_s);

/// Solves ORCA over lines[0..n) (all soft: agents only) for the velocity closest to `preferred` with
/// |v| <= max_speed (lp2, with lp3 when infeasible, as in the 2D model). `scratch` holds n lines.
Vec2 solve_orca(const orca::Line* lines, std::size_t n, const Vec2& preferred, double max_speed_mps,
                orca::Line* scratch);

}  // namespace crowdlab
