// ptukey / qtukey against R on a grid of (p, nmeans, df) (tests/data/analysis/ref_qtukey.csv).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "analysis/studentized_range.hpp"
#include "tests/analysis/reference_table.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_studentized_range {

using namespace crowdlab;
using crowdlab::test::analysis_data;
using crowdlab::test::ref_number;

namespace {
// R documents qtukey as accurate to the 4th decimal, and its ptukey loses accuracy for df < 10 (for two
// means, P(Q < q) = P(|T_df| < q/sqrt 2) shows it). There the reference is q_integral: the defining
// double integral evaluated by R's integrate() and inverted by uniroot() (scripts/make_reference_stats.R).
void check_grid_rows(double df_wanted, bool upper_tail) {
  const auto ref = read_csv(analysis_data("ref_qtukey.csv"));
  REQUIRE(ref.rows.size() >= 100);
  const size_t stride = test::kSanitized ? 5 : 1;
  double worst = 0;
  size_t checked = 0;
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    const auto& df_text = ref.cell(r, ref.column("df"));
    const double df = df_text == "Inf" ? std::numeric_limits<double>::infinity() : ref_number(ref, r, "df");
    const double p = ref_number(ref, r, "p");
    if (df != df_wanted || (p >= 0.93) != upper_tail || (r % stride) != 0) continue;
    const int k = static_cast<int>(ref_number(ref, r, "nmeans"));
    const bool r_is_accurate = df >= 10;
    const double want = r_is_accurate ? ref_number(ref, r, "q") : ref_number(ref, r, "q_integral");
    const double got = analysis::qtukey(p, k, df);
    INFO("p=" << p << " k=" << k << " df=" << df << " R qtukey=" << ref_number(ref, r, "q"));
    CHECK(std::abs(got - want) <= 1e-5 * want);
    if (r_is_accurate) {
      // And ptukey at R's quantile reproduces R's ptukey there.
      CHECK(analysis::ptukey(want, k, df) == Approx(ref_number(ref, r, "ptukey_of_q")).epsilon(1e-7));
    } else {
      CHECK(std::abs(got - want) <= 1e-7 * want);
    }
    worst = std::max(worst, std::abs(got - want) / want);
    ++checked;
  }
  CHECK(checked > 0);
  WARN("df=" << df_wanted << (upper_tail ? ", p >= .93" : ", p < .93")
             << ": worst relative qtukey difference " << worst << " over " << checked << " points");
}
}  // namespace

TEST_CASE("analysis: qtukey on the R grid, df = 2, p < .93", "[analysis]") {
  check_grid_rows(2, false);
}
TEST_CASE("analysis: qtukey on the R grid, df = 2, p >= .93", "[analysis]") {
  check_grid_rows(2, true);
}
TEST_CASE("analysis: qtukey on the R grid, df = 5, p < .93", "[analysis]") {
  check_grid_rows(5, false);
}
TEST_CASE("analysis: qtukey on the R grid, df = 5, p >= .93", "[analysis]") {
  check_grid_rows(5, true);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 10, p < .93", "[analysis]") {
  check_grid_rows(10, false);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 10, p >= .93", "[analysis]") {
  check_grid_rows(10, true);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 30, p < .93", "[analysis]") {
  check_grid_rows(30, false);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 30, p >= .93", "[analysis]") {
  check_grid_rows(30, true);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 120, p < .93", "[analysis]") {
  check_grid_rows(120, false);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = 120, p >= .93", "[analysis]") {
  check_grid_rows(120, true);
}
TEST_CASE("analysis: qtukey matches R's qtukey to 1e-5, df = Inf", "[analysis]") {
  check_grid_rows(std::numeric_limits<double>::infinity(), false);
  check_grid_rows(std::numeric_limits<double>::infinity(), true);
}

TEST_CASE("analysis: ptukey analytic cases", "[analysis]") {
  // Two means, infinite df: the range of two N(0,1) is |N(0,2)|, so P(Q<q) = 2 Phi(q/sqrt2) - 1.
  for (double q : {0.1, 0.5, 1.0, 2.0, 3.5, 6.0}) {
    const double want = std::erf(q / 2.0);
    CHECK(analysis::ptukey(q, 2, std::numeric_limits<double>::infinity()) == Approx(want).epsilon(1e-10));
  }
  // Two means, nu df: Q = sqrt2 |T_nu|, so P(Q<q) = P(|T| < q/sqrt2); nu = 1: (2/pi) atan(q/sqrt2).
  for (double q : {0.3, 1.0, 4.0}) {
    CHECK(analysis::ptukey(q, 2, 1.0) == Approx(2.0 / M_PI * std::atan(q / std::sqrt(2.0))).epsilon(1e-8));
  }
  CHECK(analysis::ptukey(0.0, 3, 10) == 0.0);
  CHECK_THROWS(analysis::qtukey(1.5, 3, 10));
}

}  // namespace test_studentized_range
