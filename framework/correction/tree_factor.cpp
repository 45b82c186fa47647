#include "framework/correction/tree_factor.hpp"

#include <cmath>

namespace crowdlab {

Mat6 coupling_matrix(const JointCoupling& k) {
  // a_c^T a_p = [I, -[r_p]x; [r_c]x, -[r_c]x [r_p]x].
  const Mat3 sc = skew(k.arm_child), sp = skew(k.arm_parent);
  Mat6 m;
  m.topLeftCorner<3, 3>() = -k.joint_k * Mat3::Identity();
  m.topRightCorner<3, 3>() = k.joint_k * sp;
  m.bottomLeftCorner<3, 3>() = -k.joint_k * sc;
  m.bottomRightCorner<3, 3>() = k.joint_k * (sc * sp) - k.rot_k * Mat3::Identity();
  return m;
}

bool spd_inverse6(const Mat6& a, Mat6& inverse) {
  // Fixed-size loops: Eigen's generic triangular solves are several times slower at this size. Fully
  // unrolled (the trip counts are constants), the compiler keeps l and w in registers and drops the loop
  // control: a third of the instructions for the same operations in the same order (bit-identical).
  // Only the lower triangles of l and w are written and read.
  double l[6][6], w[6][6];
#pragma GCC unroll 6
  for (int j = 0; j < 6; ++j) {
    double d = a(j, j);
#pragma GCC unroll 6
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > 0.0)) return false;
    l[j][j] = std::sqrt(d);
#pragma GCC unroll 6
    for (int i = j + 1; i < 6; ++i) {
      double v = a(i, j);
#pragma GCC unroll 6
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = v / l[j][j];
    }
  }
  // W = L^-1 (lower triangular), then A^-1 = W^T W.
#pragma GCC unroll 6
  for (int i = 0; i < 6; ++i) {
    w[i][i] = 1.0 / l[i][i];
#pragma GCC unroll 6
    for (int j = 0; j < i; ++j) {
      double v = 0.0;
#pragma GCC unroll 6
      for (int k = j; k < i; ++k) v -= l[i][k] * w[k][j];
      w[i][j] = v / l[i][i];
    }
  }
#pragma GCC unroll 6
  for (int i = 0; i < 6; ++i)
#pragma GCC unroll 6
    for (int j = i; j < 6; ++j) {
      double v = 0.0;
#pragma GCC unroll 6
      for (int k = j; k < 6; ++k) v += w[k][i] * w[k][j];
      inverse(i, j) = v;
      inverse(j, i) = v;
    }
  return true;
}

namespace {

/// Eliminates bone g (child of gp) of a tree whose blocks below g are eliminated: precond[g] becomes
/// S_g^-1 and precond[gp] loses H[g,p]^T S_g^-1 H[g,p] (`update`). False if S_g is not SPD.
bool eliminate_bone(CorrectorState& s, size_t g, size_t gp, Mat6& inverse, Mat6& update) {
  bool ok = true;
  if (!spd_inverse6(s.precond[g], inverse)) {
    ok = false;
    inverse.setZero();
  }
  const Mat6 b = coupling_matrix(s.coupling[g]);
  const Mat6 elim = inverse.lazyProduct(b);
  update.noalias() = b.transpose().lazyProduct(elim);
  s.precond[gp] -= update;
  s.precond[g] = inverse;
  return ok;
}

bool invert_root(CorrectorState& s, size_t base, Mat6& inverse) {
  bool ok = true;
  if (!spd_inverse6(s.precond[base], inverse)) {
    ok = false;
    inverse.setZero();
  }
  s.precond[base] = inverse;
  return ok;
}

}  // namespace

bool factor_character(CorrectorState& s, int c) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  bool ok = true;
  Mat6 inverse, update;
  for (size_t j = kJointCount - 1; j >= 1; --j)
    ok = eliminate_bone(s, base + j, base + static_cast<size_t>(kJointParent[j]), inverse, update) && ok;
  return invert_root(s, base, inverse) && ok;
}

bool factor_tree_character(CorrectorState& s, int c) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  bool ok = true;
  Mat6 inverse;
  for (size_t j = kJointCount - 1; j >= 1; --j) {
    const size_t g = base + j;
    ok = eliminate_bone(s, g, base + static_cast<size_t>(kJointParent[j]), inverse, s.tree_update[g]) && ok;
    s.tree_inverse[g] = inverse;
  }
  ok = invert_root(s, base, inverse) && ok;
  s.tree_inverse[base] = inverse;
  return ok;
}

bool refactor_character(CorrectorState& s, int c, BoneMask contact_blocks) {
  // A bone must be refactorised when it or a descendant has a contact block (parents precede children).
  BoneMask dirty = contact_blocks;
  for (size_t j = kJointCount - 1; j >= 1; --j)
    if (dirty & (BoneMask{1} << j)) dirty |= BoneMask{1} << kJointParent[j];
  const size_t base = static_cast<size_t>(c) * kJointCount;
  bool ok = true;
  Mat6 inverse, update;
  for (size_t j = kJointCount - 1; j >= 1; --j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    if (dirty & (BoneMask{1} << j)) {
      ok = eliminate_bone(s, g, gp, inverse, update) && ok;
    } else {
      s.precond[gp] -= s.tree_update[g];
      s.precond[g] = s.tree_inverse[g];
    }
  }
  if (!(dirty & BoneMask{1})) {
    s.precond[base] = s.tree_inverse[base];
    return ok;
  }
  return invert_root(s, base, inverse) && ok;
}

void apply_tree_inverse(const CorrectorState& s, int c, const std::vector<Vec6>& r, std::vector<Vec6>& z) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  std::array<Vec6, kJointCount> w, y;
  for (size_t j = 0; j < kJointCount; ++j) w[j] = r[base + j];
  for (size_t j = kJointCount - 1; j >= 1; --j) {
    const size_t pj = static_cast<size_t>(kJointParent[j]);
    y[j].noalias() = s.precond[base + j] * w[j];
    w[pj] -= coupling_transpose_times(s.coupling[base + j], y[j]);
  }
  w[0] = s.precond[base] * w[0];
  for (size_t j = 1; j < kJointCount; ++j) {
    const size_t pj = static_cast<size_t>(kJointParent[j]);
    w[j] = y[j];
    w[j].noalias() -= s.precond[base + j] * coupling_times(s.coupling[base + j], w[pj]);
  }
  for (size_t j = 0; j < kJointCount; ++j) z[base + j] = w[j];
}

}  // namespace crowdlab
