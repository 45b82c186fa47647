// Post-hoc comparisons against R (tests/data/analysis/ref_posthoc_md_12.1.csv) and simple effects.
#include <catch2/catch.hpp>

#include "analysis/posthoc.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_posthoc {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;

TEST_CASE("analysis: paired-t Bonferroni and Tukey HSD agree with R on md_12.1", "[analysis]") {
  const auto design =
      build_within_design(read_csv(analysis_data("md_12.1.csv")), "rt", "id", {"angle", "noise"});
  const auto ref = read_csv(analysis_data("ref_posthoc_md_12.1.csv"));
  for (const std::string effect : {"angle", "angle:noise"}) {
    const auto factors = parse_effect(design, effect);
    const auto bonf = posthoc(design, factors, PosthocMethod::bonferroni);
    const auto tukey = posthoc(design, factors, PosthocMethod::tukey);
    size_t matched = 0;
    for (size_t r = 0; r < ref.rows.size(); ++r) {
      if (ref.cell(r, ref.column("effect")) != effect) continue;
      const auto& a = ref.cell(r, ref.column("level_a"));
      const auto& b = ref.cell(r, ref.column("level_b"));
      for (size_t i = 0; i < bonf.pairs.size(); ++i) {
        const auto& pb = bonf.pairs[i];
        const auto& pt = tukey.pairs[i];
        const bool same = pb.level_a == a && pb.level_b == b;
        const bool swapped = pb.level_a == b && pb.level_b == a;
        if (!same && !swapped) continue;
        INFO(effect << " " << a << " vs " << b);
        ++matched;
        CHECK(close_rel(std::abs(pb.statistic), std::abs(ref_number(ref, r, "t")), 1e-9));
        CHECK(close_rel(pb.p, ref_number(ref, r, "p_t"), 1e-8));
        CHECK(close_rel(pb.p_adjusted, ref_number(ref, r, "p_bonferroni"), 1e-8));
        CHECK(close_rel(pt.statistic, ref_number(ref, r, "q"), 1e-9));
        // R's ptukey is itself accurate to ~1e-7 relative at these df (see test_studentized_range.cpp).
        CHECK(std::abs(pt.p - ref_number(ref, r, "p_tukey")) <= 1e-6 * ref_number(ref, r, "p_tukey") + 1e-9);
      }
    }
    CHECK(matched == bonf.pairs.size());
  }
}

TEST_CASE("analysis: simple comparisons and simple effects", "[analysis]") {
  const auto design =
      build_within_design(read_csv(analysis_data("md_12.1.csv")), "rt", "id", {"angle", "noise"});
  const auto factors = parse_effect(design, "angle:noise");
  const auto simple = posthoc(design, factors, PosthocMethod::bonferroni, true);
  // 3 angle pairs within each of 2 noise levels + 3 noise pairs (one per angle) = 9 simple pairs.
  REQUIRE(simple.pairs.size() == 9);
  for (const auto& p : simple.pairs) CHECK(p.simple);
  const auto all = posthoc(design, factors, PosthocMethod::bonferroni, false);
  REQUIRE(all.pairs.size() == 15);
  // Same unadjusted p, smaller family: Bonferroni factor 9 instead of 15.
  for (const auto& p : simple.pairs)
    for (const auto& q : all.pairs)
      if (p.level_a == q.level_a && p.level_b == q.level_b) CHECK(p.p == Approx(q.p));
  // Simple effect of angle at each noise level equals a one-way ANOVA of that slice.
  const auto se = simple_effects(design, factors, 1);
  REQUIRE(se.size() == 2);
  CHECK(se[0].at == "noise=absent");
  CHECK(se[0].effect.name == "angle");
  CHECK(se[0].effect.df1 == 2);
  CHECK(se[0].effect.df2 == 18);
  CHECK_THROWS_AS(parse_effect(design, "angle:colour"), InputError);
  CHECK(significance_stars(0.0005) == "***");
  CHECK(significance_stars(0.005) == "**");
  CHECK(significance_stars(0.04) == "*");
  CHECK(significance_stars(0.2).empty());
}

}  // namespace test_posthoc
