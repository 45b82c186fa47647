#include "analysis/satterthwaite.hpp"

#include <Eigen/Eigenvalues>
#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>

namespace crowdlab::analysis {
namespace {
constexpr double kEigenTolerance = 1e-8;  // lmerTest's tol in as_lmerModLmerTest

// d f / d x_k at x, through t -> f(x + scale_k t e_k) at t = 0.
double partial(const VarparFunction& f, const std::vector<double>& x, size_t k,
               const std::vector<double>& scale) {
  auto along = [&](double t) {
    std::vector<double> y = x;
    y[k] = x[k] + scale[k] * t;
    return f(y);
  };
  return boost::math::differentiation::finite_difference_derivative(along, 0.0) / scale[k];
}

Eigen::MatrixXd hessian(const VarparFunction& f, const std::vector<double>& x,
                        const std::vector<double>& scale) {
  const auto m = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd h(m, m);
  for (Eigen::Index k = 0; k < m; ++k)
    for (Eigen::Index l = k; l < m; ++l) {
      const VarparFunction dk = [&](const std::vector<double>& y) {
        return partial(f, y, static_cast<size_t>(k), scale);
      };
      h(k, l) = h(l, k) = partial(dk, x, static_cast<size_t>(l), scale);
    }
  return h;
}
}  // namespace

SatterthwaiteResult satterthwaite_df(const VarparFunction& deviance, const VarparMatrixFunction& vcov_beta,
                                     const std::vector<double>& varpar,
                                     const std::vector<double>& step_scale) {
  SatterthwaiteResult out;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hessian(deviance, varpar, step_scale));
  const Eigen::VectorXd& values = eig.eigenvalues();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(values.size(), values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (values[i] > kEigenTolerance)
      a += 2.0 / values[i] * eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose();
    else if (values[i] < -kEigenTolerance) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "Satterthwaite df: the deviance Hessian has a negative eigenvalue %.1e",
                    values[i]);
      out.warnings.push_back(std::string(buf) + " (lmerTest: \"Model failed to converge\")");
    }
  }
  const Eigen::MatrixXd c = vcov_beta(varpar);
  for (Eigen::Index j = 0; j < c.rows(); ++j) {
    const VarparFunction v = [&](const std::vector<double>& y) { return vcov_beta(y)(j, j); };
    Eigen::VectorXd g(static_cast<Eigen::Index>(varpar.size()));
    for (size_t k = 0; k < varpar.size(); ++k)
      g[static_cast<Eigen::Index>(k)] = partial(v, varpar, k, step_scale);
    const double denominator = g.dot(a * g);
    out.df.push_back(denominator > 0 ? 2.0 * c(j, j) * c(j, j) / denominator : std::nan(""));
  }
  return out;
}

double t_test_p(double t, double df) {
  if (!(df > 0) || !std::isfinite(t)) return std::nan("");
  const boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(t)));
}

}  // namespace crowdlab::analysis
