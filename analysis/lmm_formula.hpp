#pragma once
// lme4's model formula, the subset crowdlab fits (Bates, Maechler, Bolker & Walker 2015, J. Stat.
// Softw. 67(1), section 2.1):  y ~ fixed + (random | group) + ...
//   fixed:  terms joined by '+': a variable `a`, an interaction `a:b`, a crossing `a*b` (= a + b + a:b,
//           also `a*b*c`), `1` (the intercept, implied) and `0` or `-1` (no intercept);
//   random: `(1 | g)`, `(1 + x | g)`, `(x | g)` (the intercept implied), `(0 + x | g)`; each bar term
//           has correlated effects within its group; several bar terms give crossed random effects.
// Not supported (an error naming the piece): `||`, nested `g1/g2`, functions such as log(x), offsets.
#include <cstddef>
#include <string>
#include <vector>

namespace crowdlab::analysis {

/// Most distinct variables one crossing `a*b*...` may hold: n make 2^n - 1 terms (10 make 1023), each a
/// block of design-matrix columns. Beyond it the formula is refused before expansion.
inline constexpr std::size_t kMaxCrossedVariables = 10;

/// A model term: the variables it multiplies, in the order written (empty = the intercept).
using ModelTerm = std::vector<std::string>;

struct RandomTerm {
  bool intercept = true;
  std::vector<ModelTerm> terms;  ///< slopes (and their interactions), intercept excluded
  std::string group;
};

struct LmmFormula {
  std::string response;
  bool intercept = true;
  std::vector<ModelTerm> fixed;  ///< R's order: by number of variables, then as written
  std::vector<RandomTerm> random;
};

/// Throws InputError naming the formula and the offending piece.
LmmFormula parse_lmm_formula(const std::string& formula);

/// Every variable name the formula text mentions (names followed by '(' are functions, left out), in
/// order of first mention; read without parsing, so that the columns can be checked before anything the
/// formula expands to is counted or built (issue 33: 24 crossed missing columns ran out of memory).
std::vector<std::string> formula_variable_names(const std::string& formula);

/// The terms of a right-hand side without bars ("a * b + c"), expanded and in R's order; sets
/// `intercept` false for 0 / -1.
std::vector<ModelTerm> parse_fixed_terms(const std::string& rhs, bool& intercept, const std::string& formula);

}  // namespace crowdlab::analysis
