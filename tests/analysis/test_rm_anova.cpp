// RM-ANOVA against R afex::aov_ez / car::Anova (tests/data/analysis/ref_anova_*.csv).
#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <optional>

#include "analysis/rm_anova.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_rm_anova {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;

namespace {
struct Case {
  std::string name, subject, dv;
  std::vector<std::string> within;
};
const std::vector<Case> kCases = {
    {"rm_anova2", "Subject", "Performance", {"Time", "Metric"}},
    {"ez_2x3x2", "id", "DV", {"A", "B", "D"}},
    {"md_12.1", "id", "rt", {"angle", "noise"}},
    // Simulated in scripts/make_reference_stats.R: df1 up to 12 (Mauchly's second-order term, epsilons).
    {"sim_5x4x2", "participant", "score", {"density", "viewpoint", "method"}},
};

void check_optional(const std::optional<double>& got, double want, const std::string& what) {
  INFO(what);
  if (std::isnan(want)) {
    CHECK_FALSE(got.has_value());
  } else {
    REQUIRE(got.has_value());
    CHECK(close_rel(*got, want, 1e-6));
  }
}

void check_against_reference(const RmAnovaResult& res, const Case& c) {
  const auto ref = read_csv(analysis_data("ref_anova_" + c.name + ".csv"));
  REQUIRE(res.effects.size() == ref.rows.size());
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    const auto& name = ref.cell(r, ref.column("effect"));
    const auto it =
        std::find_if(res.effects.begin(), res.effects.end(), [&](auto& e) { return e.name == name; });
    INFO(c.name << " effect " << name);
    REQUIRE(it != res.effects.end());
    CHECK(it->df1 == ref_number(ref, r, "df1"));
    CHECK(it->df2 == ref_number(ref, r, "df2"));
    CHECK(close_rel(it->ss, ref_number(ref, r, "SS"), 1e-9));
    CHECK(close_rel(it->ss_error, ref_number(ref, r, "SS_error"), 1e-9));
    CHECK(close_rel(it->f, ref_number(ref, r, "F"), 1e-6));
    CHECK(close_rel(it->p, ref_number(ref, r, "p"), 1e-6));
    CHECK(close_rel(it->pes, ref_number(ref, r, "pes"), 1e-6));
    CHECK(close_rel(it->ges, ref_number(ref, r, "ges"), 1e-6));
    check_optional(it->mauchly_w, ref_number(ref, r, "mauchly_W"), "W");
    check_optional(it->mauchly_p, ref_number(ref, r, "mauchly_p"), "W p");
    check_optional(it->gg_eps, ref_number(ref, r, "gg_eps"), "GG");
    check_optional(it->hf_eps, ref_number(ref, r, "hf_eps"), "HF");
    check_optional(it->p_gg, ref_number(ref, r, "p_gg"), "p GG");
    check_optional(it->p_hf, ref_number(ref, r, "p_hf"), "p HF");
  }
}
}  // namespace

TEST_CASE("analysis: rm_anova agrees with afex/car on three published data sets and a 5x4x2 design",
          "[analysis]") {
  for (const auto& c : kCases) {
    const auto table = read_csv(analysis_data(c.name + ".csv"));
    check_against_reference(rm_anova(build_within_design(table, c.dv, c.subject, c.within)), c);
  }
}

TEST_CASE("analysis: rm_anova is invariant to row order and to duplicated repetitions", "[analysis]") {
  const Case& c = kCases[1];
  auto table = read_csv(analysis_data(c.name + ".csv"));
  std::reverse(table.rows.begin(), table.rows.end());
  std::rotate(table.rows.begin(), table.rows.begin() + 37, table.rows.end());
  check_against_reference(rm_anova(build_within_design(table, c.dv, c.subject, c.within)), c);
  // Every row twice: the cell means (and so every statistic) are unchanged.
  auto doubled = table;
  doubled.rows.insert(doubled.rows.end(), table.rows.begin(), table.rows.end());
  doubled.line_numbers.insert(doubled.line_numbers.end(), table.line_numbers.begin(),
                              table.line_numbers.end());
  check_against_reference(rm_anova(build_within_design(doubled, c.dv, c.subject, c.within)), c);
}

TEST_CASE("analysis: helmert contrasts are orthonormal and orthogonal to the mean", "[analysis]") {
  for (size_t l = 2; l <= 9; ++l) {
    const auto h = helmert_contrasts(l);
    CHECK((h.transpose() * h - Eigen::MatrixXd::Identity(h.cols(), h.cols())).norm() < 1e-12);
    CHECK((h.transpose() * Eigen::VectorXd::Ones(h.rows())).norm() < 1e-12);
  }
}

TEST_CASE("analysis: effect sums of squares add up to the total within-subject variation", "[analysis]") {
  const auto table = read_csv(analysis_data("ez_2x3x2.csv"));
  const auto design = build_within_design(table, "DV", "id", {"A", "B", "D"});
  const auto res = rm_anova(design);
  double sum = res.ss_subjects;
  for (const auto& e : res.effects) sum += e.ss + e.ss_error;
  const Eigen::MatrixXd& y = design.cell_means;
  const double total = (y.array() - y.mean()).square().sum();
  CHECK(sum == Approx(total).epsilon(1e-12));
}

TEST_CASE("analysis: unbalanced or malformed tables name the subject, cell, row and column", "[analysis]") {
  const std::string header = "subj,A,B,y\n";
  std::string body;
  for (int s = 1; s <= 3; ++s)
    for (const char* a : {"a1", "a2"})
      for (const char* b : {"b1", "b2"})
        body += std::to_string(s) + "," + a + "," + b + ",1." + std::to_string(s) + "\n";
  const auto good = parse_csv(header + body, "t.csv");
  CHECK_NOTHROW(build_within_design(good, "y", "subj", {"A", "B"}));
  // Drop subject 2's (a2, b1) row.
  const auto missing_text = header + body.substr(0, body.find("2,a2,b1")) + body.substr(body.find("2,a2,b2"));
  try {
    build_within_design(parse_csv(missing_text, "t.csv"), "y", "subj", {"A", "B"});
    FAIL("expected InputError");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("'2'") != std::string::npos);
    CHECK(msg.find("A=a2, B=b1") != std::string::npos);
  }
  try {
    build_within_design(good, "y", "subj", {"A", "C"});
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("'C'") != std::string::npos);
  }
  auto bad = body;
  bad.replace(bad.find("1.2"), 3, "abc");
  try {
    build_within_design(parse_csv(header + bad, "t.csv"), "y", "subj", {"A", "B"});
    FAIL("expected InputError");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("t.csv:6") != std::string::npos);
    CHECK(msg.find("y") != std::string::npos);
  }
}

}  // namespace test_rm_anova
