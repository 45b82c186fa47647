#include "framework/metrics/overlap_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

struct Interval {
  double lo;
  double hi;
};

/// A capsule with what the line test needs precomputed.
struct PreparedCapsule {
  Vec3 a;
  Vec3 b;
  Vec3 axis;      ///< unit (b - a), or zero for a sphere
  double length;  ///< |b - a|
  double radius;
};

PreparedCapsule prepare(const Capsule& c) {
  PreparedCapsule p{c.a, c.b, Vec3::Zero(), c.length_m(), c.radius_m};
  if (p.length > 1e-12) p.axis = (c.b - c.a) / p.length;
  return p;
}

/// Interval of t where o + t e_k lies within `radius` of the capsule's segment (false when empty).
/// o has o[k] = 0. The capsule is convex, so the union of its three pieces' intervals is one interval.
bool line_capsule_interval(const PreparedCapsule& c, const Vec3& o, int k, double radius, Interval& out) {
  if (radius <= 0.0) return false;
  const double r2 = radius * radius;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  auto sphere = [&](const Vec3& centre) {
    const Vec3 w = centre - o;
    const double d2 = w.squaredNorm() - w[k] * w[k];
    if (d2 > r2) return;
    const double half = std::sqrt(r2 - d2);
    lo = std::min(lo, w[k] - half);
    hi = std::max(hi, w[k] + half);
  };
  sphere(c.a);
  if (c.length > 1e-12) {
    sphere(c.b);
    // Finite cylinder: |w_perp + t e_perp|^2 <= r^2 and 0 <= w.u + t u_k <= L.
    const Vec3 w = o - c.a;
    const double wu = w.dot(c.axis);
    const Vec3 wp = w - wu * c.axis;
    const double uk = c.axis[k];
    const double qa = 1.0 - uk * uk;
    const double qb = 2.0 * wp[k];
    const double qc = wp.squaredNorm() - r2;
    double t0 = -HUGE_VAL, t1 = HUGE_VAL;
    bool hit = true;
    if (qa < 1e-14) {
      hit = qc <= 0.0;
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc < 0.0) {
        hit = false;
      } else {
        const double sq = std::sqrt(disc);
        t0 = (-qb - sq) / (2.0 * qa);
        t1 = (-qb + sq) / (2.0 * qa);
      }
    }
    if (hit) {
      if (std::abs(uk) > 1e-14) {
        double s0 = -wu / uk, s1 = (c.length - wu) / uk;
        if (s0 > s1) std::swap(s0, s1);
        t0 = std::max(t0, s0);
        t1 = std::min(t1, s1);
      } else if (wu < 0.0 || wu > c.length) {
        hit = false;
      }
      if (hit && t0 < t1) {
        lo = std::min(lo, t0);
        hi = std::max(hi, t1);
      }
    }
  }
  if (!(lo < hi)) return false;
  out = {lo, hi};
  return true;
}

/// Sorts and merges intervals in place; returns the merged count.
int merge_intervals(Interval* iv, int n) {
  // Insertion sort: n is small (the capsules that reach one column).
  for (int i = 1; i < n; ++i) {
    const Interval x = iv[i];
    int j = i - 1;
    while (j >= 0 && iv[j].lo > x.lo) {
      iv[j + 1] = iv[j];
      --j;
    }
    iv[j + 1] = x;
  }
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (m > 0 && iv[i].lo <= iv[m - 1].hi) {
      iv[m - 1].hi = std::max(iv[m - 1].hi, iv[i].hi);
    } else {
      iv[m++] = iv[i];
    }
  }
  return m;
}

double intersection_length(const Interval* x, int nx, const Interval* y, int ny) {
  double total = 0.0;
  int i = 0, j = 0;
  while (i < nx && j < ny) {
    const double lo = std::max(x[i].lo, y[j].lo), hi = std::min(x[i].hi, y[j].hi);
    if (hi > lo) total += hi - lo;
    if (x[i].hi < y[j].hi) {
      ++i;
    } else {
      ++j;
    }
  }
  return total;
}

