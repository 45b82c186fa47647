#include "framework/metrics/overlap_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "framework/core/capsule_box.hpp"
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
  Vec2 a2;  ///< a projected on the quadrature plane (e1, e2)
  Vec2 b2;  ///< b projected on the quadrature plane
};

/// The quadrature frame: lines run along `dir`; (e1, e2) span the plane they are integrated over.
struct LineFrame {
  Vec3 dir;
  Vec3 e1;
  Vec3 e2;
};

PreparedCapsule prepare(const Capsule& c, const LineFrame& f) {
  PreparedCapsule p{c.a,
                    c.b,
                    Vec3::Zero(),
                    c.length_m(),
                    c.radius_m,
                    Vec2(c.a.dot(f.e1), c.a.dot(f.e2)),
                    Vec2(c.b.dot(f.e1), c.b.dot(f.e2))};
  if (p.length > 1e-12) p.axis = (c.b - c.a) / p.length;
  return p;
}

/// The line direction. Preferred: the contact normal of the deepest capsule pair, across which the
/// overlap is thinnest, so the lines cross it and its projection (what the 2D grid must resolve) is
/// widest. But lines parallel to a cylinder make the chord length jump at its side (a discontinuity
/// the midpoint rule integrates to first order only), so a direction is accepted only at >= 45
/// degrees to every capsule axis involved; else of the 13 directions of a cube's axes, face and body
/// diagonals the one whose smallest angle to any axis is largest.
LineFrame choose_frame(std::span<const Capsule> caps, const Vec3& contact_normal) {
  static const std::array<Vec3, 13> kCandidates = {
      Vec3(1, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1), Vec3(1, 1, 0),  Vec3(1, -1, 0),
      Vec3(1, 0, 1),  Vec3(1, 0, -1), Vec3(0, 1, 1), Vec3(0, 1, -1), Vec3(1, 1, 1),
      Vec3(1, 1, -1), Vec3(1, -1, 1), Vec3(-1, 1, 1)};
  auto score = [&](const Vec3& d) {  // min over capsules of sin^2(angle between d and the axis)
    double out = 1.0;
    for (const Capsule& c : caps) {
      const double len = c.length_m();
      if (len <= 1e-12) continue;
      const double cosine = d.dot(c.b - c.a) / len;
      out = std::min(out, 1.0 - cosine * cosine);
    }
    return out;
  };
  Vec3 best = contact_normal.normalized();
  double best_score = score(best);
  if (best_score < 0.5) {
    for (const Vec3& candidate : kCandidates) {
      const Vec3 d = candidate.normalized();
      const double sc = score(d);
      if (sc > best_score + 1e-12) {
        best_score = sc;
        best = d;
      }
    }
  }
  const Vec3 e1 = any_perpendicular(best);
  return {best, e1, best.cross(e1)};
}

