// Solve H dq = b by preconditioned conjugate gradients (seed 000 §3.2: "we solve this linear system
// using conjugate gradient"), with a preconditioner that exploits each character's tree structure.
//
// H = T + C: T holds, per character, the inertia/joint/control blocks, which couple a bone only with
// its parent, so T is block tree-structured (24 nodes of 6 x 6); C holds the contact rank-1 terms
// k w w^T, which may couple any two bones (intra- and inter-body). The preconditioner is
// P = T + blockdiag(C), factorised EXACTLY per character (tree_factor.hpp, no fill-in on a tree).
// CG only has to resolve the off-diagonal contact couplings, so it converges in a few iterations.
// CG starts from the contact-free prediction dq_free (stage_predict), the exact answer for every
// body that touches nothing.
//
// One CG iteration is two passes over the characters (TBB), each writing per-index slots (a contact's
// term k w . p is computed by each character it touches); dot products are summed per
// character and then in character order, so results do not depend on the number of threads.
//
// Active set: E_collisions = 1/2 k max(0, delta)^2 is one-sided, but its linearisation is a full
// quadratic, which would pull apart surfaces back together when the solution separates them (a
// contact whose linearised depth ends below zero). Such "pulling" contacts are removed and the system
// re-solved from the current iterate (a primal active-set step, Nocedal & Wright 2006, §16.5), at most
// CorrectorParams::active_set_passes times.
#include <cmath>
#include <utility>

#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/tree_factor.hpp"

