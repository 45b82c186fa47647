#pragma once
// The tree-structured part T of the Newton matrix of one character and its exact factorisation
// (internal to the correction stages; see stage_solve.cpp for how it preconditions CG).
//
// T couples a bone only with its parent. The coupling block H[child, parent] of a soft ball joint
// with the Eq. 4 control term is not stored as a dense 6 x 6 matrix but by its structure:
//
//   H[c,p] = -k_J a_c^T a_p - c_R [0 0; 0 I3],   a_x = [I3, -[r_x]x]  (Jacobian of the joint point
//                                                 on bone x, r_x = joint point - COM of x, world)
//
// so a product costs two cross products (20 flops) and reads 8 numbers instead of 36; this keeps a
// character's working set (~15 kB) in cache and halves the memory traffic of a CG iteration.
// Gaussian elimination on a tree from the leaves to the root has no fill-in (Baraff 1996,
// "Linear-time dynamics using Lagrange multipliers"; Featherstone's articulated-body algorithm in
// matrix form): after factor_character, precond[g] holds S_g^-1, the inverse of bone g's eliminated
// block, and apply_tree_inverse solves T' z = r exactly (T' = T plus whatever was added to the blocks).
#include <array>
#include <vector>

#include "framework/core/joint_scope.hpp"
#include "framework/correction/corrector_state.hpp"

namespace crowdlab {

/// y = H[c,p] x_parent.
inline Vec6 coupling_times(const JointCoupling& k, const Vec6& x_parent) {
  const Vec3 u = x_parent.head<3>() - k.arm_parent.cross(x_parent.tail<3>());
  Vec6 y;
  y.head<3>() = -k.joint_k * u;
  y.tail<3>() = -k.joint_k * k.arm_child.cross(u) - k.rot_k * x_parent.tail<3>();
  return y;
}

/// y = H[c,p]^T x_child.
inline Vec6 coupling_transpose_times(const JointCoupling& k, const Vec6& x_child) {
  const Vec3 u = x_child.head<3>() - k.arm_child.cross(x_child.tail<3>());
  Vec6 y;
  y.head<3>() = -k.joint_k * u;
  y.tail<3>() = -k.joint_k * k.arm_parent.cross(u) - k.rot_k * x_child.tail<3>();
  return y;
}

/// The dense 6 x 6 block H[c,p] (used once per step by the factorisation).
Mat6 coupling_matrix(const JointCoupling& k);

/// Inverse of a symmetric positive definite 6 x 6 matrix by Cholesky. False if not SPD.
bool spd_inverse6(const Mat6& a, Mat6& inverse);

/// Factorises character c's blocks in place: on entry precond[g] holds the diagonal blocks to
/// factorise (tree diagonal, possibly plus contact blocks), on exit S_g^-1. False if a block is not
/// positive definite (cannot happen for valid parameters: every block contains M / h^2 > 0).
bool factor_character(CorrectorState& s, int c);

/// factor_character for stage_predict (blocks without contacts), which also saves every bone's S^-1
/// and parent update in s.tree_inverse and s.tree_update.
bool factor_tree_character(CorrectorState& s, int c);

/// factor_character after contact blocks were added to the bones in `contact_blocks`: a bone whose
/// subtree has none has the same S^-1 and parent update as in factor_tree_character, which are reused
/// (same values subtracted in the same order: the result is bit-identical to factor_character's). The
/// tree factorisation must be this step's and have succeeded.
bool refactor_character(CorrectorState& s, int c, BoneMask contact_blocks);

/// z = T'^-1 r for character c's 24 bones (block forward elimination, root solve, back substitution).
/// r and z may be the same vector.
void apply_tree_inverse(const CorrectorState& s, int c, const std::vector<Vec6>& r, std::vector<Vec6>& z);

}  // namespace crowdlab
