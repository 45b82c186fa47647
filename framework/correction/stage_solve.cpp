// Solve H dq = b by preconditioned conjugate gradients (seed 000 §3.2: "we solve this linear system
// using conjugate gradient"), with a preconditioner that exploits each character's tree structure.
//
// H = T + C: T holds, per character, the inertia/joint/control blocks, which couple a bone only with
// its parent, so T is block tree-structured (24 nodes of 6 x 6); C holds the contact rank-1 terms
// k w w^T, which may couple any two bones (intra- and inter-body). The preconditioner is
// P = T + blockdiag(C), factorised EXACTLY per character by eliminating the tree from the leaves to
// the root (Gaussian elimination on a tree has no fill-in: Featherstone's articulated-body algorithm
// in matrix form, or Baraff 1996 "Linear-time dynamics using Lagrange multipliers"). Factorisation is
// O(24 * 6^3) and each application O(24 * 6^2) per character; CG only has to resolve the off-tree
// contact couplings, so it converges in a few iterations. Work is split over characters (TBB); dot
// products are summed per character and then in character order, so results do not depend on the
// number of threads.
#include <cmath>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
namespace {

/// Tree elimination from the leaves (j = 23) to the root: after it, precond[g] holds the inverse of
/// bone g's eliminated block S_g and elim[g] = S_g^-1 B_g (B_g = coupling[g]), so applying the
/// preconditioner costs three 6 x 6 matrix-vector products per bone. Returns false if a block is not
/// positive definite (cannot happen for valid parameters: every block contains M / h^2 > 0).
/// Inverse of a symmetric positive definite 6 x 6 matrix by Cholesky (fixed-size loops; Eigen's
/// generic triangular solves are several times slower at this size). False if not SPD.
bool spd_inverse6(const Mat6& a, Mat6& inverse) {
  double l[6][6] = {};
  for (int j = 0; j < 6; ++j) {
    double d = a(j, j);
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > 0.0)) return false;
    l[j][j] = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      double v = a(i, j);
      for (int k = 0; k < j; ++k) v -= l[i][k] * l[j][k];
      l[i][j] = v / l[j][j];
    }
  }
  // W = L^-1 (lower triangular), then A^-1 = W^T W.
  double w[6][6] = {};
  for (int i = 0; i < 6; ++i) {
    w[i][i] = 1.0 / l[i][i];
    for (int j = 0; j < i; ++j) {
      double v = 0.0;
      for (int k = j; k < i; ++k) v -= l[i][k] * w[k][j];
      w[i][j] = v / l[i][i];
    }
  }
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      double v = 0.0;
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
    s.elim[g].noalias() = inverse.lazyProduct(s.coupling[g]);
    s.precond[gp].noalias() -= s.coupling[g].transpose().lazyProduct(s.elim[g]);
    s.precond[g] = inverse;
  }
  if (!spd_inverse6(s.precond[base], inverse)) {
    ok = false;
    inverse.setZero();
  }
  s.precond[base] = inverse;
  return ok;
}

/// z = P^-1 r for character c (block forward elimination, root solve, back substitution).
void apply_preconditioner(CorrectorState& s, int c, const std::vector<Vec6>& r, std::vector<Vec6>& z) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  for (size_t j = 0; j < kJointCount; ++j) z[base + j] = r[base + j];
  for (size_t j = kJointCount - 1; j >= 1; --j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    s.cg_y[g].noalias() = s.precond[g] * z[g];
    z[gp].noalias() -= s.coupling[g].transpose() * s.cg_y[g];
  }
  z[base] = s.precond[base] * z[base];
  for (size_t j = 1; j < kJointCount; ++j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    z[g] = s.cg_y[g];
    z[g].noalias() -= s.elim[g] * z[gp];
  }
}

/// y = H x for character c's rows; contact_scalar must hold k (w . x) for every contact.
void multiply_character(CorrectorState& s, int c, const std::vector<Vec6>& x, std::vector<Vec6>& y) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  for (size_t j = 0; j < kJointCount; ++j) y[base + j] = s.diag[base + j] * x[base + j];
  for (size_t j = 1; j < kJointCount; ++j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    y[g] += s.coupling[g] * x[gp];
    y[gp] += s.coupling[g].transpose() * x[g];
  }
  const int begin = s.incidence_offset[static_cast<size_t>(c)],
            end = s.incidence_offset[static_cast<size_t>(c) + 1];
  for (int e = begin; e < end; ++e) {
    const int entry = s.incidence[static_cast<size_t>(e)];
    const Contact& k = s.contacts[static_cast<size_t>(entry / 2)];
    const double sk = s.contact_scalar[static_cast<size_t>(entry / 2)];
    if (entry & 1) {
      y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    } else {
      y[static_cast<size_t>(k.bone_a)] += sk * k.w_a;
      if (k.bone_b >= 0 && k.bone_b / kJointCount == c) y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    }
  }
}