/// Interval of t where o + t e lies within `radius` of the capsule's segment (false when empty);
/// e is unit. The capsule is convex, so the union of its three pieces' intervals is one interval.
bool line_capsule_interval(const PreparedCapsule& c, const Vec3& o, const Vec3& e, double radius,
                           Interval& out) {
  if (radius <= 0.0) return false;
  const double r2 = radius * radius;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  auto sphere = [&](const Vec3& centre) {
    const Vec3 w = centre - o;
    const double t0 = w.dot(e);
    const double d2 = w.squaredNorm() - t0 * t0;
    if (d2 > r2) return;
    const double half = std::sqrt(r2 - d2);
    lo = std::min(lo, t0 - half);
    hi = std::max(hi, t0 + half);
  };
  sphere(c.a);
  if (c.length > 1e-12) {
    sphere(c.b);
    // Finite cylinder: |w_perp + t e_perp|^2 <= r^2 and 0 <= w.u + t (e.u) <= L.
    const Vec3 w = o - c.a;
    const double wu = w.dot(c.axis);
    const Vec3 wp = w - wu * c.axis;
    const double ue = c.axis.dot(e);
    const double qa = 1.0 - ue * ue;
    const double qb = 2.0 * wp.dot(e);
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
      if (std::abs(ue) > 1e-14) {
        double s0 = -wu / ue, s1 = (c.length - wu) / ue;
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
  /// Integrates vol(A ∩ B ∩ clip) for the capsule sets A, B.
  ColumnIntegrator(std::vector<PreparedCapsule> caps_a, std::vector<PreparedCapsule> caps_b,
                   const LineFrame& frame, const Aabb& clip, const OverlapOptions& options)
      : a_(std::move(caps_a)), b_(std::move(caps_b)), frame_(frame), clip_(clip), options_(options) {
    const int levels = options_.depth + 2;
    list_a_.assign(static_cast<size_t>(levels) * a_.size(), 0);
    list_b_.assign(static_cast<size_t>(levels) * b_.size(), 0);
    iv_a_.resize(a_.size());
    iv_b_.resize(b_.size());
  }

  OverlapVolume integrate(double u0, double u1, double v0, double v1) {
    const double eu = u1 - u0, ev = v1 - v0;
    const double side = std::max(eu, ev) / options_.base_cells;
    const int nu = std::max(1, static_cast<int>(std::ceil(eu / side - 1e-9)));
    const int nv = std::max(1, static_cast<int>(std::ceil(ev / side - 1e-9)));
    const double su = eu / nu, sv = ev / nv;
    const double h = 0.5 * std::hypot(su, sv);
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        const double cu = u0 + (i + 0.5) * su, cv = v0 + (j + 0.5) * sv;
        if (!filter(0, cu, cv, h) || chords(0, cu, cv, h).outer <= 0.0) continue;
        refine(cu, cv, su, sv, 0);
      }
    }
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

  int filter_one(const std::vector<PreparedCapsule>& caps, std::vector<int>& lists,
                 std::array<int, 64>& counts, int level, double cu, double cv, double h) const {
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
    const double au = c.a2.x(), av = c.a2.y();
    const double du = c.b2.x() - au, dv = c.b2.y() - av;
    const double len2 = du * du + dv * dv;
    double t = 0.0;
    if (len2 > 1e-24) t = std::clamp(((cu - au) * du + (cv - av) * dv) / len2, 0.0, 1.0);
    const double pu = au + t * du - cu, pv = av + t * dv - cv;
    const double reach = c.radius + h;
    return pu * pu + pv * pv <= reach * reach;
  }

  /// Length of {t : o + t dir in A_dr ∩ B_dr ∩ clip_dr}, where X_dr grows X's radii (or the clip
  /// box's half-extents) by dr (dr < 0 shrinks).
  double chord(int level, const Vec3& o, double dr) {
    double tlo = -HUGE_VAL, thi = HUGE_VAL;
    for (int k = 0; k < 3; ++k) {
      const double lo = clip_.lo[k] - dr, hi = clip_.hi[k] + dr, dk = frame_.dir[k];
      if (std::abs(dk) < 1e-14) {
        if (o[k] < lo || o[k] > hi) return 0.0;
        continue;
      }
      double t0 = (lo - o[k]) / dk, t1 = (hi - o[k]) / dk;
      if (t0 > t1) std::swap(t0, t1);
      tlo = std::max(tlo, t0);
      thi = std::min(thi, t1);
    }
    if (!(tlo < thi)) return 0.0;
    const int na = count_a_[static_cast<size_t>(level)], nb = count_b_[static_cast<size_t>(level)];
    const int* la = list_a_.data() + static_cast<size_t>(level) * a_.size();
    const int* lb = list_b_.data() + static_cast<size_t>(level) * b_.size();
    int ma = 0;
    for (int q = 0; q < na; ++q) {
      const PreparedCapsule& c = a_[static_cast<size_t>(la[q])];
      if (clipped_interval(c, o, dr, tlo, thi, iv_a_[static_cast<size_t>(ma)])) ++ma;
    }
    if (ma == 0) return 0.0;
    int mb = 0;
    for (int q = 0; q < nb; ++q) {
      const PreparedCapsule& c = b_[static_cast<size_t>(lb[q])];
      if (clipped_interval(c, o, dr, tlo, thi, iv_b_[static_cast<size_t>(mb)])) ++mb;
    }
    if (mb == 0) return 0.0;
    ma = merge_intervals(iv_a_.data(), ma);
    mb = merge_intervals(iv_b_.data(), mb);
    return intersection_length(iv_a_.data(), ma, iv_b_.data(), mb);
  }

  bool clipped_interval(const PreparedCapsule& c, const Vec3& o, double dr, double tlo, double thi,
                        Interval& out) const {
    if (!line_capsule_interval(c, o, frame_.dir, c.radius + dr, out)) return false;
    out.lo = std::max(out.lo, tlo);
    out.hi = std::min(out.hi, thi);
    return out.lo < out.hi;
  }

  /// The centre-line chords of a cell of half-diagonal h. The grown-radius chord comes first: when
  /// it is empty the cell holds no volume and the other two are zero too.
  Chords chords(int level, double cu, double cv, double h) {
    ++result_.chord_evaluations;
    const Vec3 o = cu * frame_.e1 + cv * frame_.e2;
    Chords c;
    c.outer = chord(level, o, h);
    if (c.outer > 0.0) {
      c.nominal = chord(level, o, 0.0);
      if (c.nominal > 0.0) c.inner = chord(level, o, -h);
    }
    return c;
  }

  /// Cell centred (cu, cv) of size su x sv whose capsule lists sit at `level`. At the finest level it
  /// adds its 4 children's midpoint sums (estimate and bracket); above, it recurses into them.
  void refine(double cu, double cv, double su, double sv, int level) {
    const double area = su * sv, child_area = 0.25 * area;
    const double hu = 0.25 * su, hv = 0.25 * sv;
    const double child_h = 0.5 * std::hypot(0.5 * su, 0.5 * sv);
    const std::array<double, 4> du = {-hu, hu, -hu, hu}, dv = {-hv, -hv, hv, hv};
    std::array<Chords, 4> kids;
    for (size_t q = 0; q < 4; ++q) kids[q] = chords(level, cu + du[q], cv + dv[q], child_h);
    if (level >= options_.depth) {
      for (const Chords& c : kids) {
        result_.volume_m3 += child_area * c.nominal;
        result_.lower_m3 += child_area * c.inner;
        result_.upper_m3 += child_area * c.outer;
      }
      return;
    }
    for (size_t q = 0; q < 4; ++q) {
      const double kcu = cu + du[q], kcv = cv + dv[q];
      // A child whose grown-radius chord is empty holds no volume (see the bound in the header).
      if (kids[q].outer <= 0.0 || !filter(level + 1, kcu, kcv, child_h)) continue;
      refine(kcu, kcv, 0.5 * su, 0.5 * sv, level + 1);
    }
  }

  std::vector<PreparedCapsule> a_, b_;
  LineFrame frame_;
  Aabb clip_;
  OverlapOptions options_;
  std::vector<int> list_a_, list_b_;
  std::array<int, 64> count_a_{}, count_b_{};
  std::vector<Interval> iv_a_, iv_b_;
  OverlapVolume result_;
};

void check_capsules(std::span<const Capsule> caps, const char* which) {
  for (size_t i = 0; i < caps.size(); ++i) {
    const Capsule& c = caps[i];
    if (!c.a.allFinite() || !c.b.allFinite() || !std::isfinite(c.radius_m) || c.radius_m <= 0.0)
      throw InputError("overlap_volume: capsule " + std::to_string(i) + " of body " + which +
                       " has a non-finite endpoint or a radius <= 0");
  }
}

}  // namespace

