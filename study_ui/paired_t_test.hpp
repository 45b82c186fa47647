#pragma once
// paired_t_test: the minimal test `crowdlab power` needs, kept local to study_ui on purpose (the
// analysis/ stage has the full statistics; study_ui must not depend on it). Student's paired t-test
// on differences d_i (n >= 2): t = mean(d) / (sd(d) / sqrt(n)), df = n - 1, two-sided
// p = 2 * (1 - F_t(|t|; df)) with the t CDF from Boost.Math. Cohen's d_z = mean(d) / sd(d).
// A zero standard deviation gives p = 0 when mean != 0 and p = 1 when mean == 0.
#include <vector>

namespace crowdlab::study {

struct PairedTTest {
  double mean_difference = 0.0;
  double t = 0.0;
  double df = 0.0;
  double p_two_sided = 1.0;
  double cohens_dz = 0.0;
};

/// Throws InputError when fewer than 2 differences are given or any is not finite.
PairedTTest paired_t_test(const std::vector<double>& differences);

}  // namespace crowdlab::study
