#pragma once
// Placement of EXACTLY `count` characters in a polygon with the largest minimum spacing we can reach
// (seed 000 §4.1: "the original position of the N characters ... is computed according to a desired
// density using a Poisson Disk Sampling algorithm, to ensure regular spacing between characters").
//
// Plain Poisson-disk dart throwing (Cook 1986; Bridson 2007) fixes the radius and lets the count
// vary; the studies need the count fixed by the density. So:
//   1. dart throwing with a shrinking radius: start at the hexagonal-packing spacing
//      d_hex = sqrt(2 A / (sqrt(3) N)) (the densest packing of N points in area A, Fejes Toth),
//      accept uniform samples at least r from every accepted point, and shrink r by 3 % after 100
//      consecutive rejections, until N points are accepted (random sequential adsorption saturates
//      near 0.55 packing fraction, i.e. r ~ 0.78 d_hex);
//   2. relaxation: Jacobi soft-disc repulsion toward spacing 1.1 d_hex (pairs closer than that are
//      pushed apart by half the deficit each, under-relaxed by 0.5), points projected back into the
//      area; the configuration with the largest minimum spacing seen is kept. This typically lifts
//      the minimum spacing to 0.85-0.95 d_hex.
// Points may lie on the boundary unless boundary_margin_m > 0 (then they keep that distance inside).
// Deterministic for a given seed (std::mt19937_64 with crowdlab's portable uniform01).
//
// Errors (InputError): count < 1, an invalid or empty polygon, a negative spacing or margin, and a
// count that cannot fit at the required minimum spacing: first by Oler's bound for convex areas
// (Oler 1961: N <= 2A/(sqrt(3) s^2) + P/(2 s) + 1 points with mutual distance >= s fit in a convex
// set of area A and perimeter P), then if the best configuration found is still closer than required.
#include <cstdint>
#include <vector>

#include "framework/crowd/polygon.hpp"

namespace crowdlab {

struct PlacementOptions {
  double min_spacing_m = 0.0;  ///< required minimum centre distance (0 = no requirement)
  /// > 0 and below d_hex: plain Poisson-disk sampling, dart throwing starting at this radius and no
  /// relaxation, so spacings vary from it up as in a real crowd rather than sitting near d_hex. Where
  /// the dart throwing cannot place everyone at it (it jams near 0.78 d_hex: 40 or 50 people on 9 m^2
  /// at 0.45 m), it shrinks as in step 1 and only the pairs closer than this radius are then relaxed
  /// apart (target this radius): without that, 50 people stood closer (nearest neighbours 0.32-0.38 m)
  /// than 60 placed evenly (issue 28, session 24). Otherwise ignored.
  double personal_space_m = 0.0;
  double boundary_margin_m = 0.0;  ///< keep points this far inside the boundary
  int relaxation_iterations = 300;
};

struct Placement {
  std::vector<Vec2> positions;  ///< (count) metres
  double min_spacing_m = 0.0;   ///< achieved smallest centre distance (+inf for one point)
  double area_m2 = 0.0;
  double density_per_m2 = 0.0;  ///< count / area
};

Placement place_poisson_disk(const Polygon2& area, int count, std::uint64_t seed,
                             const PlacementOptions& options = {});

/// Smallest distance between any two points (+inf for fewer than two), via a uniform grid.
double min_pairwise_distance(const std::vector<Vec2>& points);

/// Oler's upper bound on how many points with mutual distance >= s fit in a convex polygon.
double oler_bound(double area_m2, double perimeter_m, double spacing_m);

}  // namespace crowdlab
