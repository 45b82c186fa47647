// Solve H dq = b by preconditioned conjugate gradients (seed 000 §3.2: "we solve this linear system
// using conjugate gradient"), with a preconditioner that exploits each character's tree structure.
//
// H = T + C: T holds, per character, the inertia/joint/control blocks, which couple a bone only with
// its parent, so T is block tree-structured (24 nodes of 6 x 6); C holds the contact rank-1 terms
// k w w^T, which may couple any two bones (intra- and inter-body). The preconditioner is
// P = T + blockdiag(C), factorised EXACTLY per character (tree_factor.hpp, no fill-in on a tree).
//
// H is block diagonal over the connected groups of the contact graph (characters joined by contacts
// between two bones, of two characters or of one). A character in no such contact (none at all, or
// only ground and environment contacts, whose k w w^T lies in one bone's diagonal block) has H_c = P_c:
// it is solved EXACTLY by one tree solve, P_c^-1 b_c, and takes no part in CG (session 14; before, CG
// ran over every character to the global tolerance). Each group runs its own CG, to
// ||r_g|| <= cg_tolerance ||b_g||, so that ||r|| <= cg_tolerance ||b|| holds for the whole system too;
// a small group stops after its own few iterations instead of the crowd's worst. CG starts from the
// last step's motion h v_old (contact-resolved, and smooth from step to step).
//
// One CG iteration is three passes over a group's data (a pass over its contacts, then two over its
// characters), each split over contacts/characters (TBB) writing per-index slots; dot products are
// summed per character and then in character order, and the groups are disjoint, so results do not
// depend on the number of threads.
//
// Active set: E_collisions = 1/2 k max(0, delta)^2 is one-sided, but its linearisation is a full
// quadratic, which would pull apart surfaces back together when the solution separates them (a
// contact whose linearised depth ends below zero). Such "pulling" contacts are removed and the system
// re-solved from the current iterate (a primal active-set step, Nocedal & Wright 2006, §16.5), at most
// CorrectorParams::active_set_passes times.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <span>

#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/tree_factor.hpp"

