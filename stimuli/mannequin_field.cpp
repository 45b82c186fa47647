#include "stimuli/mannequin_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace crowdlab::stimuli {
namespace {

constexpr double kTrunkBlendM = 0.10;  // smooth-min width between trunk capsules (see blend_for)
constexpr int kBlockPoints = 4;        // grid points per block edge in sample_field's narrow band

/// Signed distance from p to a capsule (negative inside).
double capsule_sdf(const Vec3& p, const Capsule& c) {
  const Vec3 ab = c.b - c.a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - c.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (c.a + t * ab)).norm() - c.radius_m;
}

/// Polynomial smooth minimum of width k (Quilez 2013): within [min(a, b) - k/4, min(a, b)].
double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

size_t parent_of(size_t j) {
  return static_cast<size_t>(kJointParent[j]);
}

/// Slack added to every bound: the bounds and the values are computed in doubles, with rounding errors
/// around 1e-16 m; a nanometre keeps a term that could tie.
constexpr double kBoundSlackM = 1e-9;

}  // namespace

double MannequinField::blend_for(int bone) const {
  // The trunk is a stack of horizontal capsules (pelvis, spine1-3); a wide blend there fills the waists
  // between them into one smooth torso instead of a ribbed one.
  switch (bone) {
    case kSpine1:
    case kSpine2:
    case kSpine3:
      return std::max(blend_m_, kTrunkBlendM);
    case kLeftCollar:
    case kRightCollar:
    case kNeck:
      return std::max(blend_m_, 0.5 * kTrunkBlendM);
    default:
      return blend_m_;
  }
}

void MannequinField::distances(const Vec3& p, std::array<double, kJointCount>& s) const {
  for (size_t j = 0; j < s.size(); ++j) s[j] = capsule_sdf(p, capsules_[j]);
}

double MannequinField::value(const Vec3& p) const {
  std::array<double, kJointCount> s;
  distances(p, s);
  double d = s[0];
  for (size_t j = 1; j < s.size(); ++j)
    d = std::min(d, smooth_min(s[j], s[parent_of(j)], blend_for(static_cast<int>(j))));
  return d;
}

double MannequinField::value(const Vec3& p, const FieldTerms& terms) const {
  std::array<double, kJointCount> s;
  for (int c = 0; c < terms.capsule_count; ++c) {
    const size_t j = terms.capsule[static_cast<size_t>(c)];
    s[j] = capsule_sdf(p, capsules_[j]);
  }
  double d = std::numeric_limits<double>::infinity();
  for (int t = 0; t < terms.term_count; ++t) {
    const size_t j = terms.term[static_cast<size_t>(t)];
    d = std::min(d, j == 0 ? s[0] : smooth_min(s[j], s[parent_of(j)], blend_for(static_cast<int>(j))));
  }
  return d;
}

MannequinField::BallBounds MannequinField::bounds_in_ball(const std::array<double, kJointCount>& s_centre,
                                                          double rho_m) const {
  const double rho = rho_m * (1.0 + 1e-12) + kBoundSlackM;
  std::array<double, kJointCount> term_lower, term_upper;
  BallBounds b;
  b.upper = std::numeric_limits<double>::infinity();
  for (size_t j = 0; j < kJointCount; ++j) {
    const double lo = j == 0 ? s_centre[0] : std::min(s_centre[j], s_centre[parent_of(j)]);
    term_lower[j] = lo - rho - (j == 0 ? 0.0 : 0.25 * blend_for(static_cast<int>(j))) - kBoundSlackM;
    term_upper[j] = lo + rho + kBoundSlackM;
    b.upper = std::min(b.upper, term_upper[j]);
  }
  b.lower = *std::min_element(term_lower.begin(), term_lower.end());
  std::array<bool, kJointCount> read{};
  for (size_t j = 0; j < kJointCount; ++j) {
    if (term_lower[j] > b.upper) continue;  // above some other term everywhere in the ball
    b.terms.term[static_cast<size_t>(b.terms.term_count++)] = static_cast<std::uint8_t>(j);
    read[j] = true;
    if (j > 0) read[parent_of(j)] = true;
  }
  for (size_t j = 0; j < kJointCount; ++j)
    if (read[j]) b.terms.capsule[static_cast<size_t>(b.terms.capsule_count++)] = static_cast<std::uint8_t>(j);
  return b;
}

