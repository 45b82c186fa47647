#pragma once
// Internal reliability of a pair of questions with opposite wording (seed 000 section 4.4.3: answers
// to negative questions are reverse-coded, 7 - Q, and checked against their positive pair before
// averaging).
#include <cstddef>
#include <vector>

namespace crowdlab::analysis {

struct PairReliability {
  double pearson_r = 0;       ///< Pearson correlation of the two items
  double cronbach_alpha = 0;  ///< k/(k-1) (1 - sum var_i / var_total), k = 2 (Cronbach 1951)
  std::size_t n = 0;
};

/// `a` and `b` are the paired (already reverse-coded) answers, same length >= 2.
/// Throws InputError on length mismatch or fewer than 2 pairs; r is NaN when an item is constant.
PairReliability pair_reliability(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace crowdlab::analysis