namespace crowdlab {
namespace {

/// A contact pulls when its linearised depth at the solution is below -kPullTolerance (m): 0.1 mm,
/// far below anything visible, so that contacts resting exactly at the surface are kept.
constexpr double kPullTolerance = 1e-4;

/// k (w . (z + beta p)) of contact c, both sides: k w . p_new with p_new = z + beta p formed on the fly from
/// the last iteration's p, so each character's pass can compute the scalars of its own contacts while
/// the other characters' passes write their new p (into another buffer). A contact between two
/// characters is computed by both, with the same operations in the same order, so both get the same
/// value (this replaced a separate pass over the contacts and the barrier after it; session 20).
double contact_scalar(const Contact& c, const std::vector<Vec6>& z, const std::vector<Vec6>& p, double beta) {
  const auto a = static_cast<size_t>(c.bone_a);
  double v = c.w_a.dot(z[a] + beta * p[a]);
  if (c.bone_b >= 0) {
    const auto b = static_cast<size_t>(c.bone_b);
    v += c.w_b.dot(z[b] + beta * p[b]);
  }
  return c.stiffness * v;
}

/// y = H x for character c's rows, where x = z + beta p (x already formed for c's own bones; the
/// contact terms form it for the other characters' bones from z and the last p).
void multiply_character(CorrectorState& s, int c, const std::vector<Vec6>& x, const std::vector<Vec6>& z,
                        const std::vector<Vec6>& p, double beta, std::vector<Vec6>& y) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  for (size_t j = 0; j < kJointCount; ++j) y[base + j].noalias() = s.diag[base + j] * x[base + j];
  for (size_t j = 1; j < kJointCount; ++j) {
    const size_t g = base + j, gp = base + static_cast<size_t>(kJointParent[j]);
    y[g] += coupling_times(s.coupling[g], x[gp]);
    y[gp] += coupling_transpose_times(s.coupling[g], x[g]);
  }
  const int begin = s.incidence_offset[static_cast<size_t>(c)],
            end = s.incidence_offset[static_cast<size_t>(c) + 1];
  for (int e = begin; e < end; ++e) {
    const int entry = s.incidence[static_cast<size_t>(e)];
    const Contact& k = s.contacts[static_cast<size_t>(entry / 2)];
    const double sk = contact_scalar(k, z, p, beta);
    if (entry & 1) {
      y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    } else {
      y[static_cast<size_t>(k.bone_a)] += sk * k.w_a;
      if (k.bone_b >= 0 && k.bone_b / kJointCount == c) y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    }
  }
}

/// Fixed-order sum of per-character partial sums.
double reduce(const std::vector<double>& partial) {
  double total = 0.0;
  for (double v : partial) total += v;
  return total;
}

struct CgResult {
  int iterations = 0;
  double r_norm2 = 0.0, b_norm2 = 0.0;
  bool finite = true;
};

/// PCG on H x = b from the current s.cg_x (the factorisation in s.precond must be up to date).
CgResult conjugate_gradients(const CorrectorModel& model, CorrectorState& s) {
  const int n = model.characters();
  const CorrectorParams& p = model.params;
  CgResult out;
  // r = b - H x0, z = P^-1 r, p = z.
  tbb::parallel_for(0, n, [&](int c) {
    multiply_character(s, c, s.cg_x, s.cg_x, s.cg_x, 0.0, s.cg_q);  // contacts: k w . (x0 + 0 x0)
    const size_t base = static_cast<size_t>(c) * kJointCount;
    double bb = 0.0, rz = 0.0, rr = 0.0;
    for (size_t j = base; j < base + kJointCount; ++j) {
      s.cg_r[j] = s.rhs[j] - s.cg_q[j];
      bb += s.rhs[j].squaredNorm();
      rr += s.cg_r[j].squaredNorm();
    }
    apply_tree_inverse(s, c, s.cg_r, s.cg_z);
    for (size_t j = base; j < base + kJointCount; ++j) {
      s.cg_p[j] = s.cg_z[j];
      rz += s.cg_r[j].dot(s.cg_z[j]);
    }
    s.partial[static_cast<size_t>(c)] = bb;
    s.partial2[static_cast<size_t>(c)] = rz;
    s.partial3[static_cast<size_t>(c)] = rr;
  });
  out.b_norm2 = reduce(s.partial);
  double rz = reduce(s.partial2);
  out.r_norm2 = reduce(s.partial3);
  const double tol2 = p.cg_tolerance * p.cg_tolerance * out.b_norm2;
  out.finite = std::isfinite(out.b_norm2) && std::isfinite(rz);
  double beta = 0.0;  // p = z + beta p, applied lazily by the next contact and character passes
  while (out.finite && out.r_norm2 > tol2 && out.iterations < p.cg_max_iterations) {
    // Pass 1 (characters): p = z + beta p (into cg_p_next: the other characters' contact terms read
    // the last p), q = H p, p . q.
    tbb::parallel_for(0, n, [&](int c) {
      const size_t base = static_cast<size_t>(c) * kJointCount;
      for (size_t j = base; j < base + kJointCount; ++j) s.cg_p_next[j] = s.cg_z[j] + beta * s.cg_p[j];
      multiply_character(s, c, s.cg_p_next, s.cg_z, s.cg_p, beta, s.cg_q);
      double pq = 0.0;
      for (size_t j = base; j < base + kJointCount; ++j) pq += s.cg_p_next[j].dot(s.cg_q[j]);
      s.partial[static_cast<size_t>(c)] = pq;
    });
    std::swap(s.cg_p, s.cg_p_next);
    const double pq = reduce(s.partial);
    if (!(pq > 0.0) || !std::isfinite(pq)) {
      out.finite = std::isfinite(pq);
      break;
    }
    const double alpha = rz / pq;
    // Pass 2 (characters): x += alpha p, r -= alpha q, z = P^-1 r, r . r, r . z.
    tbb::parallel_for(0, n, [&](int c) {
      const size_t base = static_cast<size_t>(c) * kJointCount;
      double rr = 0.0, v = 0.0;
      for (size_t j = base; j < base + kJointCount; ++j) {
        s.cg_x[j] += alpha * s.cg_p[j];
        s.cg_r[j] -= alpha * s.cg_q[j];
        rr += s.cg_r[j].squaredNorm();
      }
      apply_tree_inverse(s, c, s.cg_r, s.cg_z);
      for (size_t j = base; j < base + kJointCount; ++j) v += s.cg_r[j].dot(s.cg_z[j]);
      s.partial[static_cast<size_t>(c)] = rr;
      s.partial2[static_cast<size_t>(c)] = v;
    });
    out.r_norm2 = reduce(s.partial);
    const double rz_new = reduce(s.partial2);
    ++out.iterations;
    out.finite = std::isfinite(out.r_norm2) && std::isfinite(rz_new);
    beta = rz_new / rz;
    rz = rz_new;
  }
  return out;
}

/// Removes (stiffness 0) every contact whose linearised depth at s.cg_x is below -kPullTolerance and
/// marks the characters it touches; returns how many were removed.
int remove_pulling_contacts(CorrectorState& s, std::vector<char>& touched) {
  std::fill(touched.begin(), touched.end(), 0);
  int removed = 0;
  for (Contact& c : s.contacts) {  // serial: cheap, and the marks are shared between characters
    if (c.stiffness == 0.0) continue;
    double depth = c.depth0 + c.w_a.dot(s.cg_x[static_cast<size_t>(c.bone_a)]);
    if (c.bone_b >= 0) depth += c.w_b.dot(s.cg_x[static_cast<size_t>(c.bone_b)]);
    if (depth >= -kPullTolerance) continue;
    c.stiffness = 0.0;
    ++removed;
    touched[static_cast<size_t>(c.bone_a / kJointCount)] = 1;
    if (c.bone_b >= 0) touched[static_cast<size_t>(c.bone_b / kJointCount)] = 1;
  }
  return removed;
}

}  // namespace

