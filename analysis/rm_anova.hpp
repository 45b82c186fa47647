#pragma once
// Univariate repeated-measures ANOVA for any number of within-subject factors, with Mauchly's test
// and Greenhouse-Geisser / Huynh-Feldt corrections, as R's car::Anova (summary, univariate) and
// afex::aov_ez report them.
//
// Formulation (Maxwell & Delaney 2004, ch. 11-12; O'Brien & Kaiser 1985): for effect E the
// contrast matrix over the cells is C_E = kron over factors f of (H_f if f in E else 1/sqrt(l_f)),
// H_f the l_f x (l_f-1) orthonormal Helmert contrasts. With Z = Y C_E (n x d, Y = subjects x cells):
//   SS_E = n |mean(Z)|^2,   S = sum_i (z_i - zbar)(z_i - zbar)^T  (error SSP),   SS_err = tr S,
//   df1 = d, df2 = d (n-1), F = (SS_E/df1) / (SS_err/df2).
// Effect sizes: partial eta^2 = SS_E / (SS_E + SS_err); generalised eta^2 for all-within designs
// (Olejnik & Algina 2003; Bakeman 2005) = SS_E / (SS_E + SS_subjects + sum of every effect's SS_err).
// Sphericity (d > 1): Sigma = S/(n-1); Mauchly's W = det(Sigma) / (tr(Sigma)/d)^d with the chi-square
// approximation and its second-order term (Anderson 1958, as R's mauchly.test):
//   rho = 1 - (2d^2+d+2)/(6d(n-1)), f = d(d+1)/2 - 1, z = -(n-1) rho log W,
//   w2 = (d+2)(d-1)(d-2)(2d^3+6d^2+3c+2) / (288 ((n-1) d rho)^2), c = number of cells (R's
//   mauchly.test.SSD uses the SSD's full dimension there, where Anderson has d; car and afex inherit it),
//   p = Q(z; f) + w2 (Q(z; f+4) - Q(z; f)),  Q the chi-square upper tail.
// GG epsilon = tr(S)^2 / (d tr(S^2)) (Greenhouse & Geisser 1959). HF epsilon with Lecoutre's (1991)
// correction as car: ((n-1+1) d eps_GG - 2) / (d (n-1 - d eps_GG)); reported raw (may exceed 1) and
// capped at 1 only for the corrected p. Tail probabilities from Boost.Math.
#include <optional>
#include <string>
#include <vector>

#include "analysis/within_design.hpp"

namespace crowdlab::analysis {

struct RmAnovaEffect {
  std::string name;             ///< factor names joined with ':': between factors first (afex's order)
  std::vector<size_t> factors;  ///< indices into WithinDesign::factors
  std::vector<size_t> between;  ///< indices into WithinDesign::between (mixed designs)
  double df1 = 0, df2 = 0;
  double ss = 0, ss_error = 0, ms = 0, ms_error = 0;
  double f = 0, p = 0;
  double pes = 0, ges = 0;
  // Present only when df1 > 1.
  std::optional<double> mauchly_w, mauchly_p, gg_eps, hf_eps, p_gg, p_hf;
};

struct RmAnovaResult {
  size_t subjects = 0;
  double ss_subjects = 0;              ///< between-subject SS (error of the intercept)
  std::vector<RmAnovaEffect> effects;  ///< main effects first, then 2-way, ... (R's term order); with
                                       ///< between factors, car/afex's order (see mixed_anova)
};

/// Runs the ANOVA on a design (see build_within_design). Mauchly's W and p are left empty when
/// n - 1 < df1 (the error covariance is singular); the epsilons are still reported, except a
/// Huynh-Feldt epsilon that is not positive (n - 1 <= d eps_GG), left empty with its p.
/// Throws InputError (naming the design's CSV and dv column) for fewer than 3 subjects, a constant dv,
/// or an effect with zero error variance (its F would be 0/0 or infinite).
RmAnovaResult rm_anova(const WithinDesign& design);

/// Mixed (split-plot) or between-subjects ANOVA of a design with between factors (mixed_anova.cpp);
/// rm_anova calls it for such designs. See the header comment of mixed_anova.cpp.
RmAnovaResult mixed_anova(const WithinDesign& design);

/// Every non-empty subset of {0..k-1}, ordered by size then lexicographically (R's term order).
std::vector<std::vector<size_t>> effect_subsets(size_t k);

/// Throws InputError (naming the design's CSV and dv) when ss_total is 0 (a constant dv) or the
/// effect's error SS is zero relative to it (F would be 0/0 or infinite).
void require_error_variance(const WithinDesign& design, const RmAnovaEffect& e, double ss_total);

/// Fills an effect's error SS, mean squares, F, p, pes and (d > 1) sphericity from its error SSP
/// matrix with `error_df` df; e.ss, df1 and df2 must be set. Throws as require_error_variance.
void complete_effect(const WithinDesign& design, RmAnovaEffect& e, const Eigen::MatrixXd& error_ssp,
                     double error_df, double ss_total);

/// Orthonormal Helmert-type contrasts: l x (l-1), columns orthonormal and orthogonal to 1.
Eigen::MatrixXd helmert_contrasts(size_t levels);

/// The cells x d contrast matrix of an effect (see header comment).
Eigen::MatrixXd effect_contrasts(const WithinDesign& design, const std::vector<size_t>& effect_factors);

}  // namespace crowdlab::analysis