double OverlapVolume::error_bound_m3() const {
  return std::max(upper_m3 - volume_m3, volume_m3 - lower_m3);
}

OverlapVolume overlap_volume(std::span<const Capsule> a, std::span<const Capsule> b,
                             const OverlapOptions& options) {
  check_capsules(a, "A");
  check_capsules(b, "B");
  if (options.depth < 0 || options.depth > 12 || options.base_cells < 1 || options.base_cells > 4096)
    throw InputError("overlap_volume: options need 0 <= depth <= 12 and 1 <= base_cells <= 4096");
  // Narrow phase: the capsule pairs (i, j) that overlap. (∪A) ∩ (∪B) = ∪_ij (a_i ∩ b_j), and each
  // a_i ∩ b_j lies in the intersection of the two capsules' boxes. Touching pairs are grouped into
  // clusters whose boxes (around their pairs' box intersections) are disjoint; each cluster is
  // integrated on its own grid, clipped to its box, so a small contact far from a large one gets its
  // own resolution, and the clusters' volumes add up exactly.
  struct Cluster {
    Aabb box;
    std::vector<char> in_a, in_b;
    double deepest = 0.0;
    Vec3 normal = Vec3::UnitX();
    bool alive = true;
  };
  std::vector<Cluster> clusters;
  for (size_t i = 0; i < a.size(); ++i) {
    const Aabb ba = capsule_box(a[i]);
    for (size_t j = 0; j < b.size(); ++j) {
      const Aabb bb = capsule_box(b[j]);
      if (!ba.overlaps(bb)) continue;
      const CapsuleContact contact = capsule_contact(a[i], b[j]);
      if (contact.depth_m <= 0.0) continue;
      Cluster c{ba.intersection(bb),
                std::vector<char>(a.size(), 0),
                std::vector<char>(b.size(), 0),
                contact.depth_m,
                contact.normal,
                true};
      c.in_a[i] = c.in_b[j] = 1;
      clusters.push_back(std::move(c));
    }
  }
  if (clusters.empty()) return {};
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t p = 0; p < clusters.size(); ++p) {
      for (size_t q = p + 1; q < clusters.size(); ++q) {
        if (!clusters[p].alive || !clusters[q].alive || !clusters[p].box.overlaps(clusters[q].box)) continue;
        Cluster& x = clusters[p];
        Cluster& y = clusters[q];
        x.box.extend(y.box);
        for (size_t i = 0; i < a.size(); ++i) x.in_a[i] |= y.in_a[i];
        for (size_t j = 0; j < b.size(); ++j) x.in_b[j] |= y.in_b[j];
        if (y.deepest > x.deepest) {
          x.deepest = y.deepest;
          x.normal = y.normal;
        }
        y.alive = false;
        merged = true;
      }
    }
  }
  OverlapVolume out;
  for (const Cluster& cluster : clusters) {
    if (!cluster.alive) continue;
    std::vector<Capsule> kept;
    for (size_t i = 0; i < a.size(); ++i)
      if (cluster.in_a[i]) kept.push_back(a[i]);
    const size_t kept_a = kept.size();
    for (size_t j = 0; j < b.size(); ++j)
      if (cluster.in_b[j]) kept.push_back(b[j]);
    const LineFrame frame = choose_frame(kept, cluster.normal);
    std::vector<PreparedCapsule> pa, pb;
    for (size_t i = 0; i < kept.size(); ++i) (i < kept_a ? pa : pb).push_back(prepare(kept[i], frame));
    // The quadrature rectangle: the cluster box projected on (e1, e2).
    Vec2 lo = Vec2::Constant(HUGE_VAL), hi = Vec2::Constant(-HUGE_VAL);
    for (int corner = 0; corner < 8; ++corner) {
      const Aabb& r = cluster.box;
      const Vec3 p((corner & 1) ? r.hi.x() : r.lo.x(), (corner & 2) ? r.hi.y() : r.lo.y(),
                   (corner & 4) ? r.hi.z() : r.lo.z());
      const Vec2 q(p.dot(frame.e1), p.dot(frame.e2));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    ColumnIntegrator integrator(std::move(pa), std::move(pb), frame, cluster.box, options);
    const OverlapVolume part = integrator.integrate(lo.x(), hi.x(), lo.y(), hi.y());
    out.volume_m3 += part.volume_m3;
    out.lower_m3 += part.lower_m3;
    out.upper_m3 += part.upper_m3;
    out.chord_evaluations += part.chord_evaluations;
  }
  out.colliding = true;
  return out;
}

}  // namespace crowdlab