void stage_solve(const CorrectorModel& model, CorrectorState& s) {
  const int n = model.characters();
  // Characters with contacts: refactorise with their contact blocks (the others keep stage_predict's).
  tbb::parallel_for(0, n, [&](int c) {
    char& ok = s.factor_ok[static_cast<size_t>(c)];
    if (!model.params.exact_prediction)
      ok = factor_character(s, c) ? 1 : 0;
    else if (s.has_contacts[static_cast<size_t>(c)])  // stage_predict's blocks where contacts add none
      ok = (ok ? refactor_character(s, c, s.contact_blocks[static_cast<size_t>(c)]) : factor_character(s, c))
               ? 1
               : 0;
  });
  // Warm start: the contact-free prediction where a character touches nothing (its exact answer), the
  // last step's motion h v_old where it does (contact-resolved, and smooth from step to step).
  tbb::parallel_for(0, n, [&](int c) {
    const size_t base = static_cast<size_t>(c) * kJointCount;
    const bool contact = s.has_contacts[static_cast<size_t>(c)] != 0 || !model.params.exact_prediction;
    for (size_t j = base; j < base + kJointCount; ++j) {
      if (!contact) {
        s.cg_x[j] = s.dq_free[j];
        continue;
      }
      s.cg_x[j].head<3>() = model.h * s.velocity_mps[j];
      s.cg_x[j].tail<3>() = model.h * s.omega_radps[j];
    }
  });
  CgResult cg = conjugate_gradients(model, s);
  int iterations = cg.iterations;
  std::vector<char>& touched = s.bad_character;  // scratch here; stage_integrate rewrites it
  for (int pass = 0; pass < model.params.active_set_passes && cg.finite; ++pass) {
    const int removed = remove_pulling_contacts(s, touched);
    if (removed == 0) break;
    s.stats.pulling_contacts += removed;
    ++s.stats.active_set_passes;
    tbb::parallel_for(0, n, [&](int c) {
      if (!touched[static_cast<size_t>(c)]) return;
      assemble_character_contacts(s, c);
      s.factor_ok[static_cast<size_t>(c)] = factor_character(s, c) ? 1 : 0;
    });
    cg = conjugate_gradients(model, s);
    iterations += cg.iterations;
  }
  const double tol2 = model.params.cg_tolerance * model.params.cg_tolerance * cg.b_norm2;
  bool factors_ok = true;
  for (char v : s.factor_ok) factors_ok = factors_ok && v != 0;
  s.stats.cg_iterations = iterations;
  s.stats.cg_relative_residual = cg.b_norm2 > 0.0 ? std::sqrt(cg.r_norm2 / cg.b_norm2) : 0.0;
  s.stats.converged = cg.finite && factors_ok && cg.r_norm2 <= tol2;
  if (!cg.finite || !factors_ok) s.stats.cg_relative_residual = INFINITY;
}

}  // namespace crowdlab
