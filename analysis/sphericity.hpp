#pragma once
// Sphericity of one repeated-measures effect from its error SSP matrix S (d x d, on orthonormal
// contrasts) with `error_df` residual degrees of freedom (n - 1 within subjects only; n - p with p
// between-subject parameters in a mixed design, as car::Anova's mlm):
// - Mauchly's W = det(Sigma) / (tr(Sigma)/d)^d, Sigma = S / error_df, with the chi-square
//   approximation and its second-order term (Anderson 1958; R's mauchly.test.SSD, which car and afex
//   use, has the number of cells where Anderson has d in one term: kept for agreement);
// - Greenhouse-Geisser epsilon tr(S)^2 / (d tr(S^2)) (Greenhouse & Geisser 1959);
// - Huynh-Feldt epsilon with Lecoutre's (1991) correction as car: ((df + 1) d eps_GG - 2) /
//   (d (df - d eps_GG)), reported raw (may exceed 1), capped at 1 for its p; left empty when not
//   positive (few subjects for many cells), and Mauchly's test when error_df < d (S singular).
#include <Eigen/Core>

#include "analysis/rm_anova.hpp"

namespace crowdlab::analysis {

/// Fills e.gg_eps, p_gg, hf_eps, p_hf, mauchly_w, mauchly_p from S (needs e.f, e.df1, e.df2; d > 1).
void apply_sphericity(RmAnovaEffect& e, const Eigen::MatrixXd& s, double error_df, double cells);

/// Upper tail of F(df1, df2) at f (1 for f <= 0).
double f_upper_tail(double f, double df1, double df2);

}  // namespace crowdlab::analysis