void multiply(const CorrectorModel& model, CorrectorState& s, const std::vector<Vec6>& x,
              std::vector<Vec6>& y) {
  s.contact_scalar.resize(s.contacts.size());
  tbb::parallel_for(size_t{0}, s.contacts.size(), [&](size_t k) {
    const Contact& c = s.contacts[k];
    double v = c.w_a.dot(x[static_cast<size_t>(c.bone_a)]);
    if (c.bone_b >= 0) v += c.w_b.dot(x[static_cast<size_t>(c.bone_b)]);
    s.contact_scalar[k] = c.stiffness * v;
  });
  tbb::parallel_for(0, model.characters(), [&](int c) { multiply_character(s, c, x, y); });
}

/// Fixed-order sum of per-character partial sums.
double reduce(const std::vector<double>& partial) {
  double total = 0.0;
  for (double v : partial) total += v;
  return total;
}
double reduce(const CorrectorState& s) {
  return reduce(s.partial);
}

}  // namespace

void stage_solve(const CorrectorModel& model, CorrectorState& s) {
  const int n = model.characters();
  const CorrectorParams& p = model.params;
  std::vector<char>& ok = s.factor_ok;
  tbb::parallel_for(0, n, [&](int c) { ok[static_cast<size_t>(c)] = factor_character(s, c) ? 1 : 0; });

  // Warm start from the previous velocities (x0 = h v_old: the motion is smooth from step to step),
  // r = b - H x0, z = P^-1 r, p = z.
  tbb::parallel_for(0, n, [&](int c) {
    for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount; ++j) {
      s.cg_x[j].head<3>() = model.h * s.velocity_mps[j];
      s.cg_x[j].tail<3>() = model.h * s.omega_radps[j];
    }
  });
  multiply(model, s, s.cg_x, s.cg_q);
  tbb::parallel_for(0, n, [&](int c) {
    const size_t base = static_cast<size_t>(c) * kJointCount;
    double bb = 0.0, rz = 0.0;
    for (size_t j = base; j < base + kJointCount; ++j) {
      s.cg_r[j] = s.rhs[j] - s.cg_q[j];
      bb += s.rhs[j].squaredNorm();
    }
    apply_preconditioner(s, c, s.cg_r, s.cg_z);
    for (size_t j = base; j < base + kJointCount; ++j) {
      s.cg_p[j] = s.cg_z[j];
      rz += s.cg_r[j].dot(s.cg_z[j]);
    }
    s.partial[static_cast<size_t>(c)] = bb;
    s.partial2[static_cast<size_t>(c)] = rz;
  });
  const double b_norm2 = reduce(s.partial);
  double rz = reduce(s.partial2);
  const double tol2 = p.cg_tolerance * p.cg_tolerance * b_norm2;
  tbb::parallel_for(0, n, [&](int c) {
    double rr = 0.0;
    for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount; ++j)
      rr += s.cg_r[j].squaredNorm();
    s.partial[static_cast<size_t>(c)] = rr;
  });
  double r_norm2 = reduce(s.partial);
  int it = 0;
  bool finite = std::isfinite(b_norm2) && std::isfinite(rz);
  while (finite && r_norm2 > tol2 && it < p.cg_max_iterations) {
    multiply(model, s, s.cg_p, s.cg_q);
    tbb::parallel_for(0, n, [&](int c) {
      double pq = 0.0;
      for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount; ++j)
        pq += s.cg_p[j].dot(s.cg_q[j]);
      s.partial[static_cast<size_t>(c)] = pq;
    });
    const double pq = reduce(s);
    if (!(pq > 0.0) || !std::isfinite(pq)) {
      finite = std::isfinite(pq);
      break;
    }
    const double alpha = rz / pq;
    tbb::parallel_for(0, n, [&](int c) {
      double rr = 0.0;
      for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount;
           ++j) {
        s.cg_x[j] += alpha * s.cg_p[j];
        s.cg_r[j] -= alpha * s.cg_q[j];
        rr += s.cg_r[j].squaredNorm();
      }
      s.partial[static_cast<size_t>(c)] = rr;
    });
    r_norm2 = reduce(s);
    ++it;
    if (r_norm2 <= tol2) break;
    tbb::parallel_for(0, n, [&](int c) {
      apply_preconditioner(s, c, s.cg_r, s.cg_z);
      double v = 0.0;
      for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount; ++j)
        v += s.cg_r[j].dot(s.cg_z[j]);
      s.partial[static_cast<size_t>(c)] = v;
    });
    const double rz_new = reduce(s);
    const double beta = rz_new / rz;
    rz = rz_new;
    tbb::parallel_for(0, n, [&](int c) {
      for (size_t j = static_cast<size_t>(c) * kJointCount; j < static_cast<size_t>(c + 1) * kJointCount; ++j)
        s.cg_p[j] = s.cg_z[j] + beta * s.cg_p[j];
    });
    finite = std::isfinite(r_norm2) && std::isfinite(rz);
  }
  bool factors_ok = true;
  for (char v : ok) factors_ok = factors_ok && v != 0;
  s.stats.cg_iterations = it;
  s.stats.cg_relative_residual = b_norm2 > 0.0 ? std::sqrt(r_norm2 / b_norm2) : 0.0;
  s.stats.converged = finite && factors_ok && r_norm2 <= tol2;
  if (!finite || !factors_ok) s.stats.cg_relative_residual = INFINITY;
}

}  // namespace crowdlab