struct Chords {
  double inner = 0.0;    ///< chord with radii shrunk by h
  double nominal = 0.0;  ///< chord with the true radii
  double outer = 0.0;    ///< chord with radii grown by h
};

/// The quadrature state for one overlap_volume() call.
class ColumnIntegrator {
 public:
  ColumnIntegrator(std::vector<PreparedCapsule> caps_a, std::vector<PreparedCapsule> caps_b, int axis,
                   const OverlapOptions& options)
      : a_(std::move(caps_a)), b_(std::move(caps_b)), k_(axis), options_(options) {
    i1_ = (k_ + 1) % 3;
    i2_ = (k_ + 2) % 3;
    const int levels = options_.max_depth + 2;
    list_a_.assign(static_cast<size_t>(levels) * a_.size(), 0);
    list_b_.assign(static_cast<size_t>(levels) * b_.size(), 0);
    iv_a_.resize(a_.size());
    iv_b_.resize(b_.size());
  }

  OverlapVolume integrate(double u0, double u1, double v0, double v1) {
    const double eu = u1 - u0, ev = v1 - v0;
    const double side = std::max(eu, ev) / 8.0;
    const int nu = std::max(1, static_cast<int>(std::ceil(eu / side - 1e-9)));
    const int nv = std::max(1, static_cast<int>(std::ceil(ev / side - 1e-9)));
    const double su = eu / nu, sv = ev / nv;
    const double h = 0.5 * std::hypot(su, sv);
    // Pass 1: base-grid estimate, which sets the absolute tolerance.
    std::vector<Chords> base(static_cast<size_t>(nu) * nv);
    double estimate0 = 0.0;
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double cu = u0 + (i + 0.5) * su, cv = v0 + (j + 0.5) * sv;
        if (!filter(0, cu, cv, h)) continue;
        base[static_cast<size_t>(i) * nv + j] = chords(0, cu, cv, h);
        estimate0 += su * sv * base[static_cast<size_t>(i) * nv + j].nominal;
      }
    }
    tol_per_area_ = std::max(options_.abs_tol_m3, options_.rel_tol * estimate0) / (eu * ev);
    // Pass 2: adaptive refinement of every base cell.
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double cu = u0 + (i + 0.5) * su, cv = v0 + (j + 0.5) * sv;
        if (!filter(0, cu, cv, h)) continue;
        refine(cu, cv, su, sv, 0, base[static_cast<size_t>(i) * nv + j]);
      }
    }
    result_.lower_m3 = std::min(result_.lower_m3, result_.volume_m3);
    result_.upper_m3 = std::max(result_.upper_m3, result_.volume_m3);
    return result_;
  }

 private:
  /// Fills level `level`'s lists with the capsules whose projection comes within r + h of (cu, cv),
  /// drawn from level - 1's lists (or from all capsules at level 0). False when either list is empty.
  bool filter(int level, double cu, double cv, double h) {
    const int na = filter_one(a_, list_a_, count_a_, level, cu, cv, h);
    const int nb = filter_one(b_, list_b_, count_b_, level, cu, cv, h);
    return na > 0 && nb > 0;
  }

  int filter_one(const std::vector<PreparedCapsule>& caps, std::vector<int>& lists, std::array<int, 64>& counts,
                 int level, double cu, double cv, double h) const {
    const size_t n = caps.size();
    int* dst = lists.data() + static_cast<size_t>(level) * n;
    const int* src = level == 0 ? nullptr : lists.data() + static_cast<size_t>(level - 1) * n;
    const int parent_count = level == 0 ? static_cast<int>(n) : counts[static_cast<size_t>(level - 1)];
    int count = 0;
    for (int q = 0; q < parent_count; ++q) {
      const int idx = src ? src[q] : q;
      if (reaches(caps[static_cast<size_t>(idx)], cu, cv, h)) dst[count++] = idx;
    }
    counts[static_cast<size_t>(level)] = count;
    return count;
  }

  /// Whether the capsule's projection onto the (i1, i2) plane comes within radius + h of (cu, cv).
  bool reaches(const PreparedCapsule& c, double cu, double cv, double h) const {
    const double au = c.a[i1_], av = c.a[i2_];
    const double du = c.b[i1_] - au, dv = c.b[i2_] - av;
    const double len2 = du * du + dv * dv;
    double t = 0.0;
    if (len2 > 1e-24) t = std::clamp(((cu - au) * du + (cv - av) * dv) / len2, 0.0, 1.0);
    const double pu = au + t * du - cu, pv = av + t * dv - cv;
    const double reach = c.radius + h;
    return pu * pu + pv * pv <= reach * reach;
  }

  double chord(int level, const Vec3& o, double dr) {
    const int na = count_a_[static_cast<size_t>(level)], nb = count_b_[static_cast<size_t>(level)];
    const int* la = list_a_.data() + static_cast<size_t>(level) * a_.size();
    const int* lb = list_b_.data() + static_cast<size_t>(level) * b_.size();
    int ma = 0;
    for (int q = 0; q < na; ++q) {
      const PreparedCapsule& c = a_[static_cast<size_t>(la[q])];
      if (line_capsule_interval(c, o, k_, c.radius + dr, iv_a_[static_cast<size_t>(ma)])) ++ma;
    }
    if (ma == 0) return 0.0;
    int mb = 0;
    for (int q = 0; q < nb; ++q) {
      const PreparedCapsule& c = b_[static_cast<size_t>(lb[q])];
      if (line_capsule_interval(c, o, k_, c.radius + dr, iv_b_[static_cast<size_t>(mb)])) ++mb;
    }
    if (mb == 0) return 0.0;
    ma = merge_intervals(iv_a_.data(), ma);
    mb = merge_intervals(iv_b_.data(), mb);
    return intersection_length(iv_a_.data(), ma, iv_b_.data(), mb);
  }

  Chords chords(int level, double cu, double cv, double h) {
    ++result_.chord_evaluations;
    Vec3 o = Vec3::Zero();
    o[i1_] = cu;
    o[i2_] = cv;
    Chords c;
    c.outer = chord(level, o, h);
    if (c.outer > 0.0) {
      c.nominal = chord(level, o, 0.0);
      if (c.nominal > 0.0) c.inner = chord(level, o, -h);
    }
    return c;
  }

  /// Cell centred (cu, cv) of size su x sv whose capsule lists sit at `level` and whose centre chords
  /// are `centre`. Either accepts the 4 children's midpoint sum or recurses into them.
  void refine(double cu, double cv, double su, double sv, int level, const Chords& centre) {
    const double area = su * sv, child_area = 0.25 * area;
    const double hu = 0.25 * su, hv = 0.25 * sv;
    const double child_h = 0.5 * std::hypot(0.5 * su, 0.5 * sv);
    const std::array<double, 4> du = {-hu, hu, -hu, hu}, dv = {-hv, -hv, hv, hv};
    std::array<Chords, 4> kids;
    double fine = 0.0, upper = 0.0;
    for (int q = 0; q < 4; ++q) {
      kids[static_cast<size_t>(q)] = chords(level, cu + du[static_cast<size_t>(q)], cv + dv[static_cast<size_t>(q)], child_h);
      fine += child_area * kids[static_cast<size_t>(q)].nominal;
      upper += child_area * kids[static_cast<size_t>(q)].outer;
    }
    const double coarse = area * centre.nominal;
    const double tol = tol_per_area_ * area;
    const bool unresolved = std::abs(fine - coarse) > tol || (fine == 0.0 && upper > tol);
    if (level >= options_.max_depth || !unresolved) {
      for (const Chords& c : kids) {
        result_.volume_m3 += child_area * c.nominal;
        result_.lower_m3 += child_area * c.inner;
        result_.upper_m3 += child_area * c.outer;
      }
      return;
    }
    for (int q = 0; q < 4; ++q) {
      const double kcu = cu + du[static_cast<size_t>(q)], kcv = cv + dv[static_cast<size_t>(q)];
      // A child whose grown-radius chord is empty holds no volume (see the bound in the header).
      if (kids[static_cast<size_t>(q)].outer <= 0.0 || !filter(level + 1, kcu, kcv, child_h)) continue;
      refine(kcu, kcv, 0.5 * su, 0.5 * sv, level + 1, kids[static_cast<size_t>(q)]);
    }
  }

  std::vector<PreparedCapsule> a_, b_;
  int k_, i1_ = 0, i2_ = 0;
  OverlapOptions options_;
  std::vector<int> list_a_, list_b_;
  std::array<int, 64> count_a_{}, count_b_{};
  std::vector<Interval> iv_a_, iv_b_;
  double tol_per_area_ = 0.0;
  OverlapVolume result_;
};

