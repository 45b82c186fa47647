#pragma once
// The mannequin's implicit body field (mannequin_mesh.hpp) and its samples on the polygonisation grid.
//
// Field: d(p) = min( s_0(p), min_{j >= 1} smin_{k_j}( s_j(p), s_parent(j)(p) ) ), s_j the signed distance
//   to capsule j (metres), smin the polynomial smooth minimum (Quilez 2013) of width k_j (blend_for).
//
// Narrow band (why: evaluating all 24 capsules at every grid point and six more times per vertex for the
// normal was 45 % of a small `crowdlab run` in Release and 80 % under the sanitizers). The samples are the
// same floats as evaluating every capsule everywhere, by three facts:
//  - every s_j is 1-Lipschitz, so within a ball of radius rho around c, s_j lies in s_j(c) -+ rho;
//  - smin_k(a, b) lies in [min(a, b) - k/4, min(a, b)], so each term has bounds, and a term whose lower
//    bound exceeds the smallest upper bound of any term can never be the minimum: leaving it out changes
//    no minimum (a minimum of doubles is one of them, whatever else is compared);
//  - d is 1-Lipschitz too (smin's partial derivatives are >= 0 and sum to 1), so a grid point farther
//    than a cell diagonal from the level set is in no cell the surface crosses: only its sign is used
//    (surface nets read values only for signs and for the crossings of crossed cells' edges).
// Blocks of grid points entirely farther than that band outside (or inside) store a bound of the right
// sign; the others evaluate, per point, only the terms that may be the minimum in their block.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/math_types.hpp"
#include "framework/core/skeleton.hpp"

namespace crowdlab::stimuli {

/// How sample_field evaluates the field: every term at every point (the definition, kept as the
/// reference), or the narrow band above. Both give the same floats wherever a value is read.
enum class FieldSampling { kEveryPoint, kNarrowBand };

/// A regular grid of points lo + (i, j, k) * spacing_m, i < nx, j < ny, k < nz; x varies fastest.
struct FieldGrid {
  Vec3 lo = Vec3::Zero();
  double spacing_m = 0.02;
  int nx = 0, ny = 0, nz = 0;

  Vec3 point(int i, int j, int k) const {
    return Vec3(lo.x() + i * spacing_m, lo.y() + j * spacing_m, lo.z() + k * spacing_m);
  }
  size_t index(int i, int j, int k) const {
    return (static_cast<size_t>(k) * static_cast<size_t>(ny) + static_cast<size_t>(j)) *
               static_cast<size_t>(nx) +
           static_cast<size_t>(i);
  }
  size_t size() const { return static_cast<size_t>(nx) * static_cast<size_t>(ny) * static_cast<size_t>(nz); }
};

/// The terms of d that may be the minimum somewhere in a ball, and the capsules they read.
struct FieldTerms {
  std::array<std::uint8_t, kJointCount> term{};
  std::array<std::uint8_t, kJointCount> capsule{};
  int term_count = 0;
  int capsule_count = 0;
};

class MannequinField {
 public:
  /// `capsules` (world frame, metres) must outlive the field; blend_m is the smooth-min width at joints.
  MannequinField(const WorldCapsules& capsules, double blend_m) : capsules_(capsules), blend_m_(blend_m) {}

  /// s_j(p) for every capsule j.
  void distances(const Vec3& p, std::array<double, kJointCount>& s) const;
  /// d(p), every term evaluated.
  double value(const Vec3& p) const;
  /// d(p) from `terms` only: equal to value(p) when `terms` holds every term that may be the minimum at p.
  double value(const Vec3& p, const FieldTerms& terms) const;
  /// The normalised central difference of d with step h at p (unit Y where it vanishes), every term.
  Vec3 gradient(const Vec3& p, double h) const;
  /// The same vector, evaluating only the terms that may be the minimum within h of p; `s_at_p` is
  /// distances(p).
  Vec3 gradient(const Vec3& p, double h, const std::array<double, kJointCount>& s_at_p) const;

  /// The smooth-min width of the term of `bone` (wider on the trunk, see mannequin_mesh.hpp).
  double blend_for(int bone) const;

  /// Bounds of d over the ball of radius rho_m around a point whose distances are `s_centre`, and the
  /// terms that may be its minimum there.
  struct BallBounds {
    double lower = 0.0, upper = 0.0;
    FieldTerms terms;
  };
  BallBounds bounds_in_ball(const std::array<double, kJointCount>& s_centre, double rho_m) const;

 private:
  const WorldCapsules& capsules_;
  double blend_m_;
};

/// The samples d(p) + offset_m as floats at every point of `grid`. With kNarrowBand a point farther than
/// one cell diagonal from the level set d = -offset_m holds a bound of the right sign instead of the value
/// (see above); every other point holds exactly what kEveryPoint stores.
std::vector<float> sample_field(const MannequinField& field, const FieldGrid& grid, double offset_m,
                                FieldSampling sampling);

/// The band beyond which sample_field(kNarrowBand) may store a bound: one cell diagonal, widened by a
/// relative 1e-6 and 1 nm for rounding.
double narrow_band_m(double spacing_m);

}  // namespace crowdlab::stimuli
