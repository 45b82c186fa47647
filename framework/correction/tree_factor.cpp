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

bool factor_character(CorrectorState& s, int c) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  bool ok = true;
  Mat6 inverse;
  for (size_t j = kJointCount - 1; j >= 1; --j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    if (!spd_inverse6(s.precond[g], inverse)) {
      ok = false;
      inverse.setZero();
    }
    const Mat6 b = coupling_matrix(s.coupling[g]);
    const Mat6 elim = inverse.lazyProduct(b);
    s.precond[gp].noalias() -= b.transpose().lazyProduct(elim);
    s.precond[g] = inverse;
  }
  if (!spd_inverse6(s.precond[base], inverse)) {
    ok = false;
    inverse.setZero();
  }
  s.precond[base] = inverse;
  return ok;
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