struct Box3 {
  Vec3 lo = Vec3::Constant(HUGE_VAL);
  Vec3 hi = Vec3::Constant(-HUGE_VAL);
};

Box3 capsule_box(const Capsule& c) {
  const Vec3 r = Vec3::Constant(c.radius_m);
  return {c.a.cwiseMin(c.b) - r, c.a.cwiseMax(c.b) + r};
}

void check_capsules(std::span<const Capsule> caps, const char* which) {
  for (size_t i = 0; i < caps.size(); ++i) {
    const Capsule& c = caps[i];
    if (!c.a.allFinite() || !c.b.allFinite() || !std::isfinite(c.radius_m) || c.radius_m <= 0.0)
      throw InputError("overlap_volume: capsule " + std::to_string(i) + " of body " + which +
                       " has a non-finite endpoint or a radius <= 0");
  }
}

}  // namespace

double OverlapVolume::error_bound_m3() const { return std::max(upper_m3 - volume_m3, volume_m3 - lower_m3); }

OverlapVolume overlap_volume(std::span<const Capsule> a, std::span<const Capsule> b, const OverlapOptions& options) {
  check_capsules(a, "A");
  check_capsules(b, "B");
  if (options.max_depth < 0 || options.max_depth > 60 || !(options.rel_tol >= 0.0) || !(options.abs_tol_m3 >= 0.0))
    throw InputError("overlap_volume: options need 0 <= max_depth <= 60 and tolerances >= 0");
  // Narrow phase: keep the capsules that overlap at least one capsule of the other body; only
  // they can contribute, since (∪A) ∩ (∪B) = ∪_ij (a_i ∩ b_j). The quadrature region is the box
  // around the touching pairs' box intersections.
  std::vector<char> keep_a(a.size(), 0), keep_b(b.size(), 0);
  Box3 region;
  for (size_t i = 0; i < a.size(); ++i) {
    const Box3 ba = capsule_box(a[i]);
    for (size_t j = 0; j < b.size(); ++j) {
      const Box3 bb = capsule_box(b[j]);
      if ((ba.hi.array() < bb.lo.array()).any() || (bb.hi.array() < ba.lo.array()).any()) continue;
      if (capsule_contact(a[i], b[j]).depth_m <= 0.0) continue;
      keep_a[i] = keep_b[j] = 1;
      region.lo = region.lo.cwiseMin(ba.lo.cwiseMax(bb.lo));
      region.hi = region.hi.cwiseMax(ba.hi.cwiseMin(bb.hi));
    }
  }
  std::vector<PreparedCapsule> pa, pb;
  for (size_t i = 0; i < a.size(); ++i)
    if (keep_a[i]) pa.push_back(prepare(a[i]));
  for (size_t j = 0; j < b.size(); ++j)
    if (keep_b[j]) pb.push_back(prepare(b[j]));
  if (pa.empty()) return {};
  const Vec3 extent = region.hi - region.lo;
  int k = 0;
  extent.maxCoeff(&k);
  const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
  ColumnIntegrator integrator(std::move(pa), std::move(pb), k, options);
  OverlapVolume out = integrator.integrate(region.lo[i1], region.hi[i1], region.lo[i2], region.hi[i2]);
  out.colliding = true;
  return out;
}

}  // namespace crowdlab