Vec3 MannequinField::gradient(const Vec3& p, double h) const {
  Vec3 g;
  for (int a = 0; a < 3; ++a) {
    Vec3 e = Vec3::Zero();
    e[a] = h;
    g[a] = value(p + e) - value(p - e);
  }
  const double n = g.norm();
  return n > 0 ? Vec3(g / n) : Vec3::UnitY();
}

Vec3 MannequinField::gradient(const Vec3& p, double h, const std::array<double, kJointCount>& s_at_p) const {
  const FieldTerms terms = bounds_in_ball(s_at_p, h).terms;
  Vec3 g;
  for (int a = 0; a < 3; ++a) {
    Vec3 e = Vec3::Zero();
    e[a] = h;
    g[a] = value(p + e, terms) - value(p - e, terms);
  }
  const double n = g.norm();
  return n > 0 ? Vec3(g / n) : Vec3::UnitY();
}

double narrow_band_m(double spacing_m) {
  return std::sqrt(3.0) * spacing_m * (1.0 + 1e-6) + 1e-9;
}

namespace {

/// The points of one block of the grid: [i0, i1) x [j0, j1) x [k0, k1).
struct GridBlock {
  int i0, i1, j0, j1, k0, k1;
};

void sample_block(const MannequinField& field, const FieldGrid& grid, double offset_m, const GridBlock& b,
                  std::vector<float>& out) {
  const Vec3 lo = grid.point(b.i0, b.j0, b.k0), hi = grid.point(b.i1 - 1, b.j1 - 1, b.k1 - 1);
  const Vec3 centre = 0.5 * (lo + hi);
  std::array<double, kJointCount> s;
  field.distances(centre, s);
  const MannequinField::BallBounds bounds = field.bounds_in_ball(s, 0.5 * (hi - lo).norm());
  const double band = narrow_band_m(grid.spacing_m);
  // Wholly outside (or inside) the band: only the sign is ever read.
  const bool outside = bounds.lower + offset_m > band, inside = bounds.upper + offset_m < -band;
  const float bound = static_cast<float>(outside ? bounds.lower + offset_m : bounds.upper + offset_m);
  for (int k = b.k0; k < b.k1; ++k)
    for (int j = b.j0; j < b.j1; ++j)
      for (int i = b.i0; i < b.i1; ++i)
        out[grid.index(i, j, k)] =
            outside || inside ? bound
                              : static_cast<float>(field.value(grid.point(i, j, k), bounds.terms) + offset_m);
}

}  // namespace

std::vector<float> sample_field(const MannequinField& field, const FieldGrid& grid, double offset_m,
                                FieldSampling sampling) {
  std::vector<float> out(grid.size());
  if (sampling == FieldSampling::kEveryPoint) {
    for (int k = 0; k < grid.nz; ++k)
      for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i)
          out[grid.index(i, j, k)] = static_cast<float>(field.value(grid.point(i, j, k)) + offset_m);
    return out;
  }
  for (int k0 = 0; k0 < grid.nz; k0 += kBlockPoints)
    for (int j0 = 0; j0 < grid.ny; j0 += kBlockPoints)
      for (int i0 = 0; i0 < grid.nx; i0 += kBlockPoints)
        sample_block(field, grid, offset_m,
                     {i0, std::min(i0 + kBlockPoints, grid.nx), j0, std::min(j0 + kBlockPoints, grid.ny), k0,
                      std::min(k0 + kBlockPoints, grid.nz)},
                     out);
  return out;
}

}  // namespace crowdlab::stimuli