namespace crowdlab {
namespace {

/// A contact pulls when its linearised depth at the solution is below -kPullTolerance (m): 0.1 mm,
/// far below anything visible, so that contacts resting exactly at the surface are kept.
constexpr double kPullTolerance = 1e-4;

/// The characters and contacts of one group (views into the state's CSR arrays).
struct Group {
  std::span<const int> characters, contacts;
};

Group group(const CorrectorState& s, size_t g) {
  const auto members = std::span<const int>(s.group_members);
  const auto contacts = std::span<const int>(s.group_contacts);
  const auto m0 = static_cast<size_t>(s.group_offset[g]), m1 = static_cast<size_t>(s.group_offset[g + 1]);
  const auto k0 = static_cast<size_t>(s.group_contact_offset[g]),
             k1 = static_cast<size_t>(s.group_contact_offset[g + 1]);
  return {members.subspan(m0, m1 - m0), contacts.subspan(k0, k1 - k0)};
}

/// Per contact of the group: k (w . (z + beta p)) for both sides, i.e. k w . p_new with
/// p_new = z + beta p computed on the fly (the character pass below then forms p_new itself), so no
/// separate update pass is needed.
void contact_pass(CorrectorState& s, std::span<const int> contacts, const std::vector<Vec6>& z,
                  const std::vector<Vec6>& p, double beta) {
  tbb::parallel_for(size_t{0}, contacts.size(), [&](size_t i) {
    const auto k = static_cast<size_t>(contacts[i]);
    const Contact& c = s.contacts[k];
    const auto a = static_cast<size_t>(c.bone_a);
    double v = c.w_a.dot(z[a] + beta * p[a]);
    if (c.bone_b >= 0) {
      const auto b = static_cast<size_t>(c.bone_b);
      v += c.w_b.dot(z[b] + beta * p[b]);
    }
    s.contact_scalar[k] = c.stiffness * v;
  });
}

/// y = H x for character c's rows; contact_scalar must hold k (w . x) for every contact of c's group.
void multiply_character(CorrectorState& s, int c, const std::vector<Vec6>& x, std::vector<Vec6>& y) {
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
    if (k.stiffness == 0.0) continue;  // removed by the active set: no term, and in no group's pass
    const double sk = s.contact_scalar[static_cast<size_t>(entry / 2)];
    if (entry & 1) {
      y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    } else {
      y[static_cast<size_t>(k.bone_a)] += sk * k.w_a;
      if (k.bone_b >= 0 && k.bone_b / kJointCount == c) y[static_cast<size_t>(k.bone_b)] += sk * k.w_b;
    }
  }
}

/// Fixed-order sum of the characters' partial sums.
double reduce(const std::vector<double>& partial, std::span<const int> characters) {
  double total = 0.0;
  for (int c : characters) total += partial[static_cast<size_t>(c)];
  return total;
}

/// PCG on the group's rows of H x = b from the current s.cg_x (the group's factorisations in
/// s.precond must be up to date), to ||r_g|| <= cg_tolerance ||b_g||.
CgGroupResult conjugate_gradients(const CorrectorModel& model, CorrectorState& s, const Group& g) {
  const CorrectorParams& p = model.params;
  const auto members = g.characters;
  const size_t n = members.size();
  CgGroupResult out;
  // r = b - H x0, z = P^-1 r, p = z.
  contact_pass(s, g.contacts, s.cg_x, s.cg_x, 0.0);  // k w . x0
  tbb::parallel_for(size_t{0}, n, [&](size_t i) {
    const int c = members[i];
    multiply_character(s, c, s.cg_x, s.cg_q);
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
  out.b_norm2 = reduce(s.partial, members);
  double rz = reduce(s.partial2, members);
  out.r_norm2 = reduce(s.partial3, members);
  const double tol2 = p.cg_tolerance * p.cg_tolerance * out.b_norm2;
  out.finite = std::isfinite(out.b_norm2) && std::isfinite(rz);
  double beta = 0.0;  // p = z + beta p, applied lazily by the next contact and character passes
  while (out.finite && out.r_norm2 > tol2 && out.iterations < p.cg_max_iterations) {
    // Pass 1 (contacts) and 2 (characters): p = z + beta p, q = H p, p . q.
    contact_pass(s, g.contacts, s.cg_z, s.cg_p, beta);
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const int c = members[i];
      const size_t base = static_cast<size_t>(c) * kJointCount;
      for (size_t j = base; j < base + kJointCount; ++j) s.cg_p[j] = s.cg_z[j] + beta * s.cg_p[j];
      multiply_character(s, c, s.cg_p, s.cg_q);
      double pq = 0.0;
      for (size_t j = base; j < base + kJointCount; ++j) pq += s.cg_p[j].dot(s.cg_q[j]);
      s.partial[static_cast<size_t>(c)] = pq;
    });
    const double pq = reduce(s.partial, members);
    if (!(pq > 0.0) || !std::isfinite(pq)) {
      out.finite = std::isfinite(pq);
      break;
    }
    const double alpha = rz / pq;
    // Pass 3 (characters): x += alpha p, r -= alpha q, z = P^-1 r, r . r, r . z.
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const int c = members[i];
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
    out.r_norm2 = reduce(s.partial, members);
    const double rz_new = reduce(s.partial2, members);
    ++out.iterations;
    out.finite = std::isfinite(out.r_norm2) && std::isfinite(rz_new);
    beta = rz_new / rz;
    rz = rz_new;
  }
  return out;
}

/// Union-find root of character c (path halving).
int find_root(std::vector<int>& parent, int c) {
  while (parent[static_cast<size_t>(c)] != c) {
    int& up = parent[static_cast<size_t>(c)];
    up = parent[static_cast<size_t>(up)];
    c = up;
  }
  return c;
}

/// TEMPORARY (session 14 measurement): CROWDLAB_SOLVE_GROUPS=all (one CG over every character, the old
/// solve), coupled (one CG over the coupled characters), else components.
int group_mode() {
  static const int mode = [] {
    const char* v = std::getenv("CROWDLAB_SOLVE_GROUPS");
    if (v && std::strcmp(v, "all") == 0) return 2;
    if (v && std::strcmp(v, "coupled") == 0) return 1;
    return 0;
  }();
  return mode;
}

/// The groups of this step's contact graph: characters joined by a contact between two bones (with
/// stiffness > 0) in one group, numbered by their smallest character; every character in no such
/// contact in exact_characters. Serial: a union-find over a few hundred contacts.
void build_groups(int n, CorrectorState& s) {
  const auto un = static_cast<size_t>(n);
  const int mode = group_mode();
  std::vector<int>& parent = s.group_parent;
  parent.assign(un, -1);  // -1: in no coupling contact
  auto join = [&](int a, int b) {
    if (parent[static_cast<size_t>(a)] < 0) parent[static_cast<size_t>(a)] = a;
    if (parent[static_cast<size_t>(b)] < 0) parent[static_cast<size_t>(b)] = b;
    const int ra = find_root(parent, a), rb = find_root(parent, b);
    parent[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);  // the smallest index is the root
  };
  for (const Contact& k : s.contacts)
    if (k.stiffness != 0.0 && k.bone_b >= 0) join(k.bone_a / kJointCount, k.bone_b / kJointCount);
  if (mode == 2)
    for (int c = 0; c < n; ++c) join(0, c);
  if (mode == 1) {
    int first = -1;
    for (int c = 0; c < n; ++c)
      if (parent[static_cast<size_t>(c)] >= 0) first = first < 0 ? c : (join(first, c), first);
  }
  // Group ids in order of their roots; roots precede their members, so one ascending pass numbers them.
  std::vector<int>& id = s.group_members;  // scratch: group id per character, rewritten below
  id.assign(un, -1);
  s.exact_characters.clear();
  int groups = 0;
  for (int c = 0; c < n; ++c) {
    if (parent[static_cast<size_t>(c)] < 0) {
      s.exact_characters.push_back(c);
      continue;
    }
    const int root = find_root(parent, c);
    id[static_cast<size_t>(c)] = root == c ? groups++ : id[static_cast<size_t>(root)];
  }
  for (size_t c = 0; c < un; ++c) parent[c] = id[c];  // from here: each character's group (-1: exact)
  // Counting sort of characters and contacts into their groups, ascending within each.
  s.group_offset.assign(static_cast<size_t>(groups) + 1, 0);
  s.group_contact_offset.assign(static_cast<size_t>(groups) + 1, 0);
  auto contact_group = [&](const Contact& k) {
    return k.stiffness == 0.0 ? -1 : parent[static_cast<size_t>(k.bone_a / kJointCount)];
  };
  for (size_t c = 0; c < un; ++c)
    if (parent[c] >= 0) ++s.group_offset[static_cast<size_t>(parent[c]) + 1];
  for (const Contact& k : s.contacts)
    if (const int g = contact_group(k); g >= 0) ++s.group_contact_offset[static_cast<size_t>(g) + 1];
  for (size_t g = 0; g < static_cast<size_t>(groups); ++g) {
    s.group_offset[g + 1] += s.group_offset[g];
    s.group_contact_offset[g + 1] += s.group_contact_offset[g];
  }
  s.group_members.assign(static_cast<size_t>(s.group_offset.back()), 0);
  s.group_contacts.assign(static_cast<size_t>(s.group_contact_offset.back()), 0);
  std::vector<int>& cursor = s.group_cursor;
  cursor.assign(s.group_offset.begin(), s.group_offset.end() - 1);
  for (size_t c = 0; c < un; ++c)
    if (parent[c] >= 0)
      s.group_members[static_cast<size_t>(cursor[static_cast<size_t>(parent[c])]++)] = static_cast<int>(c);
  cursor.assign(s.group_contact_offset.begin(), s.group_contact_offset.end() - 1);
  for (size_t k = 0; k < s.contacts.size(); ++k)
    if (const int g = contact_group(s.contacts[k]); g >= 0)
      s.group_contacts[static_cast<size_t>(cursor[static_cast<size_t>(g)]++)] = static_cast<int>(k);
  s.group_result.assign(static_cast<size_t>(groups), CgGroupResult{});
}

/// Solves every character outside the groups exactly: x_c = P_c^-1 b_c (the prediction dq_free where
/// the character has no contact at all and stage_predict's factorisation is this system's). Writes
/// |b_c|^2 to s.partial.
void solve_exact_characters(const CorrectorModel& model, CorrectorState& s) {
  tbb::parallel_for(size_t{0}, s.exact_characters.size(), [&](size_t i) {
    const int c = s.exact_characters[i];
    const size_t base = static_cast<size_t>(c) * kJointCount;
    if (model.params.exact_prediction && !s.has_contacts[static_cast<size_t>(c)])
      for (size_t j = base; j < base + kJointCount; ++j) s.cg_x[j] = s.dq_free[j];
    else
      apply_tree_inverse(s, c, s.rhs, s.cg_x);
    double bb = 0.0;
    for (size_t j = base; j < base + kJointCount; ++j) bb += s.rhs[j].squaredNorm();
    s.partial[static_cast<size_t>(c)] = bb;
  });
}

/// Groups, exact solves and one CG per group; the step's statistics from all of them. On the first
/// solve of a step the groups' CG starts from h v_old (dq_free for a member without contacts), on a
/// re-solve from the current iterate.
void solve_groups(const CorrectorModel& model, CorrectorState& s, bool warm_start, double& r_norm2,
                  double& b_norm2, bool& finite, bool& converged, int& iterations) {
  build_groups(model.characters(), s);
  if (warm_start)
    tbb::parallel_for(size_t{0}, s.group_members.size(), [&](size_t i) {
      const int c = s.group_members[i];
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
  solve_exact_characters(model, s);
  const double exact_b_norm2 = reduce(s.partial, s.exact_characters);
  tbb::parallel_for(size_t{0}, s.group_result.size(),
                    [&](size_t g) { s.group_result[g] = conjugate_gradients(model, s, group(s, g)); });
  const double tol = model.params.cg_tolerance;
  r_norm2 = 0.0;  // the exact characters' residuals are round-off
  b_norm2 = 0.0;
  finite = std::isfinite(exact_b_norm2);
  converged = true;
  int most = 0;
  for (const CgGroupResult& g : s.group_result) {
    r_norm2 += g.r_norm2;
    b_norm2 += g.b_norm2;
    finite = finite && g.finite;
    converged = converged && g.r_norm2 <= tol * tol * g.b_norm2;
    most = std::max(most, g.iterations);
  }
  b_norm2 += exact_b_norm2;
  iterations += most;
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
  s.contact_scalar.resize(s.contacts.size());
  double r_norm2 = 0.0, b_norm2 = 0.0;
  bool finite = true, converged = true;
  int iterations = 0;
  solve_groups(model, s, true, r_norm2, b_norm2, finite, converged, iterations);
  std::vector<char>& touched = s.bad_character;  // scratch here; stage_integrate rewrites it
  for (int pass = 0; pass < model.params.active_set_passes && finite; ++pass) {
    const int removed = remove_pulling_contacts(s, touched);
    if (removed == 0) break;
    s.stats.pulling_contacts += removed;
    ++s.stats.active_set_passes;
    tbb::parallel_for(0, n, [&](int c) {
      if (!touched[static_cast<size_t>(c)]) return;
      assemble_character_contacts(s, c);
      s.factor_ok[static_cast<size_t>(c)] = factor_character(s, c) ? 1 : 0;
    });
    solve_groups(model, s, false, r_norm2, b_norm2, finite, converged, iterations);
  }
  bool factors_ok = true;
  for (char v : s.factor_ok) factors_ok = factors_ok && v != 0;
  s.stats.cg_iterations = iterations;
  s.stats.cg_groups = static_cast<int>(s.group_result.size());
  s.stats.cg_characters = static_cast<int>(s.group_members.size());
  s.stats.cg_relative_residual = b_norm2 > 0.0 ? std::sqrt(r_norm2 / b_norm2) : 0.0;
  s.stats.converged = finite && factors_ok && converged;
  if (!finite || !factors_ok) s.stats.cg_relative_residual = INFINITY;
}

}  // namespace crowdlab
